#!/usr/bin/env bash
# Speed against error on the two Mitsuba reference scenes: renders each at several time
# budgets and prints a Markdown table of seconds, spp, M paths/s and relMSE against the
# reference, beside Mitsuba 3's relMSE at the same time on the same kind of machine.
#
#   bash bench/bench_cbox.sh [BUDGETS...]      (default: 5 10 30 60; needs build/pt)
set -euo pipefail
cd "$(dirname "$0")/.."
budgets=("$@")
[ ${#budgets[@]} -gt 0 ] || budgets=(5 10 30 60)
pt=./build/pt
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Mitsuba 3.9.1 (llvm_ad_rgb, 2 cores, warm), from bench/MITSUBA_SPEED.md
# (copied from the shared reference set): (seconds relMSE) pairs, interpolated log-log below.
declare -A mitsuba=(
  [cbox-diffuse]="0.12 0.277 0.45 0.064 1.74 0.0163 6.9 0.0042 26.4 0.00115 53.4 0.00064"
  [cbox-glass-mirror]="0.18 3.05 0.70 0.733 2.74 0.187 10.7 0.047 42.8 0.0128 85.4 0.0071"
)
interpolate() { # seconds, then the (s, e) pairs: log-log interpolation, linear extrapolation at the ends
  python3 - "$@" <<'PY'
import math, sys
t = float(sys.argv[1]); v = list(map(float, sys.argv[2:]))
pts = list(zip(v[0::2], v[1::2]))
for (s0, e0), (s1, e1) in zip(pts, pts[1:]):
    if t <= s1 or (s1, e1) == pts[-1]:
        a = (math.log(e1) - math.log(e0)) / (math.log(s1) - math.log(s0))
        print(f"{math.exp(math.log(e0) + a * (math.log(t) - math.log(s0))):.5f}"); break
PY
}

device=$($pt devices | head -n 1)
echo "Device: $device"
echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo
echo "| scene | budget (s) | seconds | spp | M paths/s | relMSE | Mitsuba 3 relMSE at that time | ratio (ours / Mitsuba) |"
echo "|---|---|---|---|---|---|---|---|"
for scene in cbox-diffuse cbox-glass-mirror; do
  dir=tests/references/$scene
  for budget in "${budgets[@]}"; do
    log=$out/$scene-$budget.csv
    $pt render "$dir/scene.gltf" --time "$budget" --reference "$dir/reference.exr" --error-log "$log" \
        -o "$out/$scene-$budget.exr" -q 2>/dev/null
    IFS=, read -r spp seconds relmse < <(tail -n 1 "$log")
    mpaths=$(python3 -c "print(f'{256*256*$spp/$seconds/1e6:.3f}')")
    mi=$(interpolate "$seconds" ${mitsuba[$scene]})
    ratio=$(python3 -c "print(f'{$relmse/$mi:.2f}')")
    printf '| %s | %s | %.2f | %s | %s | %.5f | %s | %s |\n' "$scene" "$budget" "$seconds" "$spp" "$mpaths" "$relmse" "$mi" "$ratio"
  done
done
