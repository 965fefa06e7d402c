#!/usr/bin/env python3
"""pt against Mitsuba 3 at equal time, both measured in this run on this machine.

For each reference scene (tests/references/<scene>: glTF for pt, Mitsuba XML of the very same
triangles, and Mitsuba 3's reference image), Mitsuba renders a ladder of sample counts (warm:
scene load and kernel compile excluded, as a user's second render sees them) and pt renders for
each time budget (`pt render --time T`: its passes only, pipeline creation excluded), one right
after the other. Both are scored by relMSE against the same reference; Mitsuba's relMSE at each
budget is interpolated log-log between the two ladder rungs around it. Prints the machine's CPU
model and vector ISA, a Markdown table and, with --json, everything measured.

  python3 bench/bench_vs_mitsuba.py [--budgets 10,60] [--scenes cbox-diffuse,cbox-glass-mirror]
                                    [--pt build/pt] [--pt-args "--sampler sobol" ...] [--json OUT]
(--pt-args may be given several times: each is a pt configuration, all measured in the same run.)

Needs numpy and the OpenEXR module in the Python that runs it (Debian: python3-numpy; OpenEXR
from PyPI) and the Mitsuba venv made by scripts/setup_mitsuba_venv.sh (/opt/mitsuba, or
$PT_MITSUBA_PYTHON). relMSE = mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01).
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
REFERENCES = os.path.join(REPO, "tests", "references")
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"


def read_rgb(path):
    import numpy as np
    import OpenEXR
    with OpenEXR.File(path) as f:
        ch = f.channels()
        for key in ("RGBA", "RGB"):
            if key in ch:
                return np.asarray(ch[key].pixels, dtype=np.float64)[..., :3]
        return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)


def relmse(x, ref):
    import numpy as np
    return float(np.mean((x - ref) ** 2 / (ref ** 2 + 0.01)))


def machine():
    model, flags = "?", set()
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name") and model == "?":
                model = line.split(":", 1)[1].strip()
            elif line.startswith("flags") and not flags:
                flags = set(line.split(":", 1)[1].split())
    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE4" if "sse4_2" in flags else "?"
    return f"{os.cpu_count()} cores, {model}, {isa}"


def at_time(rows, t):
    """relMSE at `t` seconds, log-log between the rungs around it (extrapolated at the ends)."""
    pts = sorted((r["seconds"], r["relmse"]) for r in rows)
    i = next((k for k in range(len(pts) - 1) if pts[k][0] <= t <= pts[k + 1][0]), None)
    (t0, e0), (t1, e1) = pts[i:i + 2] if i is not None else (pts[:2] if t < pts[0][0] else pts[-2:])
    slope = (math.log(e1) - math.log(e0)) / (math.log(t1) - math.log(t0))
    return math.exp(math.log(e0) + slope * (math.log(t) - math.log(t0)))


def mitsuba_worker(scene_dir, spp_list):
    """Runs inside the Mitsuba venv: the ladder for one scene, as JSON on stdout."""
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)  # LLVM 15 cannot lower Dr.Jit's fminimum
    import numpy as np
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    ref = read_rgb(os.path.join(scene_dir, "reference.exr"))
    scene = mi.load_file(os.path.join(scene_dir, "mitsuba", "scene.xml"))
    np.array(mi.render(scene, spp=1, seed=12345))  # compile the kernel once: warm figures
    rows = []
    for k, spp in enumerate(spp_list):
        t0 = time.perf_counter()
        x = np.array(mi.render(scene, spp=spp, seed=100 + k), dtype=np.float64)[..., :3]  # waits for the render
        seconds = time.perf_counter() - t0
        rows.append(dict(spp=spp, seconds=seconds, relmse=relmse(x, ref),
                         mpaths=spp * x.shape[0] * x.shape[1] / seconds / 1e6))
    json.dump(dict(version=mi.__version__, rows=rows), sys.stdout)


def run_mitsuba(python, scene_dir, budgets):
    # Two short rungs measure the speed; then one render per budget at the sample count that
    # speed predicts, so that each budget has a rung at about its time (and the interpolation
    # between rungs only corrects the small miss).
    def ladder(spps):
        out = subprocess.run([python, os.path.abspath(__file__), "--mitsuba-worker", scene_dir,
                              ",".join(map(str, spps))], check=True, capture_output=True, text=True).stdout
        return json.loads(out)
    first = ladder([4, 16])
    per_second = first["rows"][-1]["spp"] / first["rows"][-1]["seconds"]
    rest = ladder(sorted({max(1, round(b * per_second)) for b in budgets}))
    return first["version"], first["rows"] + rest["rows"]


def run_pt(pt, extra, scene_dir, budget, work):
    log = os.path.join(work, "errors.csv")
    cmd = [pt, "render", os.path.join(scene_dir, "scene.gltf"), "--time", str(budget), "--reference",
           os.path.join(scene_dir, "reference.exr"), "--error-log", log, "-o", os.path.join(work, "pt.exr"), "-q"]
    subprocess.run(cmd + extra, check=True, capture_output=True)
    with open(log) as f:
        spp, seconds, rel = f.read().strip().splitlines()[-1].split(",")
    with open(os.path.join(scene_dir, "meta.json")) as f:
        meta = json.load(f)
    pixels = meta["width"] * meta["height"]
    return dict(spp=int(spp), seconds=float(seconds), relmse=float(rel),
                mpaths=int(spp) * pixels / float(seconds) / 1e6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--budgets", default="10,60")
    ap.add_argument("--scenes", default="cbox-diffuse,cbox-glass-mirror")
    ap.add_argument("--pt", default=os.path.join(REPO, "build", "pt"))
    ap.add_argument("--pt-args", action="append",
                    help="extra pt render arguments, e.g. '--sampler sobol'; repeat for several configurations "
                         "(default: one, pt's defaults)")
    ap.add_argument("--json")
    ap.add_argument("--mitsuba-worker", nargs=2, metavar=("SCENE_DIR", "SPP_LIST"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.mitsuba_worker:
        mitsuba_worker(a.mitsuba_worker[0], [int(n) for n in a.mitsuba_worker[1].split(",")])
        return
    python = os.environ.get("PT_MITSUBA_PYTHON", "/opt/mitsuba/bin/python")
    if not os.path.exists(python):
        sys.exit(f"bench_vs_mitsuba: {python} not found: run scripts/setup_mitsuba_venv.sh first")
    budgets = [float(b) for b in a.budgets.split(",")]
    configs = a.pt_args or [""]
    print(f"Machine: {machine()}")
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for name in a.scenes.split(","):
            scene_dir = os.path.join(REFERENCES, name)
            version, ladder = run_mitsuba(python, scene_dir, budgets)
            ours = {c: [run_pt(a.pt, shlex.split(c), scene_dir, b, work) for b in budgets] for c in configs}
            results[name] = dict(mitsuba_version=version, mitsuba=ladder, pt=ours)
            print(f"{name}: Mitsuba {version} ladder: " +
                  ", ".join(f"{r['spp']} spp {r['seconds']:.2f} s {r['mpaths']:.2f} M paths/s relMSE {r['relmse']:.4g}"
                            for r in ladder), flush=True)
    print()
    print("pt render against Mitsuba 3 `path` (llvm_ad_rgb), same machine, same run")
    print()
    print("| scene | pt settings | budget (s) | pt spp | pt M paths/s | pt relMSE | Mitsuba M paths/s | "
          "Mitsuba relMSE | ratio (pt / Mitsuba relMSE) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in results.items():
        rate = max(r["mitsuba"], key=lambda row: row["seconds"])["mpaths"]
        for config, rows in r["pt"].items():
            for ours in rows:
                theirs = at_time(r["mitsuba"], ours["seconds"])
                ours["mitsuba_relmse_at_time"] = theirs
                print(f"| {name} | {config or 'defaults'} | {ours['seconds']:.1f} | {ours['spp']} | "
                      f"{ours['mpaths']:.2f} | {ours['relmse']:.5f} | {rate:.2f} | {theirs:.5f} | "
                      f"{ours['relmse'] / theirs:.2f} |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(machine=machine(), results=results), f, indent=1)


if __name__ == "__main__":
    main()
