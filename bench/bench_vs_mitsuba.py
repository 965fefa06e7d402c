#!/usr/bin/env python3
"""pt against Mitsuba 3 at equal time, both measured in this run on this machine.

For each scene (a folder with scene.gltf for pt, mitsuba/scene.xml of the very same triangles,
and meta.json with the image size), each budget and each repeat, Mitsuba renders the sample count
its measured speed predicts for the budget (warm: scene load and kernel compile excluded, as a
user's second render sees them) and pt renders for the budget (`pt render --time T`: its passes
only, pipeline creation excluded), one right after the other. Pairing them keeps the ratio
honest while the machine's speed drifts (a shared host here changed speed by 30% within minutes).
Both are scored by relMSE against the same reference, Mitsuba's brought to pt's exact time by
relMSE ~ 1/t (unbiased Monte Carlo). The ratio printed is the median over the repeats. Mitsuba
runs at its own defaults but for the scene: Russian roulette from depth 5 (`--mitsuba-rr-depth`;
the XML files say 1000, no roulette, as their references were rendered; without roulette Mitsuba
needed 1.6x the time for the same error on the 1 M-triangle mesh, so the ratios printed before
2026-12-07 flattered pt by up to that much).

Scenes: cbox-diffuse and cbox-glass-mirror (tests/references); cbox-bumpy-sphere (the box with a
1 M-triangle sphere, bench/make_mesh_scene.py, 128x128) and cbox-rough (rough gold, rough glass, a
textured floor: bench/make_rough_scene.py --mitsuba), both written into $PT_BENCH_CACHE (default
~/.cache/pt-bench) when missing; ajar (scenes/ajar: two rooms lit through a door ajar,
bench/make_ajar_scene.py) and ajar-daylight (the same lit by a sky through the far room's open
end), where pt's `auto` takes bidirectional path tracing. The reference is bench/references/<scene>/reference.exr where
there is one (20 minutes of Mitsuba, bench/make_mitsuba_reference.py: noise relMSE 30-50x below
the 2048-spp references of tests/references, which would otherwise pull the 60-s ratios towards
1), else the scene folder's. Each reference's own noise (ref_noise_relmse, the expected relMSE of
the reference against the true image) adds to both renderers' measured relMSE; the last column
gives the ratio with it taken out of both.

  /opt/mitsuba/bin/python bench/bench_vs_mitsuba.py [--budgets 10,60] [--repeats 2]
      [--scenes cbox-diffuse,cbox-glass-mirror,cbox-bumpy-sphere,cbox-rough] [--pt build/pt]
      [--pt-args "--sampler independent" ...] [--json OUT]
(--pt-args may be given several times: each is a pt configuration, all measured in the same run.)

Runs in the Mitsuba venv made by scripts/setup_mitsuba_venv.sh (numpy, OpenEXR and Mitsuba 3.9.1;
$PT_MITSUBA_PYTHON overrides the interpreter for the Mitsuba worker). Prints the machine's CPU
model and vector ISA and a Markdown table. relMSE = mean over pixels and channels of
(x - ref)^2 / (ref^2 + 0.01).
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

from machine_info import machine  # bench/machine_info.py

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
REFERENCES = os.path.join(REPO, "tests", "references")
LONG_REFERENCES = os.path.join(HERE, "references")
CACHE = os.environ.get("PT_BENCH_CACHE", os.path.join(os.path.expanduser("~"), ".cache", "pt-bench"))
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


# Our own scenes, generated where missing: (folder in the cache, the command's arguments).
GENERATED = {
    "cbox-bumpy-sphere": ("mesh-mitsuba", ["make_mesh_scene.py", "--triangles", "1000000", "--size", "128"]),
    "cbox-rough": ("rough-mitsuba", ["make_rough_scene.py", "--mitsuba"]),
}


# Our own scenes kept in the repository (scenes/NAME): the two rooms lit through a door ajar, by
# a lamp in the far room or by the sky its open end looks onto (`make_ajar_scene.py --sky`).
OWN = {name: os.path.join(REPO, "scenes", name) for name in ("ajar", "ajar-daylight")}


def scene_dir(name):
    """The folder of a scene, made first where it is one of ours that is generated."""
    if name in OWN:
        return OWN[name]
    if name not in GENERATED:
        return os.path.join(REFERENCES, name)
    folder, command = GENERATED[name]
    d = os.path.join(CACHE, folder)
    if not os.path.exists(os.path.join(d, "meta.json")):
        subprocess.run(["/usr/bin/python3", os.path.join(HERE, command[0]), d] + command[1:], check=True,
                       capture_output=True)
    return d


def reference_of(name, directory):
    """(reference.exr, its noise relMSE or None): the long reference where there is one."""
    for d in (os.path.join(LONG_REFERENCES, name), directory):
        path = os.path.join(d, "reference.exr")
        if os.path.exists(path):
            info = os.path.join(d, "reference.json")
            noise = json.load(open(info)).get("ref_noise_relmse") if os.path.exists(info) else None
            return path, noise
    sys.exit(f"bench_vs_mitsuba: no reference for {name}")


def mitsuba_worker(xml, reference, spp_list, seed, rr_depth):
    """Runs as a child process: renders `xml` at each sample count, as JSON on stdout, with
    Russian roulette from `rr_depth` (every scene's XML takes it as a parameter)."""
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)  # LLVM 15 cannot lower Dr.Jit's fminimum
    import numpy as np
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    ref = read_rgb(reference)
    scene = mi.load_file(xml, rr_depth=rr_depth)
    np.array(mi.render(scene, spp=1, seed=12345))  # compile the kernel once: warm figures
    rows = []
    for k, spp in enumerate(spp_list):
        t0 = time.perf_counter()
        x = np.array(mi.render(scene, spp=spp, seed=seed + k), dtype=np.float64)[..., :3]  # waits for the render
        seconds = time.perf_counter() - t0
        rows.append(dict(spp=spp, seconds=seconds, relmse=relmse(x, ref),
                         mpaths=spp * x.shape[0] * x.shape[1] / seconds / 1e6))
    json.dump(dict(version=mi.__version__, rows=rows), sys.stdout)


