#!/usr/bin/env bash
# The defaults, measured: each scene rendered at one time budget with several settings and
# seeds, one right after the other, printing spp, M paths/s and relMSE against a reference, and
# each setting's mean relMSE over the seeds against the first setting's (below 1: better at
# equal time). Scenes: the two Mitsuba reference boxes (their references), and two of this
# project's made by bench/make_mesh_scene.py (1 M triangles, 128x128) and
# bench/make_rough_scene.py (rough gold, rough glass, a textured floor), whose references pt
# renders first with the independent sampler at REF_SPP (unbiased either way; a setting's error
# includes the reference's noise, the same for every setting).
#
#   bash bench/bench_defaults.sh [BUDGET [SEEDS [SETTINGS...]]]
#     BUDGET    seconds per render (default 10)
#     SEEDS     seeds per setting (default 2)
#     SETTINGS  pt render options per setting, one string each (default: "" "--sampler sobol")
#   REF_SPP=N   the made scenes' reference samples (default 1024); references are kept in
#               $PT_BENCH_CACHE (default ~/.cache/pt-bench) for the next run.
# Needs build/pt, python3-numpy and python3-pil (the scene makers).
set -euo pipefail
cd "$(dirname "$0")/.."
budget=${1:-10}
seeds=${2:-2}
shift $(( $# > 2 ? 2 : $# ))
settings=("$@")
[ ${#settings[@]} -gt 0 ] || settings=("" "--sampler sobol")
pt=./build/pt
cache=${PT_BENCH_CACHE:-$HOME/.cache/pt-bench}
refSpp=${REF_SPP:-1024}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python=/usr/bin/python3

mkdir -p "$cache"
[ -f "$cache/mesh/scene.gltf" ] || $python bench/make_mesh_scene.py "$cache/mesh" --triangles 1000000 >/dev/null
[ -f "$cache/rough/scene.gltf" ] || $python bench/make_rough_scene.py "$cache/rough" >/dev/null
scenes=(cbox-diffuse cbox-glass-mirror mesh rough)
declare -A file ref size
for s in cbox-diffuse cbox-glass-mirror; do
  file[$s]=tests/references/$s/scene.gltf
  ref[$s]=tests/references/$s/reference.exr
  size[$s]=""
done
file[mesh]=$cache/mesh/scene.gltf
size[mesh]="--width 128 --height 128"
file[rough]=$cache/rough/scene.gltf
size[rough]=""
for s in mesh rough; do
  ref[$s]=$cache/$s/reference-$refSpp.exr
  if [ ! -f "${ref[$s]}" ]; then
    echo "rendering the $s reference ($refSpp spp)..." >&2
    # shellcheck disable=SC2086
    $pt render "${file[$s]}" ${size[$s]} --spp "$refSpp" --seed 1000003 -o "${ref[$s]}" -q
  fi
done

echo "Device: $($pt devices | head -n 1)"
echo "Machine: $(python3 bench/machine_info.py)"
echo
echo "| scene | settings | seed | spp | M paths/s | relMSE |"
echo "|---|---|---|---|---|---|"
declare -A sum
for s in "${scenes[@]}"; do
  for i in "${!settings[@]}"; do
    sum[$s,$i]=0
    # A first render fills the pipeline cache, so that no budget pays for compiling a kernel.
    # shellcheck disable=SC2086
    $pt render "${file[$s]}" ${size[$s]} ${settings[$i]} --spp 1 -o "$out/$s.exr" -q 2>/dev/null
    for seed in $(seq 0 $((seeds - 1))); do
      log=$out/$s-$i-$seed.csv
      # shellcheck disable=SC2086
      $pt render "${file[$s]}" ${size[$s]} ${settings[$i]} --seed "$seed" --time "$budget" --reference "${ref[$s]}" \
          --error-log "$log" -o "$out/$s.exr" -q 2>/dev/null
      IFS=, read -r spp seconds relmse < <(tail -n 1 "$log")
      pixels=$([ "$s" = mesh ] && echo 16384 || echo 65536)
      mpaths=$($python -c "print(f'{$pixels*$spp/$seconds/1e6:.3f}')")
      printf '| %s | %s | %s | %s | %s | %.5f |\n' "$s" "${settings[$i]:-defaults}" "$seed" "$spp" "$mpaths" "$relmse"
      sum[$s,$i]=$($python -c "print(${sum[$s,$i]} + $relmse)")
    done
  done
done
echo
echo "Mean relMSE over the seeds, and its ratio to the first setting's:"
echo
echo "| scene | settings | mean relMSE | ratio |"
echo "|---|---|---|---|"
for s in "${scenes[@]}"; do
  for i in "${!settings[@]}"; do
    $python -c "m=${sum[$s,$i]}/$seeds; b=${sum[$s,0]}/$seeds; print(f'| $s | ${settings[$i]:-defaults} | {m:.5f} | {m/b:.2f} |')"
  done
done
