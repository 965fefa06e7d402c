#!/usr/bin/env bash
# The light tree against light selection by power, at equal time, on a scene lit by many lamps
# (bench/make_many_lights_scene.py: a hall of 184 small lamps and an emissive ball). One pt binary
# renders both (`--light-tree off` and `on`), both at once, one core each, cores swapped per
# round (bench/ab_equal_time.sh), scored against a long reference it renders first with the tree
# (the tree and the power CDF render the same image: tests/shaders/lights/light_tree_test.cpp).
# Prints a Markdown row per round: spp, M paths/s and relMSE of each, and relMSE tree / power.
#
#   bash bench/bench_light_tree.sh [PT] [SECONDS] [ROUNDS] [REFERENCE_SECONDS]
#   (default build/pt, 10 s, 4 rounds, a 300-s reference)
set -euo pipefail
cd "$(dirname "$0")/.."
pt=${1:-build/pt}
seconds=${2:-10}
rounds=${3:-4}
refseconds=${4:-300}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 bench/make_many_lights_scene.py "$work/scene"
"$pt" render "$work/scene/scene.gltf" --time "$refseconds" --light-tree on --seed 99 -q -o "$work/ref.exr" 2>&1 | tail -1
BEFORE_ARGS="--light-tree off" AFTER_ARGS="--light-tree on" \
  bash bench/ab_equal_time.sh "$pt" "$pt" "$work/scene/scene.gltf" "$work/ref.exr" "$seconds" "$rounds"
