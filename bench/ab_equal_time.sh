#!/usr/bin/env bash
# Two pt binaries (before and after a change) at equal time on one scene: both render at once,
# one core each (LP_NUM_THREADS=1, cores swapped per round, as the machine's speed drifts), each
# scored against the same reference. Prints a Markdown row per round: spp, M paths/s and relMSE
# of each, and the ratio of the relMSEs (after / before).
#
#   bash bench/ab_equal_time.sh BEFORE_PT AFTER_PT SCENE REFERENCE.exr [SECONDS] [ROUNDS] [pt options...]
#
# BEFORE_ARGS and AFTER_ARGS (environment) add options to one side only: one binary against
# itself with a switch changed, e.g. BEFORE_ARGS="--light-tree off" AFTER_ARGS="--light-tree on".
set -euo pipefail
before=$1
after=$2
scene=$3
reference=$4
seconds=${5:-10}
rounds=${6:-4}
shift $(($# < 6 ? $# : 6))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| round | before: spp, M paths/s, relMSE | after: spp, M paths/s, relMSE | relMSE after / before |"
echo "|---|---|---|---|"
for r in $(seq 1 "$rounds"); do
  if [ $((r % 2)) = 1 ]; then a=0; b=1; else a=1; b=0; fi
  LP_NUM_THREADS=1 taskset -c $a "$before" render "$scene" --time "$seconds" --seed "$r" --reference "$reference" \
    -q -o "$work/before.exr" "$@" ${BEFORE_ARGS:-} 2>"$work/before.log" &
  LP_NUM_THREADS=1 taskset -c $b "$after" render "$scene" --time "$seconds" --seed "$r" --reference "$reference" \
    -q -o "$work/after.exr" "$@" ${AFTER_ARGS:-} 2>"$work/after.log" &
  wait
  row() { sed -n 's/.*: \([0-9]*\) spp in .* s, \([0-9.]*\) M paths\/s.*, relMSE \([0-9.e-]*\).*/\1 spp, \2, \3/p' "$1"; }
  o=$(row "$work/before.log")
  n=$(row "$work/after.log")
  echo "| $r | $o | $n | $(python3 -c "print(round(${n##*, } / ${o##*, }, 3))") |"
done
