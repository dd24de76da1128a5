#!/usr/bin/env bash
# An entry saved in place (the file rewritten, its folder's time kept, as an editor that writes in
# place leaves it) after the index was built: show, search and near answer with what the file says
# now, and say that they updated the index, rather than with the index's old value.
# Usage: stale_query_test.sh path/to/sandpaper tests/curation/data/mini
set -uo pipefail
sp=$1
mini=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fails=$((fails + 1)); }
cp -r "$mini" "$tmp/lib"
# Every file and folder an hour old, so that no stamp the index takes is within its racy window
# (a file that new is always re-read, and the cheap check would see the edit anyway).
find "$tmp/lib" -exec touch -d '1 hour ago' {} +
"$sp" library index --library "$tmp/lib" --quiet >/dev/null 2>&1 || bad "the index builds"

# Rewrites ribbed-cloth.hmat in place with another roughness; the folder keeps its time.
save_in_place() {
  local file="$tmp/lib/textiles/ribbed-cloth.hmat"
  local dir_time
  dir_time=$(stat -c %y "$tmp/lib/textiles")
  sed "s/^\( *roughness \)[0-9.]*/\1$1/" "$file" >"$tmp/next"
  cat "$tmp/next" >"$file"
  touch -d "$dir_time" "$tmp/lib/textiles"
}

save_in_place 0.61
out=$("$sp" library show ribbed-cloth --library "$tmp/lib" --json 2>"$tmp/err")
r=$(python3 -c 'import json,sys; print(round(json.load(sys.stdin)["compiled_roughness"], 6))' <<<"$out")
[ "$r" = 0.61 ] && ok "show answers with the saved roughness (0.61)" || bad "show answered $r, not 0.61"
grep -q "changed since its index was built" "$tmp/err" && ok "show says the index was updated" || bad "show said: $(cat "$tmp/err")"

save_in_place 0.3
out=$("$sp" library search ribbed --library "$tmp/lib" 2>"$tmp/err")
grep -Eq '^ribbed-cloth +textiles +roughness 0.3 ' <<<"$out" && ok "search answers with the saved roughness (0.3)" || bad "search: $out"
grep -q "changed since its index was built" "$tmp/err" && ok "search says the index was updated" || bad "search said: $(cat "$tmp/err")"

save_in_place 0.5
out=$("$sp" library near ribbed-cloth --library "$tmp/lib" --json 2>"$tmp/err")
grep -q "changed since its index was built" "$tmp/err" && ok "near says the index was updated" || bad "near said: $(cat "$tmp/err")"
out=$("$sp" library show ribbed-cloth --library "$tmp/lib" --json 2>"$tmp/err")
r=$(python3 -c 'import json,sys; print(round(json.load(sys.stdin)["compiled_roughness"], 6))' <<<"$out")
[ "$r" = 0.5 ] && [ ! -s "$tmp/err" ] && ok "then the index is fresh: show answers 0.5 and says nothing" || bad "show: $r, $(cat "$tmp/err")"
exit $((fails > 0))
