#!/usr/bin/env bash
# GPU figures for bench/RESULTS.md: the built-in Cornell box and the glass box at 1920x1080
# (spp/s and M paths/s, specialised kernel against --all-features), then speed against error
# on the two Mitsuba reference scenes (256x256, relMSE against their references).
#
#   bash bench/bench_gpu.sh [DEVICE-SUBSTRING]   (default: pt's choice, a discrete GPU first; needs build/pt)
#
# Every speed figure comes with an error figure: the 1080p renders print the estimated relMSE
# (no reference exists at that size), the bench runs the true relMSE against the reference.
set -euo pipefail
cd "$(dirname "$0")/.."
pt=./build/pt
device=()
[ $# -gt 0 ] && device=(--device "$1")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$pt" devices
glass=tests/references/cbox-glass-mirror
echo "== 1920x1080, 10 s each (spp / 10 = spp/s)"
"$pt" render "${device[@]}" --width 1920 --height 1080 --time 10 -q -o "$out/cbox.exr"
"$pt" render "${device[@]}" --width 1920 --height 1080 --time 10 -q --all-features -o "$out/cbox-all.exr"
"$pt" render "${device[@]}" "$glass/scene.gltf" --width 1920 --height 1080 --time 10 -q -o "$out/glass.exr"
for s in cbox-diffuse cbox-glass-mirror; do
  r=tests/references/$s
  echo "== $s, 256x256, relMSE against the Mitsuba reference"
  "$pt" bench "${device[@]}" "$r/scene.gltf" --reference "$r/reference.exr" --budgets 1,10,60 --configs nee+is+rr \
    --no-plot -o "$out/bench-$s" | grep "bench:"
  "$pt" bench "${device[@]}" "$r/scene.gltf" --reference "$r/reference.exr" --budgets 1,10 --configs nee+is+rr+sobol \
    --no-plot -o "$out/bench-sobol-$s" | grep "bench:"
  "$pt" render "${device[@]}" "$r/scene.gltf" --time 0.5 --reference "$r/reference.exr" --error-log "$out/err.csv" -q -o "$out/e.exr"
  echo "relMSE against time in the first half second (spp, seconds, relMSE):"
  cat "$out/err.csv"
done
