#!/usr/bin/env bash
# Runs one fuzz target (fuzz/<target>_fuzz.cpp) for a while: tools/fuzz.sh TARGET SECONDS [JOBS]
#
# Builds the `fuzz` preset (clang, libFuzzer, ASan + UBSan) into build-fuzz/ if needed, then fuzzes
# a working corpus, build-fuzz/corpus/TARGET/, seeded from fuzz/corpus/TARGET/ (new seeds are added,
# nothing is removed), with the target's dictionary from fuzz/dict/. Crashes, leaks, timeouts and
# out-of-memory inputs go to build-fuzz/findings/TARGET/; libFuzzer's output to build-fuzz/logs/.
# Prints executions and coverage, and appends one line per run to build-fuzz/fuzz-log.tsv:
#   date  target  seconds (as run)  execs  cov  ft  crashes  slow units
# Crashes are the run's findings (crash, leak, timeout, out-of-memory, broken invariant). A slow unit
# (over 10 s, libFuzzer's -report_slow_units) is saved beside them as slow-unit-*, but the run goes
# on and it is not counted as a finding: it is a lead to a timeout, read as such.
# JOBS > 1, or FUZZ_KEEP_GOING=1, runs libFuzzer's fork mode with JOBS workers, which keeps going
# after a crash, leak, timeout or out-of-memory (each still lands in findings/); otherwise the run
# stops at the first one.
#
# Environment: FUZZ_NO_BUILD=1 skips the build step; TMPDIR (default /dev/shm) holds the run's scratch
# folder; FUZZ_NICE (default 10) is the nice level;
# SANDPAPER_FUZZ_KNOWN names known defects to step over (fuzz/fuzz_support.hpp); FUZZ_ARGS adds
# libFuzzer flags. A saved crash replays with build-fuzz/bin/TARGET_fuzz FILE, and in the normal
# build as a test once copied to fuzz/regressions/TARGET/.
set -euo pipefail

usage() { echo "usage: tools/fuzz.sh TARGET SECONDS [JOBS]   (targets: fuzz/*_fuzz.cpp)" >&2; exit 2; }
[[ $# -ge 2 && $# -le 3 ]] || usage
target=$1 seconds=$2 jobs=${3:-1}
[[ $seconds =~ ^[0-9]+$ && $jobs =~ ^[1-9][0-9]*$ ]] || usage

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[[ -f $root/fuzz/${target}_fuzz.cpp ]] || { echo "fuzz.sh: no target '$target' (fuzz/${target}_fuzz.cpp)" >&2; exit 2; }
build=$root/build-fuzz

if [[ ${FUZZ_NO_BUILD:-0} != 1 ]]; then
  cd "$root"
  [[ -f $build/CMakeCache.txt ]] || cmake --preset fuzz
  # One build at a time on a shared machine: the same lock every build here takes.
  flock /tmp/build.lock cmake --build --preset fuzz --target "${target}_fuzz"
fi
bin=$build/bin/${target}_fuzz
[[ -x $bin ]] || { echo "fuzz.sh: $bin was not built" >&2; exit 2; }

# Largest input per target: text readers 4 KB (a material is a few lines; longer only slows the
# search), results folders, calibration files and images 16 KB (a whole small session; the knowledge
# file; a small height map, or a header claiming a huge one),
# binary files 64 KB (small patch programs; a catalog record, 20 KB with two entries). libFuzzer cuts
# every seed to this length, so it must be at least the largest seed in fuzz/corpus/TARGET (checked
# below): a cut SQLite file or TOML table only tests the reader's first page.
case $target in
  patch|workspace_program|array|gltf|gltf_scene|catalog_record) max_len=65536 ;;
  experiment_results|lsp_message|calibration|calibration_set|image) max_len=16384 ;;
  *) max_len=4096 ;;
