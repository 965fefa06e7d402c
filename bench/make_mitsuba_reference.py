#!/usr/bin/env python3
"""Renders a long Mitsuba 3 reference of a benchmark scene: SCENE_DIR/mitsuba/scene.xml in passes
of independent samples (a new seed each), until --minutes have passed, and writes

  OUT_DIR/reference.exr      the mean (linear RGB, float32)
  OUT_DIR/reference.var.exr  the variance of that mean per pixel and channel, from the spread of
                             the passes (each pass mean is one independent estimate)
  OUT_DIR/reference.json     spp, seeds, time, the machine, and ref_noise_relmse: the relMSE this
                             reference itself carries against the true image (the mean over
                             pixels and channels of var / (ref^2 + 0.01)), which adds to the
                             measured relMSE of anything scored against it

Why: the references in tests/references are 2048 spp; their own noise (relMSE 1.3e-4 in the
diffuse box) is half of what Mitsuba reaches in 60 s there, so equal-time ratios at 60 s
measured against them are pulled towards 1. An hour of Mitsuba brings that floor 30-50x lower.

Runs in the Mitsuba venv (scripts/setup_mitsuba_venv.sh):
  /opt/mitsuba/bin/python bench/make_mitsuba_reference.py SCENE_DIR OUT_DIR [--minutes 60]
      [--pass-spp 64] [--seed 2000000] [--extend]

--extend adds the new passes to the reference already in OUT_DIR (its mean and variance weighted
by sample counts; give a --seed whose passes do not overlap the seeds its json lists), so that a
reference can be made longer in several sittings.
"""
import argparse
import json
import os
import time

from bench_vs_mitsuba import read_rgb  # bench/bench_vs_mitsuba.py
from machine_info import machine  # bench/machine_info.py

LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"


def write_rgb(path, rgb):
    import numpy as np
    import OpenEXR
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    channels = {"RGB": np.ascontiguousarray(rgb.astype(np.float32))}
    with OpenEXR.File(header, channels) as f:
        f.write(path)


def mean_and_variance(total, total_squares, passes):
    """The mean of `passes` pass means (their sum and sum of squares given) and the variance of
    that mean: the unbiased variance of one pass mean over `passes`. Arrays or plain numbers."""
    mean = total / passes
    spread = total_squares / passes - mean * mean
    spread = (spread + abs(spread)) * 0.5  # rounding can take it below zero
    return mean, spread / (passes - 1)


def combine(mean_a, var_a, spp_a, mean_b, var_b, spp_b):
    """Two independent unbiased estimates of one image (means and variances of the means) as one,
    weighted by their samples: the weights' squares scale the variances."""
    w = spp_a / (spp_a + spp_b)
    return w * mean_a + (1.0 - w) * mean_b, w * w * var_a + (1.0 - w) ** 2 * var_b


def read_previous(out_dir, seed):
    """The reference already in out_dir: its mean, variance of the mean, spp and seed ranges."""
    with open(os.path.join(out_dir, "reference.json")) as f:
        info = json.load(f)
    seeds = info["seeds"]
    ranges = seeds if isinstance(seeds[0], list) else [seeds]
    if any(lo <= seed <= hi for lo, hi in ranges):
        raise SystemExit(f"{out_dir}: --seed {seed} repeats a pass of the reference there (seeds {ranges})")
    return dict(mean=read_rgb(os.path.join(out_dir, "reference.exr")),
                var=read_rgb(os.path.join(out_dir, "reference.var.exr")),
                spp=info["spp"], seeds=ranges, render_s=info["render_s"], info=info)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--minutes", type=float, default=60.0)
    ap.add_argument("--pass-spp", type=int, default=64)
    ap.add_argument("--seed", type=int, default=2000000, help="first pass's seed; pass k uses seed + k")
    ap.add_argument("--extend", action="store_true", help="add to the reference already in OUT_DIR")
    a = ap.parse_args()
    previous = read_previous(a.out_dir, a.seed) if a.extend else None
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)  # LLVM 15 cannot lower Dr.Jit's fminimum
    import numpy as np
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    xml = os.path.join(a.scene_dir, "mitsuba", "scene.xml")
    t_load = time.perf_counter()
    scene = mi.load_file(xml)
    load_s = time.perf_counter() - t_load

    total = None
    total_squares = None  # of the pass means, for the variance of the mean
    passes = 0
    start = time.perf_counter()
    while time.perf_counter() - start < a.minutes * 60.0 or passes < 2:
        x = np.array(mi.render(scene, spp=a.pass_spp, seed=a.seed + passes), dtype=np.float64)[..., :3]
        total = x if total is None else total + x
        total_squares = x * x if total_squares is None else total_squares + x * x
        passes += 1
        if passes % 16 == 0:
            print(f"{passes * a.pass_spp} spp, {time.perf_counter() - start:.0f} s", flush=True)
    render_s = time.perf_counter() - start
    mean, var_mean = mean_and_variance(total, total_squares, passes)
    spp = passes * a.pass_spp
    samples_per_s = round(spp * mean.shape[0] * mean.shape[1] / render_s)  # this sitting's
    seeds = [[a.seed, a.seed + passes - 1]]
    if previous:
        mean, var_mean = combine(previous["mean"], previous["var"], previous["spp"], mean, var_mean, spp)
        seeds = previous["seeds"] + seeds
        render_s += previous["render_s"]
        spp += previous["spp"]
    os.makedirs(a.out_dir, exist_ok=True)
    write_rgb(os.path.join(a.out_dir, "reference.exr"), mean)
    write_rgb(os.path.join(a.out_dir, "reference.var.exr"), var_mean)
    info = dict(scene=os.path.relpath(xml), variant="llvm_ad_rgb", mitsuba=mi.__version__, spp=spp,
                pass_spp=a.pass_spp, seeds=seeds, load_s=round(load_s, 3),
                render_s=round(render_s, 1), samples_per_s=samples_per_s,
                machine=machine(), date=time.strftime("%Y-%m-%d"),
                mean_rgb=mean.reshape(-1, 3).mean(0).tolist(),
                ref_noise_relmse=float(np.mean(var_mean / (mean * mean + 0.01))),
                ref_noise_note="expected relMSE of this reference vs the true image (mean var_of_mean/(ref^2+0.01))",
                command="/opt/mitsuba/bin/python bench/make_mitsuba_reference.py %s %s --minutes %g --pass-spp %d "
                        "--seed %d%s" % (a.scene_dir, a.out_dir, a.minutes, a.pass_spp, a.seed,
                                         " --extend" if previous else ""))
    if previous:
        info["extends"] = previous["info"]
    with open(os.path.join(a.out_dir, "reference.json"), "w") as f:
        json.dump(info, f, indent=1)
    print(f"{a.out_dir}: {spp} spp in {render_s:.0f} s, noise relMSE {info['ref_noise_relmse']:.3g}")


if __name__ == "__main__":
    main()
