"""python -m pt_ray render SCENE... --spp N --chunks K [--address ray://HOST:10001] [-o OUT.exr]"""
from __future__ import annotations

import argparse
import os
import shlex
import shutil
import sys

from .chunks import parse_cameras
from .driver import run


def default_pt() -> str:
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "..", "..", "..", "build", "pt"), shutil.which("pt") or ""):
        if candidate and os.path.isfile(candidate):
            return os.path.abspath(candidate)
    return "pt"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pt_ray", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("render", help="render sample-range chunks as Ray tasks and merge them")
    r.add_argument("scenes", nargs="*", help="scene files (several: one image each); none: the built-in Cornell box")
    r.add_argument("--spp", type=int, required=True, help="samples per pixel of each image")
    r.add_argument("--chunks", type=int, required=True, help="sample-range chunks per image (Ray tasks)")
    r.add_argument("--cameras", type=parse_cameras, default=[None],
                   help="frames: cameras to render, e.g. 0-3,7 (glTF indices or course camera ids)")
    r.add_argument("--address", help="Ray cluster: 'auto' on a cluster node, ray://HOST:10001 from outside "
                                     "(needs ray[client]); default: a local cluster on this machine")
    r.add_argument("-o", "--output", help="OUT.exr for one image, else a folder (default out)")
    r.add_argument("--parts-dir", help="where parts are kept (default OUT.parts); a re-run skips parts there")
    r.add_argument("--pt", default=default_pt(), help="pt binary, at the same path on every node")
    r.add_argument("--pt-args", type=shlex.split, default=[],
                   help="more pt render options, quoted: '--width 640 --height 480 --seed 3'")
    r.add_argument("--retries", type=int, default=2, help="resubmissions of a chunk after Ray's own 3 retries")
    r.add_argument("--cpus-per-chunk", type=float, default=1)
    r.add_argument("--gpus-per-chunk", type=float, default=0)
    r.add_argument("--num-cpus", type=int, default=None, help="CPUs of the local cluster (default: all)")
    options = parser.parse_args(argv)
    if options.spp < 1 or options.chunks < 1:
        parser.error("--spp and --chunks must be at least 1")
    for forbidden in ("--spp", "--samples", "--time", "-o", "--output", "--camera"):
        if forbidden in options.pt_args:
            parser.error(f"--pt-args must not contain {forbidden} (pt_ray sets it)")
    options.pt = os.path.abspath(options.pt) if os.path.sep in options.pt else options.pt
    return run(options)


if __name__ == "__main__":
    sys.exit(main())
