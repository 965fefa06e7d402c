#!/usr/bin/env bash
# Responsiveness of `pt view` on the built-in Cornell box, through its scripted mode in a
# virtual X server: frame rate and frame times while the camera moves (one orbit step per
# frame), frame times while it refines, time from the last move to 16 spp at full resolution,
# and the input latency bound that follows (an input waits for the frame in flight, then for
# the frame that shows it).
#
#   bash bench/bench_viewer.sh [SIZE] [RUNS] [extra pt view options...]
#   (default: 512 pixels square, 3 runs; needs build/pt (PT=path overrides), xvfb-run)
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-512}
runs=${2:-3}
shift $(( $# > 2 ? 2 : $# ))
pt=${PT:-./build/pt}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -m 700 "$work/xdg"
cat > "$work/script.txt" <<'SCRIPT'
wait-spp 2          # warm up: the speed is learnt, the first full pass done
stats               # (resets the counters)
repeat 30 orbit 3 0 # moving: one orbit step per frame, 26 degrees and back, so the
repeat 30 orbit -3 0 # refinement below is of the starting view (inside the box)
stats
wait-spp 16         # still: refine to 16 spp
report
stats
quit
SCRIPT

echo "| run | moving: fps | frame ms mean / max | still: frame ms mean / max | last move to 16 spp (s) | latency bound ms (max still + max moving frame) |"
echo "|---|---|---|---|---|---|"
for run in $(seq "$runs"); do
  XDG_RUNTIME_DIR="$work/xdg" xvfb-run -a -s "-screen 0 1280x1024x24" \
    "$pt" view --width "$size" --height "$size" --script "$work/script.txt" "$@" > "$work/out.txt" 2> "$work/err.txt" \
    || { cat "$work/err.txt" >&2; exit 1; }
  python3 - "$run" "$work/out.txt" <<'PY'
import re, sys
run, path = sys.argv[1], sys.argv[2]
stats = [dict(re.findall(r"(\w+)=([\d.]+)", l)) for l in open(path) if l.startswith("pt: view: stats")]
report = [dict(re.findall(r"(\w+)=([\d.]+)", l)) for l in open(path) if l.startswith("pt: view: report")]
moving, still = stats[1], stats[2]
f = lambda d, k: float(d[k])
print(f"| {run} | {f(moving,'fps'):.1f} | {f(moving,'frame_ms_mean'):.1f} / {f(moving,'frame_ms_max'):.1f} "
      f"| {f(still,'frame_ms_mean'):.1f} / {f(still,'frame_ms_max'):.1f} | {f(report[0],'since_change'):.2f} "
      f"| {f(still,'frame_ms_max') + f(moving,'frame_ms_max'):.0f} |")
PY
done
grep -m1 "device" "$work/err.txt" | sed 's/^pt: view: /device: /'
