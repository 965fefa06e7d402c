#!/usr/bin/env bash
# Instances kept (two-level BVH) against copied into world space (one tree), at equal time, and
# the memory of the 98 M-triangle scene. For each (triangles, nodes) pair,
# bench/make_instanced_scene.py places one bumpy sphere by that many glTF nodes; pt renders it
# at 256x256 with --instances keep and --instances expand for SECONDS each, both at once, one core each
# (cores swapped per round), each scored by relMSE against a long reference. Then the default
# scene (327,680 triangles x 300 nodes, 98 M placed) renders at 512x512 with the defaults, and
# its summary line (time, paths/s, peak memory) is printed.
#
#   bash bench/bench_instances.sh [PT] [SECONDS] [ROUNDS] [REFERENCE_SPP] [PAIRS]
#   (default build/pt, 8 s, 2 rounds, 512 spp, "600x20 2000x12 2000x30 20000x30"; needs python3-numpy)
set -euo pipefail
cd "$(dirname "$0")/.."
pt=${1:-build/pt}
seconds=${2:-8}
rounds=${3:-2}
refspp=${4:-512}
pairs=${5:-"600x20 2000x12 2000x30 20000x30"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sky=(--env-colour 0.3 0.4 0.6 --width 256 --height 256)
echo "| triangles x nodes | placed | round | keep: spp, M paths/s, relMSE | expand: spp, M paths/s, relMSE | paths/s keep / expand |"
echo "|---|---|---|---|---|---|"
for pair in $pairs; do
  out=$(/usr/bin/python3 bench/make_instanced_scene.py "$work/$pair" --triangles "${pair%x*}" --nodes "${pair#*x}")
  placed=$(echo "$out" | sed -n 's/.*= \([0-9]*\) triangles placed/\1/p')
  scene="$work/$pair/scene.gltf"
  "$pt" render "$scene" "${sky[@]}" --spp "$refspp" -q -o "$work/ref.exr" 2>/dev/null
  for r in $(seq 1 "$rounds"); do
    if [ $((r % 2)) = 1 ]; then a=0; b=1; else a=1; b=0; fi
    LP_NUM_THREADS=1 taskset -c $a "$pt" render "$scene" "${sky[@]}" --time "$seconds" --seed $r --instances keep \
      --reference "$work/ref.exr" -q -o "$work/keep.exr" 2>"$work/keep.log" &
    LP_NUM_THREADS=1 taskset -c $b "$pt" render "$scene" "${sky[@]}" --time "$seconds" --seed $r --instances expand \
      --reference "$work/ref.exr" -q -o "$work/expand.exr" 2>"$work/expand.log" &
    wait
    row() { sed -n 's/.*: \([0-9]*\) spp in .* s, \([0-9.]*\) M paths\/s.*, relMSE \([0-9.e-]*\).*/\1 spp, \2, \3/p' "$1"; }
    k=$(row "$work/keep.log"); e=$(row "$work/expand.log")
    ratio=$(python3 -c "k='$k'.split(', '); e='$e'.split(', '); print(round(float(k[1]) / float(e[1]), 3))")
    echo "| $pair | $placed | $r | $k | $e | $ratio |"
  done
done
echo
/usr/bin/python3 bench/make_instanced_scene.py "$work/forest"
"$pt" render "$work/forest/scene.gltf" --env-colour 0.3 0.4 0.6 --spp 16 -o "$work/forest.exr" 2>&1 | grep -E "instances|wrote"
