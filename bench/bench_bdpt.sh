#!/usr/bin/env bash
# Path tracing against bidirectional path tracing, with and without vertex merging, at equal time
# on one scene: one after the other on the whole machine, each scored against the same reference
# (box-filtered down to the render's size where it is a whole multiple of it, as `pt render
# --reference` does). Prints the CPU, a Markdown row per integrator (spp, M paths/s, relMSE,
# estimated relMSE) and the relMSE ratios path / bdpt and path / vcm; keeps the images (EXR and
# PNG) in OUT_DIR. INTEGRATORS (environment) chooses which run (default "path bdpt vcm").
#
#   bash bench/bench_bdpt.sh PT SCENE REFERENCE.exr SECONDS WIDTH HEIGHT OUT_DIR [pt options...]
#
# Veach Ajar (the course's 2022-hw6-veach-ajar, camera 2, against its official 2500-spp image):
#   V=../shared/ceng795/scenes/2022-hw6-veach-ajar
#   bash bench/bench_bdpt.sh build/pt $V/inputs/scene.xml $V/outputs/VeachAjar_path.exr 60 320 180 out/veach --camera 2
# The official image's own noise (relMSE 0.72) hides most of the difference; at 320x180 score
# against the longer render instead (bench/references/README.md):
#   bash bench/bench_bdpt.sh build/pt $V/inputs/scene.xml bench/references/veach-ajar-320x180/reference.exr 60 320 180 out/veach --camera 2
set -euo pipefail
pt=$1
scene=$2
reference=$3
seconds=$4
width=$5
height=$6
out=$7
shift 7
mkdir -p "$out"
echo "Machine: $(python3 "$(dirname "$0")/machine_info.py")"
echo "| integrator | spp | M paths/s | relMSE | estimated relMSE |"
echo "|---|---|---|---|---|"
declare -A err
for integrator in ${INTEGRATORS:-path bdpt vcm}; do
  "$pt" render "$scene" --integrator "$integrator" --time "$seconds" --width "$width" --height "$height" \
    --reference "$reference" -o "$out/$integrator.exr" "$@" 2>"$out/$integrator.log"
  line=$(grep ' spp in ' "$out/$integrator.log" | tail -1)
  spp=$(sed -n 's/.*: \([0-9]*\) spp in .*/\1/p' <<<"$line")
  rate=$(sed -n 's/.* \([0-9.]*\) M paths\/s.*/\1/p' <<<"$line")
  err[$integrator]=$(sed -n 's/.*, relMSE \([0-9.e+-]*\).*/\1/p' <<<"$line")
  estimate=$(sed -n 's/.*estimated relMSE \([0-9.e+-]*\).*/\1/p' <<<"$line")
  echo "| $integrator | $spp | $rate | ${err[$integrator]} | $estimate |"
done
for other in bdpt vcm; do
  if [ -n "${err[path]:-}" ] && [ -n "${err[$other]:-}" ]; then
    echo "relMSE path / $other at ${seconds} s, ${width}x${height}: $(python3 -c "print(round(${err[path]} / ${err[$other]}, 2))")"
  fi
done
