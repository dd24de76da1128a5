#!/usr/bin/env bash
# The include arrows hold in this tree, and the checker catches one that points the wrong way.
#   include_arrows_test.sh SOURCE_DIR
set -uo pipefail
src=$1
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }

out=$(bash "$src/tests/architecture/include_arrows.sh" "$src" 2>&1) && ok "every room includes only the rooms below it" \
  || bad "includes against the arrows:"$'\n'"$out"
echo "$out" | grep -qE '^include_arrows: 1[0-9] rooms, [0-9]{3,} includes checked$' && ok "the checker read the rooms and their includes" \
  || bad "the checker read too little: $out"

# A scratch tree with the same arrows, where schema includes the compiler: refused, with the place.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs"
cp "$src/docs/ARCHITECTURE.md" "$tmp/docs/"
for room in $(awk '/^```arrows$/{on=1; next} /^```$/{on=0} on && NF {sub(/:.*/, ""); print}' "$src/docs/ARCHITECTURE.md"); do
  mkdir -p "$tmp/$room/src"
done
printf '#include <vector>\n  #include "sandpaper/compiler/compiler.hpp"\n' > "$tmp/schema/src/upward.cpp"
printf '#include "sandpaper/schema/units.hpp"\n#include "sandpaper/studio/server.hpp"\n' > "$tmp/curation/src/sideways.cpp"
printf '#include "sandpaper/schema/units.hpp"\n#include "sandpaper/sandpaper.hpp"\n' > "$tmp/apps/src/fine.cpp"
out=$(bash "$src/tests/architecture/include_arrows.sh" "$tmp" 2>&1)
rc=$?
[ $rc -eq 1 ] && ok "an include against the arrows fails the check" || bad "exit $rc for a tree with wrong includes: $out"
grep -qx 'schema/src/upward.cpp:2: schema includes compiler ("sandpaper/compiler/compiler.hpp"), against docs/ARCHITECTURE.md'"'"'s arrows' <<<"$out" \
  && ok "it names the file, line and rooms" || bad "no line for schema/src/upward.cpp:2 in: $out"
grep -q 'curation/src/sideways.cpp:2: curation includes studio' <<<"$out" && ok "a sideways include is caught too" \
  || bad "curation including the studio was not caught: $out"
grep -q 'fine.cpp' <<<"$out" && bad "an allowed include was reported: $out" || ok "allowed includes pass"

echo "$pass passed, $fail failed"
