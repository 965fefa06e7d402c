"""Submits the chunks, shows progress, retries failures, writes parts, merges each frame."""
from __future__ import annotations

import os
import subprocess
import sys
import time

import ray

from .chunks import Chunk, Frame, pending, plan
from .tasks import BadCommand, render_chunk

EXR_MAGIC = b"\x76\x2f\x31\x01"


def log(message: str) -> None:
    print(f"pt_ray: {message}", file=sys.stderr, flush=True)


def write_atomically(path: str, data: bytes) -> None:
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def submit(chunk: Chunk, options) -> ray.ObjectRef:
    task = render_chunk.options(num_cpus=options.cpus_per_chunk, num_gpus=options.gpus_per_chunk)
    return task.remote(options.pt, chunk.frame.scene or None, chunk.frame.camera, chunk.begin, chunk.end,
                       options.pt_args)


def render_chunks(todo: list[Chunk], parts_dir: str, options) -> None:
    """Runs every chunk to a part file; a chunk that still fails after Ray's own retries is
    resubmitted up to options.retries more times (a lost node, a flaky device)."""
    start = time.monotonic()
    attempts: dict[Chunk, int] = {}
    running = {submit(c, options): c for c in todo}
    done = 0
    while running:
        ready, _ = ray.wait(list(running), num_returns=1)
        ref = ready[0]
        chunk = running.pop(ref)
        try:
            data = ray.get(ref)
            if data[:4] != EXR_MAGIC:
                raise RuntimeError("the part is not an OpenEXR file")
        except BadCommand as e:
            raise SystemExit(f"pt_ray: error: {e}")
        except Exception as e:  # task errors, lost workers and nodes: all ray.exceptions.RayError
            attempts[chunk] = attempts.get(chunk, 0) + 1
            cause = str(e).strip().splitlines()[-1] if str(e).strip() else type(e).__name__
            if attempts[chunk] > options.retries:
                raise SystemExit(f"pt_ray: error: {chunk.part_name()} failed {attempts[chunk]} times; last: {cause}")
            log(f"{chunk.part_name()} failed ({cause}); resubmitting (attempt {attempts[chunk] + 1})")
            running[submit(chunk, options)] = chunk
            continue
        write_atomically(os.path.join(parts_dir, chunk.part_name()), data)
        done += 1
        elapsed = time.monotonic() - start
        eta = elapsed / done * (len(todo) - done)
        log(f"{done}/{len(todo)} chunks done ({100 * done // len(todo)}%), {elapsed:.1f} s, ETA {eta:.0f} s")


def merge(frame: Frame, parts: list[str], output: str, pt: str) -> None:
    proc = subprocess.run([pt, "merge", *parts, "-o", output], stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["(no message)"])[-1]
        raise SystemExit(f"pt_ray: error: merging {frame.name()}: {last}")
    log(proc.stderr.strip().splitlines()[-1].removeprefix("pt: "))


def outputs_for(frames: list[Frame], output: str | None) -> dict[Frame, str]:
    """One frame: OUTPUT (default out/<frame>.exr). Several: OUTPUT is a folder (default out)."""
    if len(frames) == 1 and output and output.endswith(".exr"):
        return {frames[0]: output}
    folder = output or "out"
    return {f: os.path.join(folder, f.name() + ".exr") for f in frames}


def run(options) -> int:
    scenes = [os.path.abspath(s) for s in options.scenes] or [""]
    chunks = plan(scenes, options.cameras, options.spp, options.chunks)
    frames = list(dict.fromkeys(c.frame for c in chunks))
    outputs = outputs_for(frames, options.output)
    first_output = next(iter(outputs.values()))
    parts_dir = options.parts_dir or os.path.splitext(first_output)[0] + ".parts"
    os.makedirs(parts_dir, exist_ok=True)
    for path in outputs.values():
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    todo = pending(chunks, parts_dir)
    log(f"{len(frames)} frame(s), {len(chunks)} chunks of about {options.spp // max(1, options.chunks)} spp; "
        f"{len(chunks) - len(todo)} already rendered in {parts_dir}")
    if todo:
        if options.address:
            ray.init(address=options.address, logging_level="WARNING")
        else:  # a local cluster on this machine
            ray.init(num_cpus=options.num_cpus, include_dashboard=False, logging_level="WARNING")
        try:
            render_chunks(todo, parts_dir, options)
        finally:
            ray.shutdown()
    for frame in frames:
        parts = [os.path.join(parts_dir, c.part_name()) for c in chunks if c.frame == frame]
        merge(frame, parts, outputs[frame], options.pt)
    return 0
