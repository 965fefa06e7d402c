"""Planning: which sample ranges, frames and part files a render consists of (no Ray here)."""
from __future__ import annotations

import dataclasses
import os
import re


@dataclasses.dataclass(frozen=True)
class Frame:
    """One output image: a scene file and, optionally, a camera (glTF index or course camera id)."""
    scene: str
    camera: str | None = None

    def name(self) -> str:
        stem = os.path.splitext(os.path.basename(self.scene))[0] if self.scene else "cornell-box"
        return stem if self.camera is None else f"{stem}-cam{self.camera}"


@dataclasses.dataclass(frozen=True)
class Chunk:
    frame: Frame
    begin: int  # first sample index
    end: int    # one past the last

    def part_name(self) -> str:
        return f"{self.frame.name()}.part-{self.begin:010d}-{self.end:010d}.exr"


def split_samples(spp: int, chunks: int) -> list[tuple[int, int]]:
    """Contiguous ranges covering [0, spp), as equal as possible (sizes differ by at most 1)."""
    if spp < 1 or chunks < 1:
        raise ValueError("need spp >= 1 and chunks >= 1")
    chunks = min(chunks, spp)
    base, extra = divmod(spp, chunks)
    ranges, begin = [], 0
    for k in range(chunks):
        end = begin + base + (1 if k < extra else 0)
        ranges.append((begin, end))
        begin = end
    return ranges


def parse_cameras(text: str | None) -> list[str | None]:
    """'0-3,7' -> ['0', '1', '2', '3', '7']; None -> [None] (the scene's default camera)."""
    if not text:
        return [None]
    cameras: list[str | None] = []
    for item in text.split(","):
        match = re.fullmatch(r"\s*(\d+)\s*-\s*(\d+)\s*", item)
        if match:
            first, last = int(match.group(1)), int(match.group(2))
            if last < first:
                raise ValueError(f"camera range '{item}' runs backwards")
            cameras.extend(str(c) for c in range(first, last + 1))
        elif item.strip():
            cameras.append(item.strip())
    return cameras


def plan(scenes: list[str], cameras: list[str | None], spp: int, chunks: int) -> list[Chunk]:
    """Every chunk of every frame (scene x camera), frame by frame."""
    frames = [Frame(scene, camera) for scene in scenes for camera in cameras]
    return [Chunk(frame, a, b) for frame in frames for a, b in split_samples(spp, chunks)]


def pending(all_chunks: list[Chunk], parts_dir: str) -> list[Chunk]:
    """Chunks whose part file is not there yet (parts are written by rename, so present = whole)."""
    return [c for c in all_chunks if not os.path.isfile(os.path.join(parts_dir, c.part_name()))]
