#!/usr/bin/env bash
# `sandpaper compile FILES... FOLDERS... -o OUT`: many materials in one process.
#   batch_compile_test.sh SANDPAPER SOURCE_DIR
set -u
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# The whole shipped library, one process; the folder structure is kept below OUT.
want=$(find "$src/library" -name '*.hmat' | wc -l)
"$sp" compile "$src/library" -o "$tmp/lib" >"$tmp/out" 2>"$tmp/err"; rc=$?
[ "$rc" -eq 0 ] && ok || bad "library batch: exit $rc: $(tail -3 "$tmp/err")"
got=$(find "$tmp/lib" -name '*.patch' | wc -l)
[ "$got" -eq "$want" ] && ok || bad "library batch wrote $got patches for $want materials"
[ -f "$tmp/lib/woods/cork.patch" ] && ok || bad "library/woods/cork.hmat should land at OUT/woods/cork.patch"
grep -q "compiled $want of $want material(s)" "$tmp/out" && ok || bad "summary: $(cat "$tmp/out")"
"$sp" inspect "$tmp/lib/woods/cork.patch" >/dev/null && ok || bad "a batch-compiled patch does not read back"

# Files and a broken one: the others are written, the broken one is not, exit 1.
cp "$src/examples/corduroy.hmat" "$tmp/a.hmat"
printf 'material "broken" {\n  roughnes 0.5\n}\n' >"$tmp/broken.hmat"
"$sp" compile "$tmp/a.hmat" "$tmp/broken.hmat" -o "$tmp/two" --json >"$tmp/out" 2>"$tmp/err"; rc=$?
[ "$rc" -eq 1 ] && ok || bad "one broken input: exit $rc, wanted 1"
[ -f "$tmp/two/a.patch" ] && ok || bad "the good input was not written"
[ ! -e "$tmp/two/broken.patch" ] && ok || bad "the broken input left a patch"
jq -e '.compiled == 1 and .failed == 1' "$tmp/out" >/dev/null && ok || bad "--json summary: $(cat "$tmp/out")"

# Two inputs that would write the same patch, and no -o: refused before anything is written.
mkdir -p "$tmp/x" && cp "$tmp/a.hmat" "$tmp/x/a.hmat"
"$sp" compile "$tmp/a.hmat" "$tmp/x/a.hmat" -o "$tmp/clash" >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q 'would both write' "$tmp/err" && ok || bad "clashing outputs: exit $rc"
[ ! -e "$tmp/clash" ] && ok || bad "a refused batch wrote something"
"$sp" compile "$tmp/a.hmat" "$tmp/x/a.hmat" >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q 'need -o FOLDER' "$tmp/err" && ok || bad "several inputs without -o: exit $rc"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
