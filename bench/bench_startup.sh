#!/usr/bin/env bash
# Start-up: how long `pt render` takes to create its pipeline and to finish a tiny render, the
# first time (empty caches: pt's and Mesa's, in a fresh XDG_CACHE_HOME) and the second time
# (both caches filled by the first), for scenes that need different kernels. The accuracy beside
# each time is exactness: every image must be bit-identical to the cold run's (pt_exr_equal), and
# to OLD_PT's when given (a pt from before a change, e.g. one that let the driver specialise).
#
#   bash bench/bench_startup.sh [OLD_PT]     (needs build/pt and build/pt_exr_equal)
set -euo pipefail
cd "$(dirname "$0")/.."
pt=$(realpath build/pt)
equal=$(realpath build/pt_exr_equal)
old=${1:+$(realpath "$1")}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

scenes=(
  "cornell box (built in)|"
  "cornell box, every feature compiled in|--all-features"
  "glass and mirror box (light tracing kernel)|tests/references/cbox-glass-mirror/scene.gltf"
  "course HW6 glass box, camera 3 (NEE)|tests/data/ceng795/cornellbox_jaroslav_path_glass.xml --camera 3"
  "textured glTF (TextureSettingsTest)|tests/data/gltf_samples/TextureSettingsTest/glTF/TextureSettingsTest.gltf"
)

# Runs one render; prints "pipeline-seconds wall-seconds source".
render() { # binary cache-home output args...
  local bin=$1 home=$2 exr=$3; shift 3
  local start end log
  start=$(date +%s.%N)
  # shellcheck disable=SC2068
  log=$(XDG_CACHE_HOME=$home "$bin" render $@ --spp 1 --width 64 --height 64 -o "$exr" 2>&1) || {
    echo "render failed: $bin $*" >&2; echo "$log" >&2; exit 1; }
  end=$(date +%s.%N)
  local pipeline source
  pipeline=$(echo "$log" | grep -m1 -o 'pipeline [0-9.]* s' | grep -o '[0-9.]*')
  source=$(echo "$log" | grep -m1 -o '(\(cached\|specialised\) kernel)' | tr -d '()' || true)
  echo "$pipeline $(python3 -c "print(f'{$end - $start:.2f}')") ${source:-driver}"
}

same() { "$equal" "$1" "$2" >/dev/null 2>&1 && echo yes || echo NO; }

echo "Machine: $(python3 bench/machine_info.py); $("$pt" devices 2>/dev/null | grep -m1 -o 'Mesa [0-9.]*' || true)"
echo
header="| scene | first: pipeline s / wall s | second: pipeline s / wall s | same image |"
sep="|---|---|---|---|"
if [ -n "$old" ]; then
  header="$header old pt first | old pt second | same as old |"
  sep="$sep---|---|---|"
fi
echo "$header"
echo "$sep"
i=0
for entry in "${scenes[@]}"; do
  name=${entry%%|*}; args=${entry#*|}
  i=$((i + 1))
  home=$out/home$i
  mkdir -p "$home"
  read -r p1 w1 s1 < <(render "$pt" "$home" "$out/$i-first.exr" $args)
  read -r p2 w2 s2 < <(render "$pt" "$home" "$out/$i-second.exr" $args)
  row="| $name | $p1 / $w1 ($s1) | $p2 / $w2 ($s2) | $(same "$out/$i-first.exr" "$out/$i-second.exr") |"
  if [ -n "$old" ]; then
    oldhome=$out/old$i
    mkdir -p "$oldhome"
    read -r p3 w3 _ < <(render "$old" "$oldhome" "$out/$i-old1.exr" $args)
    read -r p4 w4 _ < <(render "$old" "$oldhome" "$out/$i-old2.exr" $args)
    row="$row $p3 / $w3 | $p4 / $w4 | $(same "$out/$i-first.exr" "$out/$i-old1.exr") |"
  fi
  echo "$row"
done
