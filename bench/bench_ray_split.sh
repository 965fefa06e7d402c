#!/usr/bin/env bash
# Cost of splitting one render into K Ray chunks on this machine: wall time of a single
# `pt render --spp N` against `python -m pt_ray render --spp N --chunks K` (local Ray cluster,
# its start included) for several K, and the fixed cost of one pt process (a 1-spp render:
# Vulkan start-up, scene load, pipeline creation), each repeated RUNS times (min and max).
#
#   bash bench/bench_ray_split.sh [SPP] [SIZE] [RUNS] [K...]
#   (default: 256 spp, 256 pixels square, 2 runs, K = 1 2 4 8; needs build/pt (PT=path
#   overrides) and the venv of scripts/setup_ray_venv.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
spp=${1:-256}
size=${2:-256}
runs=${3:-2}
shift $(( $# > 3 ? 3 : $# ))
ks=("${@:-1 2 4 8}")
[ $# -gt 0 ] || ks=(1 2 4 8)
pt=$(realpath "${PT:-./build/pt}")
python=${PT_RAY_PYTHON:-/opt/pt-ray/bin/python}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export RAY_USAGE_STATS_ENABLED=0 PYTHONPATH=tools/pt_ray
args="--width $size --height $size"

seconds() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>"$work/err" || { cat "$work/err"; exit 1; }; t1=$(date +%s.%N); awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }'; }
range() { tr ' ' '\n' | sort -n | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%s–%s", lo, hi }'; }

fixed=""; single=""
for r in $(seq "$runs"); do
  fixed+="$(seconds "$pt" render $args --spp 1 -q -o "$work/one.exr") "
  single+="$(seconds "$pt" render $args --spp "$spp" -q -o "$work/single.exr") "
done
echo "| configuration | wall seconds (min–max of $runs) |"
echo "|---|---|"
echo "| one pt process, 1 spp (fixed cost) | $(echo $fixed | range) |"
echo "| single pt render, $spp spp | $(echo $single | range) |"
for k in "${ks[@]}"; do
  times=""
  for r in $(seq "$runs"); do
    rm -rf "$work/ray.parts"
    times+="$(seconds "$python" -m pt_ray render --spp "$spp" --chunks "$k" --pt "$pt" --pt-args "$args" -o "$work/ray.exr") "
  done
  echo "| pt_ray, $k chunk(s) | $(echo $times | range) |"
done
