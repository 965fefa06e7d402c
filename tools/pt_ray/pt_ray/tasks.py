"""The Ray task: one chunk = one `pt render --samples A:B` on whichever node Ray picks."""
from __future__ import annotations

import os
import subprocess
import tempfile

import ray


class ChunkFailed(RuntimeError):
    """pt failed in a way worth retrying (device lost, out of memory, killed)."""


class BadCommand(RuntimeError):
    """pt rejected its command line or scene (exit status 2, or 1 before rendering): retrying is pointless."""


def render_command(pt: str, scene: str | None, camera: str | None, begin: int, end: int, output: str,
                   extra: list[str]) -> list[str]:
    cmd = [pt, "render"]
    if scene:
        cmd.append(scene)
    if camera is not None:
        cmd += ["--camera", camera]
    return cmd + ["--samples", f"{begin}:{end}", "-o", output, "-q"] + extra


# max_retries: Ray resubmits a task whose worker process or node died; retry_exceptions: and one
# that raised ChunkFailed. BadCommand is not retried.
@ray.remote(max_retries=3, retry_exceptions=[ChunkFailed])
def render_chunk(pt: str, scene: str | None, camera: str | None, begin: int, end: int, extra: list[str]) -> bytes:
    """Renders the chunk to a temporary file on the worker and returns the EXR's bytes (so the
    driver needs no shared filesystem for outputs; the scene must be at the same path on every node)."""
    with tempfile.TemporaryDirectory(prefix="pt_ray_") as tmp:
        output = os.path.join(tmp, "part.exr")
        proc = subprocess.run(render_command(pt, scene, camera, begin, end, output, extra),
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        last = (proc.stderr.strip().splitlines() or ["(no message)"])[-1]
        if proc.returncode == 2 or (proc.returncode == 1 and "pt: error:" in last and not os.path.exists(output)
                                    and "device" not in last and "memory" not in last):
            raise BadCommand(f"pt render --samples {begin}:{end}: {last}")
        if proc.returncode != 0:
            raise ChunkFailed(f"pt render --samples {begin}:{end} exited with {proc.returncode}: {last}")
        with open(output, "rb") as f:
            return f.read()
