#!/usr/bin/env bash
# Resident memory of a long render: runs `pt render` on a textured glTF scene for many samples
# (one-sample passes with a checkpoint every few seconds, the long-render path) and samples the
# process's VmRSS from /proc every INTERVAL seconds. Prints a table (seconds, spp so far, RSS in
# MiB) and the growth after warm-up; a flat resident set shows as the same RSS from the first
# rows to the last.
#
#   bash bench/bench_memory.sh [SPP] [SIZE] [INTERVAL]
#   (default: 10000 spp, 64 pixels square, 5 s; needs build/pt, PT=path overrides)
set -euo pipefail
cd "$(dirname "$0")/.."
spp=${1:-10000}
size=${2:-64}
interval=${3:-5}
pt=${PT:-./build/pt}
scene=tests/data/gltf_samples/TextureSettingsTest/glTF/TextureSettingsTest.gltf
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$pt" render "$scene" --env-colour 1 1 1 --spp "$spp" --width "$size" --height "$size" --pass-spp 1 \
  --checkpoint "$work/ckpt.exr" --checkpoint-every 10 -o "$work/out.exr" 2>"$work/log" &
pid=$!
start=$(date +%s)
echo "| seconds | spp | VmRSS (MiB) |"
echo "|---|---|---|"
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$rss" ] || break
  done_spp=$(tr '\r' '\n' < "$work/log" | grep -o '^pt: [0-9]* spp' | tail -1 | grep -o '[0-9]*' || echo 0)
  awk -v t=$(( $(date +%s) - start )) -v s="${done_spp:-0}" -v r="$rss" 'BEGIN { printf "| %d | %s | %.1f |\n", t, s, r / 1024 }' 
  [ "${done_spp:-0}" -gt 0 ] && echo "$rss" >> "$work/rss.rendering"
  sleep "$interval"
done
wait "$pid"
tail -1 "$work/log"
# Growth after warm-up: the last sample against the first taken once rendering had started.
first=$(head -1 "$work/rss.rendering")
last=$(tail -1 "$work/rss.rendering")
echo "RSS once rendering: $(( first / 1024 )) MiB; at the end: $(( last / 1024 )) MiB; growth $(( last - first )) KiB"
