#!/usr/bin/env bash
# tools/library_gen.py writes a valid library: `library check` finds no error in it, every entry
# indexes, the search word the benchmark uses finds its five entries, and one seed gives one
# library, byte for byte (issue 18: the generated scale library of bench/library_scale.sh).
#   generated_library_test.sh SANDPAPER LIBRARY_GEN
set -uo pipefail
sp=$1 gen=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }

python3 "$gen" 60 "$tmp/a" --seed 3 >/dev/null || bad "the generator failed"
python3 "$gen" 60 "$tmp/b" --seed 3 >/dev/null || bad "the generator failed the second time"
diff -r "$tmp/a" "$tmp/b" >/dev/null && ok || bad "one seed gave two libraries"
[ "$(find "$tmp/a" -name '*.hmat' | wc -l)" -eq 60 ] && ok || bad "not 60 entries"
"$sp" library check --library "$tmp/a" --quiet --json >"$tmp/check.json" 2>"$tmp/check.err"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if j["errors"] == 0 and j["entries"] == 60 else 1)' \
  "$tmp/check.json" && ok || { bad "library check found errors"; head -40 "$tmp/check.err"; }
"$sp" library index --library "$tmp/a" --quiet --json >"$tmp/index.json" 2>&1 || bad "library index failed"
grep -q '"compiled": 60' "$tmp/index.json" && ok || bad "not every entry indexed: $(cat "$tmp/index.json")"
[ "$("$sp" library search corduroy --library "$tmp/a" --quiet | wc -l)" -eq 5 ] && ok || bad "search corduroy should find 5"
# Told which file changed (one a line on stdin, as `git diff --name-only` prints them), the index
# updates that entry in place; a file of another folder is refused and changes nothing.
one=""  # an entry nothing is built on
for f in $(find "$tmp/a" -name 'gen-grating-*.hmat' | sort); do
  grep -rqE "^\s*like $(basename "$f" .hmat)\s*$" "$tmp/a" || { one=$f; break; }
done
echo "# edited" >>"$one"
printf '%s\n' "$one" | "$sp" library index --library "$tmp/a" --changed - --quiet --json >"$tmp/changed.json" 2>&1 || bad "--changed failed"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if j["compiled"] == 1 and j["in_place"] else 1)' \
  "$tmp/changed.json" && ok || bad "--changed did not update one entry in place: $(cat "$tmp/changed.json")"
# The catalog takes the same list for its index update, and draws that entry alone.
"$sp" library catalog --library "$tmp/a" -o "$tmp/cat" --quiet >/dev/null 2>&1 || bad "library catalog failed"
echo "# edited again" >>"$one"
out=$("$sp" library catalog --library "$tmp/a" -o "$tmp/cat" --changed "$one" 2>/dev/null)
[[ $out == *"(1 drawn, 59 unchanged, updated in place)"* ]] && ok || bad "catalog --changed: $out"
cp "$tmp/a/.index/library.sqlite" "$tmp/index.before"
"$sp" library index --library "$tmp/a" --changed "$tmp/check.json" --quiet >/dev/null 2>"$tmp/outside.err"
[ $? -eq 2 ] && grep -q "neither the library folder" "$tmp/outside.err" && cmp -s "$tmp/index.before" "$tmp/a/.index/library.sqlite" && ok ||
  bad "a changed file outside the library: $(cat "$tmp/outside.err")"
mkdir -p "$tmp/c" && echo "a curator's notes" >"$tmp/c/notes.txt"
python3 "$gen" 60 "$tmp/c" >/dev/null 2>&1 && bad "wrote into a folder that is not a generated library" || ok
[ -f "$tmp/c/notes.txt" ] && ok || bad "the folder's own file was removed"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
