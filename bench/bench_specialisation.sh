#!/usr/bin/env bash
# What kernel specialisation saves: the diffuse Cornell box (Mitsuba reference scene) rendered
# for the same time with the kernel specialised to the scene and with every feature compiled
# in (--all-features), on each lavapipe found. Prints pipeline creation seconds, M paths/s and
# relMSE against the reference (both kernels compute the same image, so at equal time the
# faster one has the lower error).
#
#   bash bench/bench_specialisation.sh [SECONDS]    (default 20; needs build/pt)
#   MESA22_ICD=/path/to/lvp_icd.json adds Debian 12's own Mesa 22 lavapipe (unpack
#   mesa-vulkan-drivers_22.3.6 from bookworm with dpkg-deb -x and point at its ICD json).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
pt=./build/pt
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene=tests/references/cbox-diffuse
drivers=("default:")
[ -n "${MESA22_ICD:-}" ] && drivers+=("mesa22:$MESA22_ICD")

echo "Machine: $(python3 bench/machine_info.py)"
echo
echo "| driver | kernel | pipeline (s) | spp | M paths/s | relMSE |"
echo "|---|---|---|---|---|---|"
for d in "${drivers[@]}"; do
  name=${d%%:*}; icd=${d#*:}
  for kernel in specialised all-features; do
    flag=(); [ "$kernel" = all-features ] && flag=(--all-features)
    log=$out/$name-$kernel.csv
    err=$( (if [ -n "$icd" ]; then export VK_ICD_FILENAMES=$icd; fi
            $pt render "$scene/scene.gltf" --time "$seconds" "${flag[@]}" --reference "$scene/reference.exr" \
                --error-log "$log" -o "$out/$name-$kernel.exr" 2>&1 >/dev/null) || true)
    device=$(echo "$err" | grep -m1 '^pt: device' | grep -o 'Mesa [0-9][0-9.]*' || true)
    pipeline=$(echo "$err" | grep -m1 -o 'pipeline [0-9.]* s' | grep -o '[0-9.]*' || echo "?")
    IFS=, read -r spp secs relmse < <(tail -n 1 "$log")
    mpaths=$(python3 -c "print(f'{256*256*$spp/$secs/1e6:.3f}')")
    printf '| %s %s | %s | %s | %s | %s | %.5f |\n' "$name" "$device" "$kernel" "$pipeline" "$spp" "$mpaths" "$relmse"
  done
done
