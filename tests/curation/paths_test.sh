#!/usr/bin/env bash
# One library file is printed the same way by `library check`, `explain`, `library show` and the
# catalog: relative to the working directory (the catalog: to the folder that holds the library),
# for the entry's own lines and for those it inherits through `like`, whatever the library's folder
# is called. Usage: paths_test.sh path/to/sandpaper tests/curation/data/mini
set -uo pipefail
sp=$(realpath "$1")
mini=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fails=$((fails + 1)); }
mkdir -p "$tmp/work"
cp -r "$mini" "$tmp/work/world"
# fine-rib's own grating statement (line 7) and the roughness of the ribbed cloth it is like.
cd "$tmp/work" || exit 1
own="world/textiles/fine-rib.hmat:7:"
inherited="world/textiles/ribbed-cloth.hmat:"
sed -i 's/^  accept W0350.*$//' world/textiles/fine-rib.hmat   # let W0350 be shown (the line stays, empty)

"$sp" library check --library world --quiet >"$tmp/check" 2>&1
grep -q "^${own}[0-9]*: warning\[W0350\]" "$tmp/check" && ok "check: $own" || bad "check: $(head -3 "$tmp/check")"
"$sp" explain -e fine-rib --library world >"$tmp/explain" 2>&1
grep -q "^${own}[0-9]*: warning\[W0350\]" "$tmp/explain" && ok "explain's warning: $own" || bad "explain: $(grep -m2 hmat "$tmp/explain")"
grep -q "(${inherited}[0-9]*:[0-9]*)" "$tmp/explain" && ok "explain's provenance: $inherited" || bad "explain: $(grep -m3 hmat "$tmp/explain")"
if [ -s "$tmp/explain" ] && ! grep -q "library/" "$tmp/explain"; then ok "explain names no library/... file"
else bad "explain still names a file library/...: $(grep -m1 'library/' "$tmp/explain")"; fi
"$sp" library show fine-rib --library world --quiet >"$tmp/show" 2>&1
grep -q "(${inherited}[0-9]*:[0-9]*)" "$tmp/show" && ok "show's resolution: $inherited" || bad "show: $(grep -m3 hmat "$tmp/show")"
grep -q " ${own}[0-9]*" "$tmp/show" && ok "show's resolution: $own" || bad "show: $(grep -m3 hmat "$tmp/show")"
"$sp" library catalog --library world -o "$tmp/site" --quiet 2>/dev/null || bad "catalog"
grep -q ">${own}[0-9]*<" "$tmp/site/entries/fine-rib.html" && ok "catalog: $own" || bad "catalog: $(grep -o '[a-z/-]*\.hmat:[0-9:]*' "$tmp/site/entries/fine-rib.html" | sort -u | head -3)"
grep -q "(${inherited}[0-9]*:[0-9]*)" "$tmp/site/entries/fine-rib.html" && ok "catalog: $inherited" || bad "catalog: $(grep -o '[a-z/-]*\.hmat:[0-9:]*' "$tmp/site/entries/fine-rib.html" | sort -u | head -3)"
# From another folder, the CLI's paths are relative to it.
cd "$tmp" || exit 1
"$sp" explain -e fine-rib --library work/world >"$tmp/explain2" 2>&1
grep -q "(work/${inherited}[0-9]*:[0-9]*)" "$tmp/explain2" && ok "from elsewhere: work/$inherited" || bad "explain from $tmp: $(grep -m3 hmat "$tmp/explain2")"
exit $((fails > 0))
