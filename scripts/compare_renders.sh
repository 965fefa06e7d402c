#!/usr/bin/env bash
# Renders a fixed set of scenes with two pt binaries and checks that every image is the same, bit
# for bit (every EXR channel, every PNG byte), and that every input one refuses the other refuses
# with the same message. For refactors that must not change any image.
#
#   bash scripts/compare_renders.sh OLD_PT NEW_PT [WORK_DIR]
#
# OLD_PT is typically a build of the previous commit (git worktree add /tmp/old HEAD~1, build it).
# The set: the scenes in scenes/ and tests/ (glTF and course XML), the shared course scenes and
# glTF samples in ../shared when present, and the default scene with each integrator switch; each
# at 40x30 and 3 spp (several cameras give several images). About 13 minutes per binary on 2 cores.
# Needs build/pt_exr_equal (tools/exr_equal.cpp, built with the benchmarks); override with EXR_EQUAL.
set -uo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OLD_PT NEW_PT [WORK_DIR]"; exit 2; }
repo=$(cd "$(dirname "$0")/.." && pwd)
old=$(realpath "$1"); new=$(realpath "$2"); work=${3:-$(mktemp -d)}
exr_equal=${EXR_EQUAL:-$repo/build/pt_exr_equal}
[ -x "$exr_equal" ] || { echo "compare: $exr_equal not found (cmake --build build --target pt_exr_equal)"; exit 2; }
shared=$repo/../shared

render_set() { # PT OUT
    local pt=$1 out=$2
    run() { # NAME ARGS...
        local name=$1; shift
        mkdir -p "$out/$name"
        "$pt" render "$@" --width 40 --height 30 --spp 3 -q -o "$out/$name/img.exr" >"$out/$name/log.txt" 2>&1
        echo "rc=$?" >>"$out/$name/log.txt"
        if grep -q "several cameras" "$out/$name/log.txt"; then
            "$pt" render "$@" --width 40 --height 30 --spp 3 -q -o "$out/$name/" >"$out/$name/log.txt" 2>&1
            echo "rc=$?" >>"$out/$name/log.txt"
        fi
    }
    run default
    run default-classic --integrator classic
    run default-sobol --sampler sobol
    run default-all-features --all-features
    run default-plain --nee off --mis off --rr off
    run default-env-colour --env-colour 0.2 0.3 0.4
    run default-variance --variance
    run default-tiled --tile 16 --pass-spp 1
    run glass-no-light-tracing "$repo/tests/references/cbox-glass-mirror/scene.gltf" --light-tracing off
    run env-map "$repo/tests/references/cbox-diffuse/scene.gltf" --env "$repo/tests/references/own/textured.exr"
    local f name
    for f in "$repo"/scenes/*.gltf "$repo"/scenes/*/*.gltf "$repo"/scenes/*/*.xml "$repo"/tests/references/*/scene.gltf \
        "$repo"/tests/data/ceng795/*.xml "$repo"/tests/data/ceng795/classic/*.xml \
        "$repo"/tests/data/gltf_samples/*/glTF/*.gltf "$repo"/tests/data/cli/*.gltf \
        "$shared"/ceng795/scenes/*/inputs/*.xml "$shared"/gltf-samples/*/glTF/*.gltf; do
        [ -f "$f" ] || continue
        name=$(realpath --relative-to="$repo/.." "$f" | tr '/' '_')
        run "$name" "$f"
    done
}

echo "compare: rendering with $old"
render_set "$old" "$work/old"
echo "compare: rendering with $new"
render_set "$new" "$work/new"

same=0 refused=0 differ=0
for dir in "$work"/old/*/; do
    name=$(basename "$dir")
    a=$work/old/$name b=$work/new/$name
    if [ "$(grep '^rc=' "$a/log.txt" | tail -1)" != "$(grep '^rc=' "$b/log.txt" | tail -1)" ]; then
        echo "DIFFER $name: exit status"; differ=$((differ + 1)); continue
    fi
    if ! grep -q '^rc=0' "$a/log.txt"; then
        if [ "$(grep error "$a/log.txt")" == "$(grep error "$b/log.txt")" ]; then refused=$((refused + 1)); else
            echo "DIFFER $name: error message"; differ=$((differ + 1)); fi
        continue
    fi
    for exr in "$a"/*.exr; do
        png=${exr%.exr}.png
        if "$exr_equal" "$exr" "$b/$(basename "$exr")" >/dev/null && cmp -s "$png" "$b/$(basename "$png")"; then
            same=$((same + 1))
        else
            echo "DIFFER $name/$(basename "$exr")"; differ=$((differ + 1))
        fi
    done
done
echo "compare: $same images identical (EXR and PNG), $refused refused inputs with the same message, $differ differences"
[ $differ -eq 0 ]
