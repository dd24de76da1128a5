#!/usr/bin/env bash
# `library review` and `library check` as a contributor runs them (docs/LIBRARY.md, "Which library"):
# in a clone of a library's repository, on a branch with planted defects, with no --library. They
# judge the library of the folder they run in, never the one the program was built with; from a
# folder with no library above it they refuse (exit 2) and say what to do. On a fresh clone (no
# .index), a clash of names is the newcomer's: git says which entry came first.
#   contributor_clone_test.sh SANDPAPER MINI_LIBRARY SHIPPED_LIBRARY
set -uo pipefail
sp=$(realpath "$1") mini=$(realpath "$2") shipped=$(realpath "$3")
tmp=$(realpath "$(mktemp -d)")
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
g() { git -c user.name=clone-test -c user.email=clone-test@example.invalid -c commit.gpgsign=false "$@"; }
# The variables a user may have set for compiling must not choose what check and review judge.
export SANDPAPER_LIBRARY_PATH="$shipped" SANDPAPER_LIBRARY="$shipped"

# The library's own repository: the library is the top of it, as the world library's would be.
mkdir -p "$tmp/origin"
cp -r "$mini/." "$tmp/origin/"
(cd "$tmp/origin" && g init -q -b main && g add -A && g commit -qm "the library") || bad "the origin repository"
g clone -q "$tmp/origin" "$tmp/clone" || bad "git clone"
[ ! -e "$tmp/clone/.index" ] && ok || bad "a fresh clone has no index (the premise)"
cd "$tmp/clone" && g checkout -q -b six-defects || bad "the branch"

entry() {  # entry FILE NAME BODY...: an entry of family textiles with a licence unless BODY says one
  local file=$1 name=$2
  shift 2
  { printf 'material "%s" {\n  describes "a planted defect"\n  family textiles\n' "$name"; printf '%s\n' "$@"; printf '}\n'; } >"$file"
}
# 1. A name already taken, by a file that sorts before the established one (E0607).
sed 's/^  describes .*/  describes "a second fine-rib"/' textiles/fine-rib.hmat >abrasives/fine-rib.hmat
# 2. A number without a source (E0606).
entry textiles/unsourced.hmat unsourced '  licence "CC0-1.0"' '  grating period 4 mm' '  roughness 0.3' '  source by-ear "x"'
# 3. A licence that is not an SPDX expression (E0605).
entry textiles/badlicence.hmat badlicence '  licence "CC0-1.0 and MIT"' '  grating period 5 mm' '  source by-ear "x"' \
  '  roughness 0.3' '  source by-ear "x"'
# 4. An image without its licence and credit (E0615).
mkdir -p images
cp "$shipped/images/gravel.png" images/gravel.png
entry textiles/unlicensed.hmat unlicensed '  licence "CC0-1.0"' '  heightmap "../images/gravel.png" size 6 mm' '  source by-ear "x"' \
  '  roughness 0.6' '  source by-ear "x"' '  accept W0304 "a photograph"'
# 5. An image that leads outside the library through a link (E0612).
mkdir -p "$tmp/outside"
printf 'P2\n2 2\n255\n0 255\n255 0\n' >"$tmp/outside/x.pgm"
ln -s "$tmp/outside/x.pgm" images/linked.pgm
entry textiles/linked.hmat linked '  licence "CC0-1.0"' '  heightmap "../images/linked.pgm" size 10 mm' '  source by-ear "x"' \
  '  roughness 0.4' '  source by-ear "x"'
# 6. A new warning the entry does not accept: a fine grating read weaker at 100 mm/s (W0350).
entry textiles/finer.hmat finer '  licence "CC0-1.0"' '  grating period 1.2 mm hill 50%' '  source by-ear "x"' \
  '  roughness 0.3' '  source by-ear "x"'
g add -A && g commit -qm "six planted defects" || bad "committing the defects"

# From the clone's top, and from a folder inside it: the clone's library is the one judged, with its
# 8 changed files (6 entries, 2 images).
for where in . textiles; do
  (cd "$where" && "$sp" library review --base main --quiet) >"$tmp/review.out" 2>"$tmp/review.err"
  rc=$?
  [ "$rc" -eq 1 ] && ok || bad "review from $where: exit $rc, wanted 1: $(cat "$tmp/review.out" "$tmp/review.err" | head -20)"
  grep -q "^review of $tmp/clone against main: 8 changed files" "$tmp/review.out" && ok \
    || bad "review from $where: not the clone's library, or not its changes: $(head -3 "$tmp/review.out")"
  for code in E0607 E0606 E0605 E0615 E0612 W0350; do
    grep -q "\[$code\]" "$tmp/review.err" && ok || bad "review from $where: the planted $code is not found"
  done
  (cd "$where" && "$sp" library check --quiet) >"$tmp/check.out" 2>"$tmp/check.err"
  rc=$?
  [ "$rc" -eq 1 ] && ok || bad "check from $where: exit $rc, wanted 1: $(head -20 "$tmp/check.err")"
  for code in E0607 E0606 E0605 E0615 E0612 W0350; do
    grep -q "\[$code\]" "$tmp/check.err" && ok || bad "check from $where: the planted $code is not found"
  done
