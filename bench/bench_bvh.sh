#!/usr/bin/env bash
# BVH build speed and quality, and what they buy at render time.
#
#   bash bench/bench_bvh.sh [BUDGET_SECONDS]      (default 10; needs build/pt and build/pt_bvh_bench)
#
# 1. Build: pt_bvh_bench on 1 M triangles (a random soup and a bumpy-sphere surface), 1 and 2
#    threads, median of 5 builds: seconds, M triangles/s, SAH cost, nodes, depth.
# 2. Render: for cbox-diffuse, cbox-glass-mirror (references in tests/references) and a 1 M-triangle
#    bumpy sphere in the Cornell box (bench/make_mesh_scene.py; its reference is rendered here at
#    $REF_SPP spp, default 1024, 128x128), `pt render` reports the BVH build and `pt bench` renders
#    BUDGET seconds with NEE + BSDF sampling + RR: spp, M rays/s and relMSE against the reference.
set -euo pipefail
cd "$(dirname "$0")/.."
budget=${1:-10}
ref_spp=${REF_SPP:-1024}
pt=${PT:-./build/pt}
bvhbench=${PT_BVH_BENCH:-./build/pt_bvh_bench}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "Device: $($pt devices | head -n 1)"
echo "Machine: $(python3 bench/machine_info.py); load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "### BVH build (pt_bvh_bench, median of 5)"
echo
$bvhbench --mesh soup --repeats 5
$bvhbench --mesh surface --repeats 5 | tail -n +3
echo

python3 bench/make_mesh_scene.py "$out/bumpy" >/dev/null
"$pt" render "$out/bumpy/scene.gltf" --width 128 --height 128 --spp "$ref_spp" -o "$out/bumpy/reference.exr" -q 2>/dev/null

echo "### Render at $budget s (pt bench, nee+is+rr)"
echo
echo "| scene | triangles | BVH build s | M triangles/s | SAH cost | depth | spp | M rays/s | relMSE |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in cbox-diffuse cbox-glass-mirror bumpy; do
  if [ "$scene" = bumpy ]; then
    file=$out/bumpy/scene.gltf; ref=$out/bumpy/reference.exr; size=(--width 128 --height 128)
  else
    file=tests/references/$scene/scene.gltf; ref=tests/references/$scene/reference.exr; size=()
  fi
  # "pt: FILE: N triangles, S spheres, L lights, BVH X s (SAH C, depth D), load Y s"
  line=$("$pt" render "$file" "${size[@]}" --spp 1 -o "$out/probe.exr" 2>&1 | grep ' triangles, ')
  tris=$(sed -E 's/.*: ([0-9]+) triangles,.*/\1/' <<<"$line")
  bvh=$(sed -E 's/.*BVH ([0-9.]+) s.*/\1/' <<<"$line")
  sah=$(sed -E 's/.*SAH ([0-9.]+),.*/\1/' <<<"$line")
  depth=$(sed -E 's/.*depth ([0-9]+)\).*/\1/' <<<"$line")
  "$pt" bench "$file" "${size[@]}" --reference "$ref" --configs nee+is+rr --budgets "$budget" --no-plot \
      -o "$out/bench-$scene" >/dev/null 2>&1
  # bench.csv: config,budget_s,spp,seconds,mpaths_per_s,mrays_per_s,...,relmse,...
  IFS=, read -r _ _ spp _ _ mrays _ _ _ relmse _ < <(tail -n 1 "$out/bench-$scene/bench.csv")
  mtris=$(python3 -c "print(f'{$tris / $bvh / 1e6:.2f}' if $bvh >= 0.005 else '-')") # too short to time
  printf '| %s | %s | %s | %s | %s | %s | %s | %.3f | %.5f |\n' "$scene" "$tris" "$bvh" "$mtris" "$sah" "$depth" "$spp" "$mrays" "$relmse"
done
