#!/usr/bin/env bash
# Runs the benchmarks and writes bench/results/<YYYY-MM-DD>.json (Google Benchmark's JSON) and
# bench/results/<YYYY-MM-DD>-loop.json (the servo loop's timing at 1 kHz and 10 kHz).
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
for rate in 1000 10000; do
  "$bin/sandpaper_bench_loop" --rate "$rate" --duration "$seconds" --json-out "$out/$day-loop-$rate.json" || true
  loops+=("$out/$day-loop-$rate.json")
done
python3 - "$out/$day-loop.json" "${loops[@]}" <<'PY'
import json, sys, os
runs = [json.load(open(f)) for f in sys.argv[2:] if os.path.exists(f)]
json.dump({"loop_runs": runs}, open(sys.argv[1], "w"), indent=2)
for f in sys.argv[2:]:
    if os.path.exists(f): os.remove(f)
PY
echo "wrote $out/$day.json and $out/$day-loop.json"