esac
for seed in "$root/fuzz/corpus/$target"/*; do
  [[ -f $seed ]] || continue
  size=$(stat -c %s "$seed")
  [[ $size -le $max_len ]] || { echo "fuzz.sh: seed $seed is $size bytes, over max_len $max_len for $target" >&2; exit 2; }
done
case $target in
  material) dict=material ;;
  workspace) dict=workspace ;;
  patch|workspace_program) dict='patch' ;;
  calibration|calibration_set|experiment_design) dict=toml ;;
  movie|shuffle) dict=movie ;;
  trace_csv) dict=trace_csv ;;
  studio_request) dict=studio_request ;;
  experiment_results) dict=experiment_results ;;
  lsp_message) dict=lsp_message ;;
  image) dict=image ;;
  hid_descriptor) dict=hid_descriptor ;;
  calibration_csv) dict=calibration_csv ;;
  page_answer) dict=page_answer ;;
  scene_program) dict=scene_program ;;
  scene_file) dict=scene_file ;;
  gltf_scene) dict=gltf_scene ;;
  *) dict= ;;
esac

corpus=$build/corpus/$target findings=$build/findings/$target logs=$build/logs
mkdir -p "$corpus" "$findings" "$logs"
cp -n "$root/fuzz/corpus/$target"/* "$corpus"/ 2>/dev/null || true
stamp=$(date -u +%Y%m%dT%H%M%SZ)
log=$logs/$target-$stamp-$$.log  # the PID too: two runs started in one second would share a log
marker=$(mktemp)  # findings newer than this are this run's

args=(-max_total_time="$seconds" -max_len="$max_len" -print_final_stats=1 -timeout=25 -rss_limit_mb=2048
      -artifact_prefix="$findings/")
[[ -n $dict ]] && args+=(-dict="$root/fuzz/dict/$dict.dict")
[[ $jobs -gt 1 || ${FUZZ_KEEP_GOING:-0} == 1 ]] && args+=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
# shellcheck disable=SC2206
args+=(${FUZZ_ARGS:-})

# Each input goes through a scratch file (fuzz/fuzz_support.hpp, under TMPDIR): in memory, not on
# disk, where there is one (1.5x the executions per second of /tmp on disk, measured 2026-11-24).
# A folder of this run's own, removed at the end: a fuzzer stopped by its time limit exits without
# removing its scratch files, and in /dev/shm they would hold memory until the machine restarts.
shm_base=${TMPDIR:-}
if [[ -z $shm_base && -d /dev/shm && -w /dev/shm ]]; then shm_base=/dev/shm; fi
scratch=$(mktemp -d "${shm_base:-/tmp}/sandpaper-fuzz-run.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
export TMPDIR=$scratch

# Leaks of the libraries read through, each explained in the file (docs/RELIABILITY.md, F17).
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

# Relative image paths in material text resolve here (fuzz/CMakeLists.txt, SANDPAPER_FUZZ_WORKDIR).
cd "$root/tests/golden/diagnostics"
echo "fuzz.sh: $target for ${seconds}s, jobs $jobs, log $log" >&2
status=0
started=$(date +%s)
nice -n "${FUZZ_NICE:-10}" "$bin" "${args[@]}" "$corpus" >"$log" 2>&1 || status=$?

# Executions: libFuzzer's final stats (stat::number_of_executed_units) in the default mode; in fork
# mode, the count on its last status line ("#N: cov: ..."). Coverage: cov/ft of the last status line.
execs=$(awk '/stat::number_of_executed_units:/ {n=$2} END {print n}' "$log")
last=$(grep -E '^#[0-9]+:?[[:space:]].*cov: ' "$log" | tail -1 || true)
[[ -z $execs ]] && execs=$(sed -E 's/^#([0-9]+).*/\1/' <<<"$last")
cov=$(sed -nE 's/.*cov: ([0-9]+).*/\1/p' <<<"$last")
ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
new_findings=$(find "$findings" -type f -newer "$marker" ! -name 'slow-unit-*')
crashes=$(grep -c . <<<"$new_findings" || true)
new_slow=$(find "$findings" -type f -newer "$marker" -name 'slow-unit-*')
slow=$(grep -c . <<<"$new_slow" || true)
rm -f "$marker"
elapsed=$(( $(date +%s) - started ))  # less than SECONDS when the run stopped at a finding

printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$stamp" "$target" "$elapsed" "${execs:-0}" "${cov:-0}" "${ft:-0}" \
  "$crashes" "$slow" >>"$build/fuzz-log.tsv"
echo "target $target: ${elapsed}s, ${execs:-0} executions, cov ${cov:-0}, ft ${ft:-0}, ${crashes} finding(s), ${slow} slow unit(s) in $findings (libFuzzer exit $status)"
[[ $slow -gt 0 ]] && echo "$new_slow"
if [[ $crashes -gt 0 ]]; then
  echo "$new_findings"
  grep -E '^(==[0-9]+==ERROR|SUMMARY|fuzz invariant broken|.*runtime error:)' "$log" | head -5 || true
fi
exit 0
