#!/usr/bin/env bash
# Speed against error on the two Mitsuba reference scenes: renders each at several time
# budgets and prints a Markdown table of seconds, spp, M paths/s and relMSE against the
# reference. For Mitsuba 3 at the same budgets, measured in the same run on this machine, use
# bench/bench_vs_mitsuba.py (figures from another machine compare nothing).
#
#   bash bench/bench_cbox.sh [BUDGETS...]      (default: 5 10 30 60; needs build/pt)
set -euo pipefail
cd "$(dirname "$0")/.."
budgets=("$@")
[ ${#budgets[@]} -gt 0 ] || budgets=(5 10 30 60)
pt=./build/pt
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

device=$($pt devices | head -n 1)
echo "Device: $device"
echo "Machine: $(python3 bench/machine_info.py)"
echo
echo "| scene | budget (s) | seconds | spp | M paths/s | relMSE |"
echo "|---|---|---|---|---|---|"
for scene in cbox-diffuse cbox-glass-mirror; do
  dir=tests/references/$scene
  for budget in "${budgets[@]}"; do
    log=$out/$scene-$budget.csv
    $pt render "$dir/scene.gltf" --time "$budget" --reference "$dir/reference.exr" --error-log "$log" \
        -o "$out/$scene-$budget.exr" -q 2>/dev/null
    IFS=, read -r spp seconds relmse < <(tail -n 1 "$log")
    mpaths=$(python3 -c "print(f'{256*256*$spp/$seconds/1e6:.3f}')")
    printf '| %s | %s | %.2f | %s | %s | %.5f |\n' "$scene" "$budget" "$seconds" "$spp" "$mpaths" "$relmse"
  done
done