def run_mitsuba(python, directory, reference, spp_list, seed, rr_depth):
    out = subprocess.run([python, os.path.abspath(__file__), "--mitsuba-worker",
                          os.path.join(directory, "mitsuba", "scene.xml"), reference,
                          ",".join(map(str, spp_list)), str(seed), str(rr_depth)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def run_pt(pt, extra, directory, reference, meta, budget, seed, work):
    log = os.path.join(work, "errors.csv")
    cmd = [pt, "render", os.path.join(directory, "scene.gltf"), "--time", str(budget), "--reference", reference,
           "--error-log", log, "-o", os.path.join(work, "pt.exr"), "-q", "--width", str(meta["width"]),
           "--height", str(meta["height"]), "--seed", str(seed)]
    if "sky_radiance" in meta:  # glTF has no environment: pt takes the sky from its command line
        cmd += ["--env-colour"] + [str(meta["sky_radiance"])] * 3
    subprocess.run(cmd + extra, check=True, capture_output=True)
    with open(log) as f:
        spp, seconds, rel = f.read().strip().splitlines()[-1].split(",")
    pixels = meta["width"] * meta["height"]
    return dict(spp=int(spp), seconds=float(seconds), relmse=float(rel),
                mpaths=int(spp) * pixels / float(seconds) / 1e6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--budgets", default="10,60")
    ap.add_argument("--repeats", type=int, default=2, help="pairs per scene and budget (the median ratio is printed)")
    ap.add_argument("--scenes", default="cbox-diffuse,cbox-glass-mirror,cbox-bumpy-sphere,cbox-rough")
    ap.add_argument("--pt", default=os.path.join(REPO, "build", "pt"))
    ap.add_argument("--pt-args", action="append",
                    help="extra pt render arguments, e.g. '--sampler independent'; repeat for several "
                         "configurations (default: one, pt's defaults)")
    ap.add_argument("--mitsuba-rr-depth", type=int, default=5,
                    help="Mitsuba's Russian roulette from this depth (default 5, Mitsuba's own default; the "
                         "scenes' XML files say 1000, no roulette, which their references were rendered with)")
    ap.add_argument("--json")
    ap.add_argument("--mitsuba-worker", nargs=5, metavar=("XML", "REFERENCE", "SPP_LIST", "SEED", "RR_DEPTH"),
                    help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.mitsuba_worker:
        xml, reference, spps, seed, rr_depth = a.mitsuba_worker
        mitsuba_worker(xml, reference, [int(n) for n in spps.split(",")], int(seed), int(rr_depth))
        return
    python = os.environ.get("PT_MITSUBA_PYTHON", "/opt/mitsuba/bin/python")
    if not os.path.exists(python):
        sys.exit(f"bench_vs_mitsuba: {python} not found: run scripts/setup_mitsuba_venv.sh first")
    budgets = [float(b) for b in a.budgets.split(",")]
    configs = a.pt_args or [""]
    print(f"Machine: {machine()}")
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name in a.scenes.split(","):
            directory = scene_dir(name)
            meta = json.load(open(os.path.join(directory, "meta.json")))
            reference, noise = reference_of(name, directory)
            probe = run_mitsuba(python, directory, reference, [4, 16], 100, a.mitsuba_rr_depth)
            version = probe["version"]
            per_second = probe["rows"][-1]["spp"] / probe["rows"][-1]["seconds"]
            noise_text = "?" if noise is None else "%.2g" % noise
            print(f"{name}: reference {os.path.relpath(reference, REPO)} (its noise relMSE {noise_text}); "
                  f"Mitsuba {version} at {per_second:.1f} spp/s", flush=True)
            for repeat in range(a.repeats):
                for budget in budgets:
                    spp = max(1, round(budget * per_second))
                    theirs = run_mitsuba(python, directory, reference, [spp], 1000 * (repeat + 1),
                                         a.mitsuba_rr_depth)["rows"][0]
                    per_second = theirs["spp"] / theirs["seconds"]  # follows the machine's drift
                    for config in configs:
                        ours = run_pt(a.pt, shlex.split(config), directory, reference, meta, budget, repeat, work)
                        # Mitsuba's relMSE at pt's exact time (relMSE ~ 1/t).
                        at_time = theirs["relmse"] * theirs["seconds"] / ours["seconds"]
                        row = dict(scene=name, config=config or "defaults", budget=budget, repeat=repeat,
                                   pt=ours, mitsuba=theirs, mitsuba_relmse_at_pt_time=at_time,
                                   ratio=ours["relmse"] / at_time, reference_noise=noise)
                        if noise is not None:
                            # Both errors include the reference's own noise (x and the reference are
                            # independent): without it, the ratio of the errors against the true image.
                            row["ratio_noise_removed"] = max(ours["relmse"] - noise, 0.0) / max(at_time - noise, 1e-30)
                        rows.append(row)
                        print(f"  {name} {row['config']} {budget:g} s #{repeat}: pt {ours['spp']} spp "
                              f"{ours['mpaths']:.2f} M paths/s relMSE {ours['relmse']:.4g} | Mitsuba {theirs['spp']} "
                              f"spp {theirs['seconds']:.1f} s {theirs['mpaths']:.2f} M paths/s relMSE "
                              f"{theirs['relmse']:.4g} | ratio {row['ratio']:.2f}", flush=True)
    print()
    print(f"pt render against Mitsuba 3 `path` (llvm_ad_rgb, rr_depth {a.mitsuba_rr_depth}), same machine, "
          f"paired runs ({machine()})")
    print()
    print("| scene | pt settings | budget (s) | pt M paths/s | pt relMSE | Mitsuba M paths/s | Mitsuba relMSE "
          "| ratio (pt / Mitsuba relMSE), median | each pair | reference noise | ratio without it |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    keys = []
    for r in rows:
        if (r["scene"], r["config"], r["budget"]) not in keys:
            keys.append((r["scene"], r["config"], r["budget"]))
    for scene, config, budget in keys:
        group = [r for r in rows if (r["scene"], r["config"], r["budget"]) == (scene, config, budget)]
        med = lambda f: statistics.median(f(r) for r in group)
        noise = group[0]["reference_noise"]
        pairs = ", ".join("%.2f" % r["ratio"] for r in group)
        noise_text = "?" if noise is None else "%.1g" % noise
        without = "?" if noise is None else "%.2f" % med(lambda r: r["ratio_noise_removed"])
        print(f"| {scene} | {config} | {budget:g} | {med(lambda r: r['pt']['mpaths']):.2f} | "
              f"{med(lambda r: r['pt']['relmse']):.3g} | {med(lambda r: r['mitsuba']['mpaths']):.2f} | "
              f"{med(lambda r: r['mitsuba_relmse_at_pt_time']):.3g} | **{med(lambda r: r['ratio']):.2f}** | "
              f"{pairs} | {noise_text} | {without} |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(machine=machine(), rows=rows), f, indent=1)


if __name__ == "__main__":
    main()
