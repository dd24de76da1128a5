#!/usr/bin/env bash
# The library's tools at scale (issue 18): for each N, writes a generated library of N entries
# (tools/library_gen.py) into a temporary folder and times, with peak memory:
#   library check --quiet           every entry on every device, names, cycles, JND collisions
#   library index --quiet           full build into a fresh <library>/.index/
#   library index --quiet           again, nothing changed
#   library index --quiet           after appending a comment line to one entry
#   library search WORD             a word in a few entries' describes (default corduroy: five)
#   library show NAME / near NAME   one generated grating
#   in-process queries              build/bin/sandpaper_bench_library (staleness check, search, show,
#                                   near, each with opening the index), when built beside the binary
#   library catalog -o DIR --quiet  and the catalog's size (du -sb) and bytes per entry
# and `sandpaper --help` (median of 5) as the process start-up, so that the queries can be read
# net of it. Prints a Markdown table (one row per N) and, with two or more N, the growth exponent
# between neighbouring N (log t2/t1 / log N2/N1: 1 is linear, 0 flat) to stdout; raw per-command
# lines to stderr.
#
#   bench/library_scale.sh [SANDPAPER_BIN] [N...]      (default build/bin/sandpaper; 1000 10000 100000)
#
# Environment:
#   LIBRARY_SCALE_SKIP=catalog,check  steps to leave out: check, index, index-unchanged,
#                                     index-touched, search, show, near, inprocess, catalog
#   LIBRARY_SCALE_TIMEOUT=3600        seconds per step; a step that runs out shows ">timeout"
#   LIBRARY_SCALE_REPEAT=3            runs of each query (search, show, near); the median is shown
#   LIBRARY_SCALE_QUERY=corduroy      the search words
#   LIBRARY_SCALE_SEED=1              tools/library_gen.py --seed
#   LIBRARY_SCALE_TMP=$TMPDIR|/tmp    where the temporary libraries and catalogs go
#   LIBRARY_SCALE_KEEP=1              keep them (their path is printed on stderr)
# Timing on a shared machine is noisy: run it when nothing else is building (and `nice` it when
# something is).
set -uo pipefail
export LC_ALL=C

