#!/usr/bin/env python3
"""Peak resident memory against triangle count: pt render and Mitsuba 3 on the same scenes.

For each triangle count, bench/make_mesh_scene.py writes the Cornell box with a displaced sphere
of that many triangles, as glTF for pt and as Mitsuba XML of the same triangles (cached in
$PT_BENCH_CACHE, default ~/.cache/pt-bench). Each renderer runs as a child process at 256x256,
4 spp, depth 8 (the issue's setting), and its peak resident set is read from the kernel when it
exits (ru_maxrss of os.wait4: the same measure for both, whatever they report themselves). pt's
own "peak memory" from its summary line is printed beside it. Mitsuba's figure includes its
Python interpreter and Dr.Jit's LLVM JIT, as a user's process would. Writes a Markdown table and
a log-log plot (PNG) of both.

  python3 bench/bench_peak_memory.py [--triangles 100000,300000,1000000,3000000] [--pt build/pt]
      [--mitsuba-python /opt/mitsuba/bin/python] [--plot OUT.png]

Mitsuba comes from scripts/setup_mitsuba_venv.sh; without it only pt is measured.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CACHE = os.environ.get("PT_BENCH_CACHE", os.path.join(os.path.expanduser("~"), ".cache", "pt-bench"))
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"

MITSUBA_CHILD = r"""
import os, sys
os.environ.setdefault("DRJIT_LIBLLVM_PATH", sys.argv[2])
import mitsuba as mi
mi.set_variant("llvm_ad_rgb")
scene = mi.load_file(sys.argv[1], max_depth=8)
import numpy as np
np.array(mi.render(scene, spp=4))
"""


def peak_of(cmd):
    """Runs cmd; returns (peak resident bytes from the kernel, stderr text)."""
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"bench_peak_memory: {cmd[0]} failed ({proc.returncode}):\n{err}")
    return usage.ru_maxrss * 1024, err


def scene_for(triangles):
    d = os.path.join(CACHE, f"mesh-memory-{triangles}")
    if not os.path.exists(os.path.join(d, "meta.json")):
        subprocess.run(["/usr/bin/python3", os.path.join(HERE, "make_mesh_scene.py"), d, "--triangles",
                        str(triangles), "--size", "256"], check=True, capture_output=True)
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--triangles", default="100000,300000,1000000,3000000")
    ap.add_argument("--pt", default=os.path.join(os.path.dirname(HERE), "build", "pt"))
    ap.add_argument("--mitsuba-python", default="/opt/mitsuba/bin/python")
    ap.add_argument("--plot", default="")
    args = ap.parse_args()
    counts = [int(t) for t in args.triangles.split(",")]
    with_mitsuba = os.path.exists(args.mitsuba_python)
    rows = []
    for n in counts:
        d = scene_for(n)
        pt_peak, err = peak_of([args.pt, "render", os.path.join(d, "scene.gltf"), "--spp", "4", "--max-depth", "8",
                                "--width", "256", "--height", "256", "-o", os.path.join(d, "pt.exr")])
        flat = re.search(r"(\d+) triangles", err)
        reported = re.search(r"peak memory ([0-9.]+ [kMG]B)", err)
        mi_peak = None
        if with_mitsuba:
            mi_peak, _ = peak_of([args.mitsuba_python, "-c", MITSUBA_CHILD, os.path.join(d, "mitsuba", "scene.xml"),
                                  LLVM19])
        rows.append(dict(triangles=int(flat.group(1)) if flat else n, pt=pt_peak,
                         reported=reported.group(1) if reported else "?", mitsuba=mi_peak))
        r = rows[-1]
        print(f"{r['triangles']} triangles: pt {r['pt'] / 1e6:.0f} MB (its own report: {r['reported']})" +
              (f", Mitsuba {mi_peak / 1e6:.0f} MB, ratio {pt_peak / mi_peak:.2f}" if mi_peak else ""), flush=True)

    print("\n| triangles | pt peak RSS (MB) | pt's summary line | bytes per triangle (pt, above the smallest) "
          "| Mitsuba 3 peak RSS (MB) | pt / Mitsuba |")
    print("|---|---|---|---|---|---|")
    base = rows[0]
    for r in rows:
        per = (r["pt"] - base["pt"]) / (r["triangles"] - base["triangles"]) if r is not base else float("nan")
        mi = f"{r['mitsuba'] / 1e6:.0f}" if r["mitsuba"] else "-"
        ratio = f"{r['pt'] / r['mitsuba']:.2f}" if r["mitsuba"] else "-"
        print(f"| {r['triangles']} | {r['pt'] / 1e6:.0f} | {r['reported']} | "
              f"{'-' if r is base else f'{per:.0f}'} | {mi} | {ratio} |")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.loglog([r["triangles"] for r in rows], [r["pt"] / 1e6 for r in rows], "o-", label="pt render")
        if with_mitsuba:
            ax.loglog([r["triangles"] for r in rows], [r["mitsuba"] / 1e6 for r in rows], "s-", label="Mitsuba 3 (llvm)")
        ax.set_xlabel("triangles")
        ax.set_ylabel("peak resident memory (MB)")
        ax.set_title("Peak RSS, 256x256, 4 spp, depth 8")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=100)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
