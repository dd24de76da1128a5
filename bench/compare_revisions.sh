#!/usr/bin/env bash
# Times the same benchmarks on an older revision and on the current tree in one session, base and
# current alternately (A B A B A B ...), and prints per benchmark the median of each side, the
# ratio current/base, the spread of each side's round medians, and whether the figures played
# (counters named fig_*) are the same.
#
#   bench/compare_revisions.sh BASE [BENCH_TARGET...]     (default target: sandpaper_bench_tick)
#   e.g. bench/compare_revisions.sh 659b60d               the 2-D tick before the 3-D room
#        bench/compare_revisions.sh HEAD                  the current tree against its own commit: the noise floor
#
# How: a git worktree of BASE in a temporary directory (removed on exit, failure and Ctrl-C
# included) gets the current tree's bench/ sources (the harness is the same on both sides; only the
# code it links differs, so a bench source must build against BASE's headers too), is configured as
# the release preset is (RelWithDebInfo, warnings as errors, CMake's default generator) but with
# only what the benchmarks need (no tests, curation, LSP, glTF, studio, experiments, Python, USB lab
# or shapes), and its targets are built; the current tree is built with the same options in
# $CURRENT_BUILD_DIR (default build-compare/, kept between runs; point it at an existing build, e.g.
# build/, to reuse that one instead). Builds and configures hold /tmp/build.lock (flock) when that
# file exists. Times compared are CPU times (cpu_time), which a shared machine disturbs less than
# wall time; each side's median is over every repetition of every round.
#
# Needs: git, cmake (>= 3.25), a C++20 compiler, the project's build dependencies (tools/install-deps.sh;
# Google Benchmark among them), python3, util-linux flock.
# Takes (2 cores, measured 2026-11-30): 3-7 min to configure and build BASE's schema, calibration,
# compiler and runtime from scratch (every run) and what changed in build-compare/ (the first run,
# both from scratch and waiting for the lock, took 14 min), then a warm-up and ROUNDS x 2 runs of
# ~15 s each with the default target and settings: 5.5-9.5 min in all for 5 rounds.
# "Current" is the working tree as it is, uncommitted changes included.
#
# Settings (environment):
#   ROUNDS=3            rounds; each round runs base, then current
#   REPS=5              --benchmark_repetitions of each run
#   MIN_TIME=0.2        --benchmark_min_time of each repetition, s (5 x 0.2 s x 8 benchmarks, with the
#                       untimed set-up between iterations: ~15 s a run)
#   FILTER=.            --benchmark_filter
#   CURRENT_BUILD_DIR   build directory of the current tree (default <repo>/build-compare)
#   KEEP_JSON=DIR       also copy every run's JSON there
#   PIN_CPU=N           run the benchmarks under taskset -c N (both sides alike)
#   MEASURE_LOCK=1      hold /tmp/build.lock from the first build to the last round, so that no other
#                       build that takes it runs beside the measurement (other load, a fuzzer, still
#                       does); other builds wait that long
#   WARMUP=1            runs of each side before the rounds, short and not counted (0: none)
set -euo pipefail

if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 2
fi
base_rev=$1
shift
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(sandpaper_bench_tick)

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
rounds=${ROUNDS:-3}
reps=${REPS:-5}
min_time=${MIN_TIME:-0.2}
filter=${FILTER:-.}
current_build=${CURRENT_BUILD_DIR:-$root/build-compare}
base_sha=$(git -C "$root" rev-parse --verify "$base_rev^{commit}")
head_sha=$(git -C "$root" rev-parse HEAD)

