#!/usr/bin/env bash
# Runs the benchmarks and writes bench/results/<YYYY-MM-DD>.json (Google Benchmark's JSON),
# bench/results/<YYYY-MM-DD>-loop.json (the servo loop's timing: 1 kHz once, 10 kHz three times)
# bench/results/<YYYY-MM-DD>-player.json (sandpaper-play's start-up and memory) and
# bench/results/<YYYY-MM-DD>-overruns.json (the player's late ticks beside a bare clock_nanosleep loop).
#   tools/bench.sh [BIN_DIR] [LOOP_SECONDS]      (default /tmp/build/bin, 60 s)
# Timing on a shared machine is noisy: run it when nothing else is building.
set -euo pipefail
bin=${1:-/tmp/build/bin}
seconds=${2:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/bench/results"
mkdir -p "$out"
day=$(date +%F)
"$bin/sandpaper_bench" --benchmark_out="$out/$day.json" --benchmark_out_format=json \
  --benchmark_filter='^(BM_Term|BM_HeightFieldSize|BM_GratingSize|BM_Force|BM_Material|BM_Workspace|BM_Compile)'
loops=()
for run in 1000:1 10000:1 10000:2 10000:3; do
  rate=${run%%:*}
  "$bin/sandpaper_bench_loop" --rate "$rate" --duration "$seconds" --json-out "$out/$day-loop-$rate-${run##*:}.json" || true
  loops+=("$out/$day-loop-$rate-${run##*:}.json")
done
python3 - "$out/$day-loop.json" "${loops[@]}" <<'PY'
import json, sys, os
runs = [json.load(open(f)) for f in sys.argv[2:] if os.path.exists(f)]
json.dump({"loop_runs": runs}, open(sys.argv[1], "w"), indent=2)
for f in sys.argv[2:]:
    if os.path.exists(f): os.remove(f)
PY
python3 "$root/bench/player_bench.py" "$bin" --seconds "$seconds" --json-out "$out/$day-player.json"
"$bin/sandpaper_bench_overruns" --rate 10000 --seconds "$seconds" --json-out "$out/$day-overruns.json"
echo "wrote $out/$day.json, $out/$day-loop.json, $out/$day-player.json and $out/$day-overruns.json"