root=$(cd "$(dirname "$0")/.." && pwd)
bin="$root/build/bin/sandpaper"
if [[ $# -gt 0 && ! $1 =~ ^[0-9]+$ ]]; then bin=$1; shift; fi
sizes=("$@")
[[ ${#sizes[@]} -eq 0 ]] && sizes=(1000 10000 100000)
for n in "${sizes[@]}"; do
  [[ $n =~ ^[1-9][0-9]*$ ]] || { echo "library_scale: N must be a positive whole number, not '$n'" >&2; exit 2; }
done
[[ -x $bin ]] || { echo "library_scale: $bin is not an executable (give the sandpaper binary first)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "library_scale: needs GNU time at /usr/bin/time (apt-get install time)" >&2; exit 2; }
command -v timeout >/dev/null || { echo "library_scale: needs timeout (coreutils)" >&2; exit 2; }

skip=",${LIBRARY_SCALE_SKIP:-},"
limit=${LIBRARY_SCALE_TIMEOUT:-3600}
repeat=${LIBRARY_SCALE_REPEAT:-3}
query=${LIBRARY_SCALE_QUERY:-corduroy}
seed=${LIBRARY_SCALE_SEED:-1}
tmproot=${LIBRARY_SCALE_TMP:-${TMPDIR:-/tmp}}
gen="$root/tools/library_gen.py"

work=$(mktemp -d "$tmproot/library_scale.XXXXXX") || exit 2
if [[ -n ${LIBRARY_SCALE_KEEP:-} ]]; then
  echo "library_scale: keeping $work" >&2
else
  trap 'rm -rf "$work"' EXIT
fi
trap 'exit 130' INT TERM

skipped() { [[ $skip == *",$1,"* ]]; }

# run LABEL CMD...: runs CMD with the step timeout; sets WALL (s), RSS (KB), RC, OUT and ERR (files).
run() {
  local label=$1; shift
  OUT="$work/$label.out" ERR="$work/$label.err"
  local tf="$work/$label.time" t0 t1
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$tf" timeout -k 10 "$limit" "$@" >"$OUT" 2>"$ERR"
  RC=$?
  t1=$EPOCHREALTIME
  WALL=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  RSS=$(tail -n 1 "$tf" 2>/dev/null)
  [[ $RSS =~ ^[0-9]+$ ]] || RSS=0
  echo "N=$N step=$label rc=$RC wall=${WALL}s rss=${RSS}KB cmd=$*" >&2
}

median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
mb() { awk -v k="$1" 'BEGIN { printf "%.0f MB", k / 1024 }'; }
human() {  # bytes
  awk -v b="$1" 'BEGIN { split("B KB MB GB TB", u); i = 1; while (b >= 1000 && i < 5) { b /= 1000; i++ }
                        printf (i == 1 ? "%d %s" : "%.3g %s"), b, u[i] }'
}

declare -A cell secs   # cell[N:step] = table text; secs[N:step] = wall seconds (for growth)

# A timed step: the cell says the time and the peak memory, or >timeout, or the exit status.
step() {
  local label=$1; shift
  if skipped "$label"; then cell[$N:$label]="skipped"; return 1; fi
  run "$label" "$@"
  if [[ $RC -eq 124 || $RC -eq 137 ]]; then cell[$N:$label]=">timeout (${limit} s)"; return 1; fi
  secs[$N:$label]=$WALL
  cell[$N:$label]="$WALL s, $(mb "$RSS")"
  if [[ $RC -ne 0 ]]; then
    cell[$N:$label]+=" (exit $RC)"
    echo "library_scale: N=$N $label exited $RC; its stderr ends:" >&2
    tail -n 5 "$ERR" | sed 's/^/    /' >&2
  fi
  return 0
}

# A query: median of $repeat runs, also shown net of the process start-up.
query_step() {
  local label=$1; shift
  if skipped "$label"; then cell[$N:$label]="skipped"; return; fi
  local walls=() rsss=() i rc=0
  for ((i = 0; i < repeat; i++)); do
    run "$label" "$@"
    if [[ $RC -eq 124 || $RC -eq 137 ]]; then cell[$N:$label]=">timeout (${limit} s)"; return; fi
    [[ $RC -ne 0 ]] && rc=$RC
    walls+=("$WALL") rsss+=("$RSS")
  done
  local w r
  w=$(median "${walls[@]}")
  r=$(median "${rsss[@]}")
  secs[$N:$label]=$w
  cell[$N:$label]="$w s (net $(awk -v w="$w" -v s="$startup" 'BEGIN { printf "%.3f", w - s }')), $(mb "$r")"
  if [[ $rc -ne 0 ]]; then
    cell[$N:$label]+=" (exit $rc)"
    echo "library_scale: N=$N $label exited $rc; its stderr ends:" >&2
    tail -n 5 "$ERR" | sed 's/^/    /' >&2
  fi
}

# Process start-up: the median of 5 runs of --help (no library is read).
N=0
walls=()
for i in 1 2 3 4 5; do run startup "$bin" --help; walls+=("$WALL"); done
startup=$(median "${walls[@]}")
startup_rss=$RSS

for N in "${sizes[@]}"; do
  lib="$work/lib-$N" cat_dir="$work/catalog-$N"
  run generate python3 "$gen" "$N" "$lib" --seed "$seed"
  if [[ $RC -ne 0 ]]; then
    echo "library_scale: tools/library_gen.py failed for N=$N:" >&2
    cat "$ERR" >&2
    exit 1
  fi
  cell[$N:generate]="$WALL s"
  secs[$N:generate]=$WALL
  cell[$N:library]=$(human "$(find "$lib" -name '*.hmat' -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }')")
  width=$(( ${#N} > 6 ? ${#N} : 6 ))
  name=$(printf 'gen-grating-%0*d' "$width" 1)
  touched=$(printf '%s/gen-gratings/000/gen-grating-%0*d.hmat' "$lib" "$width" 2)
  [[ -f $touched ]] || touched="$lib/gen-gratings/000/gen-reference.hmat"
  common=(--library "$lib")

  # check: diagnostics go to stderr; at most 200 warnings are printed, then a W0009 line with the rest.
  if step check "$bin" library check "${common[@]}" --quiet; then
    errors=$(grep -c ': error\[' "$ERR")
    warnings=$(grep ': warning\[' "$ERR" | grep -vc 'warning\[W0009\]')
    more=$(sed -n 's/.*warning\[W0009\]: too many warnings: \([0-9]*\) more.*/\1/p' "$ERR" | head -n 1)
    warnings=$((warnings + ${more:-0}))
    kinds=$(grep -o ': warning\[W[0-9]*\]' "$ERR" | grep -v W0009 | sort | uniq -c | awk '{ gsub(/[^A-Z0-9]/, "", $2); printf "%s%s", (NR > 1 ? " " : ""), $2 }')
    cell[$N:diags]="$errors E, $warnings W${kinds:+ ($kinds)}"
  else
    cell[$N:diags]="-"
  fi

  rm -rf "$lib/.index"
  step index "$bin" library index "${common[@]}" --quiet
  step index-unchanged "$bin" library index "${common[@]}" --quiet
  echo "# touched by bench/library_scale.sh" >>"$touched"
  step index-touched "$bin" library index "${common[@]}" --quiet
  if [[ -f $lib/.index/library.sqlite ]]; then
    cell[$N:index-size]=$(human "$(stat -c %s "$lib/.index/library.sqlite")")
  else
    cell[$N:index-size]="-"
  fi

  read -ra words <<<"$query"
  query_step search "$bin" library search "${common[@]}" --quiet "${words[@]}"
  [[ -n ${secs[$N:search]:-} ]] && echo "N=$N search '$query' found $(wc -l <"$OUT") lines" >&2
  query_step show "$bin" library show "${common[@]}" --quiet "$name"
  query_step near "$bin" library near "${common[@]}" --quiet "$name"
  # In-process (no start-up): bench/library_query_bench.cpp, when built beside the binary.
  qbench="$(dirname "$bin")/sandpaper_bench_library"
  if [[ -x $qbench ]] && ! skipped inprocess; then
    run inprocess env SANDPAPER_BENCH_INDEX="$lib/.index/library.sqlite" SANDPAPER_BENCH_LIBRARY="$lib" \
      SANDPAPER_BENCH_NAME="$name" SANDPAPER_BENCH_QUERY="$query" "$qbench" --benchmark_min_time=0.2
    cell[$N:inprocess]=$(awk '/^BM_Library/ { sub("BM_Library", "", $1); printf "%s%s %s %s", (n++ ? ", " : ""), $1, $2, $3 }' "$OUT")
    [[ -n ${cell[$N:inprocess]} ]] || cell[$N:inprocess]="(exit $RC)"
  else
    cell[$N:inprocess]="-"
  fi

  if step catalog "$bin" library catalog "${common[@]}" -o "$cat_dir" --quiet && [[ -d $cat_dir ]]; then
    bytes=$(du -sb "$cat_dir" | cut -f1)
    cell[$N:catalog-size]=$(human "$bytes")
    cell[$N:per-entry]=$(human $((bytes / N)))
    rm -rf "$cat_dir"
  else
    cell[$N:catalog-size]="-" cell[$N:per-entry]="-"
  fi
  [[ -n ${LIBRARY_SCALE_KEEP:-} ]] || rm -rf "$lib"
done

# The table.
cols=(generate library check diags index index-unchanged index-touched index-size search show near inprocess catalog catalog-size per-entry)
heads=("generate" "library (.hmat bytes)" "check" "check diagnostics" "index (full)" "index (unchanged)"
       "index (1 entry touched)" "index size" "search '$query'" "show" "near" "in-process, no start-up" "catalog" "catalog size" "catalog per entry")
echo
echo "sandpaper: \`$bin\`; process start-up (\`--help\`, median of 5): $startup s, $(mb "$startup_rss"). Queries: median of $repeat runs, (net) = less start-up. Times are wall-clock, memory is peak RSS."
echo
line="| N |"; sep="|---:|"
for h in "${heads[@]}"; do line+=" $h |"; sep+="---|"; done
echo "$line"; echo "$sep"
for N in "${sizes[@]}"; do
  line="| $N |"
  for c in "${cols[@]}"; do line+=" ${cell[$N:$c]:--} |"; done
  echo "$line"
done

if [[ ${#sizes[@]} -gt 1 ]]; then
  timed=(generate check index index-unchanged index-touched search show near catalog)
  echo
  echo "Growth: exponent b of time ~ N^b between neighbouring N (1 linear, 0 independent of N; queries gross of start-up)."
  echo
  line="| from N | to N |"; sep="|---:|---:|"
  for c in "${timed[@]}"; do line+=" $c |"; sep+="---:|"; done
  echo "$line"; echo "$sep"
  for ((i = 1; i < ${#sizes[@]}; i++)); do
    a=${sizes[i - 1]} b=${sizes[i]}
    line="| $a | $b |"
    for c in "${timed[@]}"; do
      ta=${secs[$a:$c]:-} tb=${secs[$b:$c]:-}
      if [[ -n $ta && -n $tb ]]; then
        line+=" $(awk -v ta="$ta" -v tb="$tb" -v na="$a" -v nb="$b" 'BEGIN { if (ta <= 0 || tb <= 0) print "-"; else printf "%.2f", log(tb / ta) / log(nb / na) }') |"
      else
        line+=" - |"
      fi
    done
    echo "$line"
  done
fi