done

# The fresh clone has no index: git says textiles/fine-rib.hmat came first, so the newcomer is told
# to rename, not the established entry's owner (whose file sorts later in path order).
"$sp" library check --library "$tmp/clone" --quiet >/dev/null 2>"$tmp/clash.err"
grep -Eq "abrasives/fine-rib\.hmat:1:10: error\[E0607\]: name 'fine-rib' is already the name of textiles/fine-rib\.hmat" "$tmp/clash.err" \
  && ok || bad "a fresh clone's check blames the established entry: $(grep -A1 E0607 "$tmp/clash.err")"
if grep -q "textiles/fine-rib.hmat:1:10: error\[E0607\]" "$tmp/clash.err"; then bad "the established entry is told to rename"; else ok; fi
# Work not committed yet is newer than anything committed, whatever its path.
g checkout -q main && g checkout -q -b uncommitted
sed 's/^  describes .*/  describes "a second fine-rib"/' textiles/fine-rib.hmat >abrasives/fine-rib.hmat
"$sp" library check --library "$tmp/clone" --quiet >/dev/null 2>"$tmp/clash2.err"
grep -q "abrasives/fine-rib.hmat:1:10: error\[E0607\]" "$tmp/clash2.err" && ok \
  || bad "an uncommitted newcomer is not the one blamed: $(grep E0607 "$tmp/clash2.err")"
rm abrasives/fine-rib.hmat
g checkout -q six-defects

# From a folder with no library.toml above it: exit 2, and say how to name the library.
mkdir -p "$tmp/nowhere/deeper"
for cmd in "review --base main" check; do
  (cd "$tmp/nowhere/deeper" && "$sp" library $cmd --quiet) >"$tmp/none.out" 2>"$tmp/none.err"
  rc=$?
  [ "$rc" -eq 2 ] && ok || bad "library $cmd with no library here: exit $rc, wanted 2: $(cat "$tmp/none.out" "$tmp/none.err" | head -5)"
  grep -q "no library here" "$tmp/none.err" && grep -q -- "--library DIR" "$tmp/none.err" && grep -q "cd into the library" "$tmp/none.err" \
    && ok || bad "library $cmd with no library here: the message: $(cat "$tmp/none.err")"
done
# Nor in a git repository without one (its top has no library/ either).
mkdir -p "$tmp/otherrepo/src" && (cd "$tmp/otherrepo" && g init -q -b main)
(cd "$tmp/otherrepo/src" && "$sp" library check --quiet) >/dev/null 2>"$tmp/none.err"
[ $? -eq 2 ] && ok || bad "check in a repository with no library: $(cat "$tmp/none.err")"
# A repository that keeps its library in library/ (as Sandpaper's own does): found from its top.
mkdir -p "$tmp/withlib" && cp -r "$mini" "$tmp/withlib/library" && (cd "$tmp/withlib" && g init -q -b main && g add -A && g commit -qm base)
(cd "$tmp/withlib" && "$sp" library review --base main --quiet) >"$tmp/withlib.out" 2>&1
grep -q "^review of $tmp/withlib/library against main: 0 changed files" "$tmp/withlib.out" && ok \
  || bad "review at the top of a repository with library/: $(cat "$tmp/withlib.out")"

# Progress on a terminal: the counter counts to the number of entries (not "6/0") and is cleared
# before the review's summary, which starts a line of its own.
if command -v script >/dev/null; then
  script -qec "$(printf '%q ' "$sp" library review --library "$tmp/clone" --base main)" /dev/null </dev/null >"$tmp/tty.raw" 2>&1
  python3 - "$tmp/tty.raw" "$(ls "$tmp"/clone/*/*.hmat | wc -l)" >"$tmp/tty.check" <<'PY'
import re, sys
text = open(sys.argv[1], encoding="utf-8", errors="replace").read()
entries = sys.argv[2]
lines = [l.rstrip("\r").split("\r")[-1] for l in text.split("\n")]  # what a terminal leaves on each line
problems = []
if re.search(r"checking \d+/0\b", text): problems.append("a counter out of 0: " + repr(re.search(r"checking \d+/0\b[^\r\n]*", text).group(0)))
if "checking %s/%s " % (entries, entries) not in text: problems.append("the counter does not reach %s/%s" % (entries, entries))
if not any(l.startswith("review of ") for l in lines): problems.append("the summary does not start a line: " + repr([l for l in lines if "review of" in l]))
print("\n".join(problems) if problems else "ok")
PY
  [ "$(cat "$tmp/tty.check")" = ok ] && ok || bad "progress on a terminal: $(cat "$tmp/tty.check")"
else
  echo "SKIP: no script(1) for a terminal"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
