#!/usr/bin/env bash
# `sandpaper library catalog` as a user runs it: exit codes, progress, and that a failed run or a
# folder that is not a catalog changes nothing. Usage: cli_catalog_test.sh path/to/sandpaper
set -uo pipefail
sp=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
check() {  # check "what" expected_status actual_status
  if [ "$2" = "$3" ]; then echo "ok   $1"; else echo "FAIL $1 (exit $3, expected $2)"; fails=$((fails + 1)); fi
}
has() {  # has "what" file pattern
  if grep -q -- "$3" "$2"; then echo "ok   $1"; else echo "FAIL $1: no '$3' in $2:"; cat "$2"; fails=$((fails + 1)); fi
}

"$sp" library catalog >"$tmp/out" 2>"$tmp/err"; check "no -o is a usage error" 2 $?

mkdir -p "$tmp/lib/cloth"
printf 'material "rib" {\n  family cloth\n  grating period 2 mm\n  roughness 0.4\n}\n' >"$tmp/lib/cloth/rib.hmat"
printf 'material "spring" {\n  spring 200 N/m\n}\n' >"$tmp/lib/spring.hmat"
"$sp" library catalog -o "$tmp/site" --library "$tmp/lib" >"$tmp/out" 2>"$tmp/err"; check "a good library is written" 0 $?
has "it says where" "$tmp/out" "catalog of 2 entries"
has "progress on stderr (not a terminal: a line at the end)" "$tmp/err" "catalog 2/2"
[ -f "$tmp/site/index.html" ] && [ -f "$tmp/site/entries/rib.png" ] && [ -f "$tmp/site/entries/spring.html" ]
check "index, pages and pictures exist" 0 $?
"$sp" library catalog -o "$tmp/site" --library "$tmp/lib" --quiet >"$tmp/out" 2>"$tmp/err"; check "a catalog replaces the previous one" 0 $?
[ ! -s "$tmp/err" ]; check "--quiet prints no progress" 0 $?
[ ! -s "$tmp/out" ]; check "--quiet prints no summary either" 0 $?
cp "$tmp/site/index.html" "$tmp/index.before"

printf 'material "broken" {\n  grating period -2 mm\n}\n' >"$tmp/lib/broken.hmat"
"$sp" library catalog -o "$tmp/site" --library "$tmp/lib" --quiet >"$tmp/out" 2>"$tmp/err"; check "an entry that does not compile: exit 1" 1 $?
has "the message names the entry" "$tmp/err" "do.* not compile: broken"
cmp -s "$tmp/index.before" "$tmp/site/index.html"; check "the previous catalog is left as it was" 0 $?
[ ! -e "$tmp/site/entries/broken.html" ]; check "nothing of the failed run is in it" 0 $?
[ -z "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '.site.*')" ]; check "no temporary folder is left beside it" 0 $?
rm "$tmp/lib/broken.hmat"

mkdir -p "$tmp/mine" && echo keep >"$tmp/mine/notes.txt"
"$sp" library catalog -o "$tmp/mine" --library "$tmp/lib" >"$tmp/out" 2>"$tmp/err"; check "a folder that is not a catalog is refused" 2 $?
has "and the user is told why" "$tmp/err" "not a catalog"
[ "$(cat "$tmp/mine/notes.txt")" = keep ]; check "its files are untouched" 0 $?

# A layered path: drawn from each root's index; an edit in place in the lab's root draws that entry alone.
mkdir -p "$tmp/lab"
printf 'id = "lab"\nname = "lab"\nversion = "0.1.0"\n' >"$tmp/lab/library.toml"
printf 'material "rib" {\n  overrides\n  like lib:rib\n  describes "our rib"\n  roughness 0.5\n}\n' >"$tmp/lab/rib.hmat"
printf 'material "wide-rib" {\n  like rib\n  grating period 4 mm\n}\n' >"$tmp/lab/wide-rib.hmat"
"$sp" library catalog -o "$tmp/layered" --library "$tmp/lab:$tmp/lib" >"$tmp/out" 2>"$tmp/err"; check "a layered path is drawn" 0 $?
has "the lab's rib hides the library's" "$tmp/out" "catalog of 3 entries"
has "the page is the lab's" "$tmp/layered/entries/rib.html" "our rib"
has "the page names its root and what it hides" "$tmp/layered/entries/rib.html" "<code>lab</code>, in front of <code>lib:rib</code>, which it hides"
has "the index's data names the root" "$tmp/layered/catalog-data/part-00000.js" '"root":{"[0-9]*":"lab"'
printf 'material "one" {\n  grating period 2 mm\n  roughness 0.4\n}\n' >"$tmp/one.hmat" && mkdir -p "$tmp/lib1" && mv "$tmp/one.hmat" "$tmp/lib1/"
"$sp" library catalog -o "$tmp/site1" --library "$tmp/lib1" >"$tmp/out" 2>/dev/null; check "a library of one entry" 0 $?
has "one entry is \"1 entry\"" "$tmp/out" "catalog of 1 entry ->"
has "its index page too" "$tmp/site1/index.html" "<p id=\"count\" aria-live=\"polite\">1 entry</p>"
[ -f "$tmp/lab/.index/library.sqlite" ] && [ -f "$tmp/lib/.index/library.sqlite" ]; check "each root has its index" 0 $?
echo "# touched" >>"$tmp/lab/wide-rib.hmat"
"$sp" library catalog -o "$tmp/layered" --library "$tmp/lab:$tmp/lib" >"$tmp/out" 2>"$tmp/err"; check "drawn again" 0 $?
has "an edit in place draws that entry alone" "$tmp/out" "(1 drawn, 2 unchanged, updated in place)"

exit $((fails > 0))
