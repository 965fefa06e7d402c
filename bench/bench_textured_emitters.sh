#!/usr/bin/env bash
# Light selection for textured emitters at equal time: two pt binaries (say, before and after a
# change to the light table) render bench/make_patchy_emitter_scene.py's sphere of bright spots
# under a dim sky for SECONDS each, both at once, one core each (cores swapped per round, as the
# machine's speed drifts), and each is scored by relMSE against a long reference rendered first
# by the second binary. Prints a Markdown row per round: spp, M paths/s and relMSE of each.
#
#   bash bench/bench_textured_emitters.sh OLD_PT NEW_PT [SECONDS] [ROUNDS] [REFERENCE_SPP]
#   (default 10 s, 2 rounds, 2048 spp; needs python3-numpy, python3-pil)
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
seconds=${3:-10}
rounds=${4:-2}
refspp=${5:-2048}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 bench/make_patchy_emitter_scene.py "$work/scene" >/dev/null
scene="$work/scene/scene.gltf"
sky=(--env-colour 0.05 0.05 0.05)
"$new" render "$scene" "${sky[@]}" --spp "$refspp" -q -o "$work/ref.exr" 2>/dev/null
# The same-moment A/B (bench/ab_equal_time.sh): rows of spp, M paths/s and relMSE before (OLD)
# and after (NEW), and relMSE new / old.
bash bench/ab_equal_time.sh "$old" "$new" "$scene" "$work/ref.exr" "$seconds" "$rounds" "${sky[@]}"