tmp=$(mktemp -d "${TMPDIR:-/tmp}/sandpaper-compare.XXXXXX")
worktree=$tmp/base
cleanup() {
  local status=$?
  if [[ -d $worktree ]]; then
    git -C "$root" worktree remove --force "$worktree" >/dev/null 2>&1 || true
  fi
  rm -rf "$tmp"
  git -C "$root" worktree prune >/dev/null 2>&1 || true
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

holding_lock=0
locked() {
  if [[ -e /tmp/build.lock && $holding_lock == 0 ]]; then flock /tmp/build.lock "$@"; else "$@"; fi
}
if [[ ${MEASURE_LOCK:-0} == 1 && -e /tmp/build.lock ]]; then
  exec 9>>/tmp/build.lock
  echo "== waiting for /tmp/build.lock, to hold it until the last round"
  flock 9
  holding_lock=1
fi

# The release preset's cache variables, and only the rooms the benchmarks need.
options=(
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSANDPAPER_WARNINGS_AS_ERRORS=ON
  -DSANDPAPER_BUILD_TESTS=OFF -DSANDPAPER_BUILD_BENCH=ON
  -DSANDPAPER_CURATION=OFF -DSANDPAPER_LSP=OFF -DSANDPAPER_GLTF=OFF -DSANDPAPER_STUDIO=OFF
  -DSANDPAPER_EXPERIMENTS=OFF -DSANDPAPER_PYTHON=OFF -DSANDPAPER_USB_LAB=OFF -DSANDPAPER_SHAPES=OFF
  --no-warn-unused-cli
)

started=$(date +%s)
echo "== compare_revisions: base $base_rev ($base_sha), current: the working tree at $head_sha"
echo "== targets: ${targets[*]}; rounds $rounds, repetitions $reps, min time $min_time s, filter '$filter'"
echo "== load before: $(cat /proc/loadavg)"

echo "== base worktree: $worktree"
git -C "$root" worktree add --detach --quiet "$worktree" "$base_sha"
# The same harness on both sides: the current tree's bench sources and bench/CMakeLists.txt.
find "$root/bench" -maxdepth 1 -type f -exec cp {} "$worktree/bench/" \;

echo "== configure and build base"
locked cmake -S "$worktree" -B "$tmp/build-base" "${options[@]}" >"$tmp/configure-base.log" 2>&1 ||
  { tail -30 "$tmp/configure-base.log"; exit 1; }
locked cmake --build "$tmp/build-base" -j2 --target "${targets[@]}" >"$tmp/build-base.log" 2>&1 ||
  { tail -40 "$tmp/build-base.log"; exit 1; }

echo "== configure and build current in $current_build"
if [[ ! -f $current_build/CMakeCache.txt ]]; then
  locked cmake -S "$root" -B "$current_build" "${options[@]}" >"$tmp/configure-current.log" 2>&1 ||
    { tail -30 "$tmp/configure-current.log"; exit 1; }
fi
locked cmake --build "$current_build" -j2 --target "${targets[@]}" >"$tmp/build-current.log" 2>&1 ||
  { tail -40 "$tmp/build-current.log"; exit 1; }
built=$(date +%s)
echo "== built in $((built - started)) s"

bin_of() {  # build dir, target -> the executable
  local f
  for f in "$1/bin/$2" "$1/bench/$2" "$1/$2"; do
    [[ -x $f ]] && { echo "$f"; return; }
  done
  echo "no executable for $2 in $1" >&2
  exit 1
}
runner=()
[[ -n ${PIN_CPU:-} ]] && runner=(taskset -c "$PIN_CPU")

mkdir -p "$tmp/json"
for ((w = 1; w <= ${WARMUP:-1}; ++w)); do
  for dir in "$tmp/build-base" "$current_build"; do
    for target in "${targets[@]}"; do
      "${runner[@]}" "$(bin_of "$dir" "$target")" --benchmark_min_time=0.05 --benchmark_filter="$filter" \
        >/dev/null 2>"$tmp/run.err" || { cat "$tmp/run.err"; exit 1; }
    done
  done
done
echo "== measuring; load at start: $(cat /proc/loadavg)"
for ((round = 1; round <= rounds; ++round)); do
  for side in base current; do
    dir=$tmp/build-base
    [[ $side == current ]] && dir=$current_build
    t0=$(date +%s)
    for target in "${targets[@]}"; do
      "${runner[@]}" "$(bin_of "$dir" "$target")" --benchmark_repetitions="$reps" --benchmark_min_time="$min_time" \
        --benchmark_filter="$filter" --benchmark_out="$tmp/json/$side-$round-$target.json" \
        --benchmark_out_format=json --benchmark_format=console >/dev/null 2>"$tmp/run.err" ||
        { cat "$tmp/run.err"; exit 1; }
    done
    echo "   round $round $side: $(($(date +%s) - t0)) s (load $(cut -d' ' -f1-3 /proc/loadavg))"
  done
done
if [[ $holding_lock == 1 ]]; then flock -u 9; holding_lock=0; fi
if [[ -n ${KEEP_JSON:-} ]]; then mkdir -p "$KEEP_JSON" && cp "$tmp"/json/*.json "$KEEP_JSON/"; fi

python3 - "$tmp/json" "$rounds" <<'PY'
import glob, json, os, statistics, sys
folder, rounds = sys.argv[1], int(sys.argv[2])
# side -> name -> {"t": [cpu times], "rounds": {round: [..]}, "unit": u, "figs": {counter: set}}
data = {"base": {}, "current": {}}
order = []
for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
    side, rnd = os.path.basename(path).split("-")[:2]
    for b in json.load(open(path))["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        if b.get("error_occurred"):
            sys.exit(f"{side}: {b['name']}: {b.get('error_message')}")
        name = b.get("run_name", b["name"])
        if name not in order:
            order.append(name)
        d = data[side].setdefault(name, {"t": [], "rounds": {}, "unit": b["time_unit"], "figs": {}})
        d["t"].append(b["cpu_time"])
        d["rounds"].setdefault(rnd, []).append(b["cpu_time"])
        for k, v in b.items():
            if k.startswith("fig_"):
                d["figs"].setdefault(k, set()).add(v)

def spread(d):
    meds = [statistics.median(v) for v in d["rounds"].values()]
    return 100 * (max(meds) - min(meds)) / statistics.median(d["t"])

def same(a, b):
    return all(abs(x - y) <= 1e-9 * max(1.0, abs(x), abs(y)) for x in a for y in b)

print()
print("CPU time per iteration, median of every repetition of every round; spread: (largest - smallest")
print("round median) / median, per side; figures: the fig_* counters played, base against current.")
print()
w = max(len(n) for n in order)
print(f"| {'benchmark':<{w}} | {'base':>12} | {'current':>12} | {'current/base':>12} | {'spread base':>11} | {'spread cur.':>11} | figures |")
print(f"|{'-' * (w + 2)}|{'-' * 14}|{'-' * 14}|{'-' * 14}|{'-' * 13}|{'-' * 13}|---------|")
differ = []
for name in order:
    b, c = data["base"].get(name), data["current"].get(name)
    if not b or not c:
        print(f"| {name:<{w}} | {'-' if not b else 'only base':>12} | {'-' if not c else 'only current':>12} | | | | |")
        continue
    mb, mc = statistics.median(b["t"]), statistics.median(c["t"])
    figs = "none"
    if b["figs"] or c["figs"]:
        keys = set(b["figs"]) | set(c["figs"])
        bad = [k for k in sorted(keys) if k not in b["figs"] or k not in c["figs"] or not same(b["figs"][k], c["figs"][k])]
        figs = "same" if not bad else "DIFFER"
        differ += [(name, k, sorted(b["figs"].get(k, [])), sorted(c["figs"].get(k, []))) for k in bad]
    print(f"| {name:<{w}} | {mb:>9.4g} {b['unit']:<2} | {mc:>9.4g} {c['unit']:<2} | {mc / mb:>12.3f} | "
          f"{spread(b):>10.1f}% | {spread(c):>10.1f}% | {figs:<7} |")
for name, k, vb, vc in differ:
    print(f"figures differ: {name} {k}: base {vb} current {vc}")
print()
print("Round medians (base / current), in the table's units:")
for name in order:
    b, c = data["base"].get(name), data["current"].get(name)
    if not b or not c:
        continue
    fmt = lambda d: " ".join(f"{statistics.median(d['rounds'][r]):.4g}" for r in sorted(d["rounds"], key=int))
    print(f"  {name:<{w}}  {fmt(b)}  /  {fmt(c)}")
PY
echo
echo "== load after: $(cat /proc/loadavg)"
echo "== took $(($(date +%s) - started)) s (builds $((built - started)) s)"
