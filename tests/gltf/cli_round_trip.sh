#!/usr/bin/env bash
# ctest gltf.cli: `sandpaper export --format gltf` then `sandpaper compile ASSET.gltf`, through the
# command line as a user runs them: the read-back maximum lateral force within 0.5 % of the original's
# (both from `compile --json`), a workspace asset compiled to a workspace program, `explain` of a
# .gltf and of a .glb (`export --format glb`) showing the patch they hold, and a hostile asset
# refused with exit 1 and its diagnostic code, writing nothing.
# Usage: cli_round_trip.sh SANDPAPER_BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
sp="$1" src="$2" out="$3"
rm -rf "$out" && mkdir -p "$out"
cd "$src"
for m in examples/corduroy.hmat examples/gravel.hmat; do
  name=$(basename "$m" .hmat)
  "$sp" export "$m" --format gltf -o "$out/$name.gltf" 2>/dev/null
  a=$("$sp" compile "$m" -o "$out/$name.patch" --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["compiled_max_lateral_force_N"])')
  b=$("$sp" compile "$out/$name.gltf" -o "$out/$name-back.patch" --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["compiled_max_lateral_force_N"])')
  python3 -c "import sys; a, b = $a, $b; print('$name: %.6g N -> %.6g N' % (a, b)); sys.exit(0 if a > 0 and abs(a - b) <= 0.005 * a else 1)"
  test -s "$out/$name-back.patch"
done
"$sp" export examples/workspace/sampler.hws --format gltf -o "$out/sampler.gltf" 2>/dev/null
"$sp" compile "$out/sampler.gltf" -o "$out/sampler.wsp" 2>/dev/null | grep -q "workspace of 7 patch(es)"
test -s "$out/sampler.wsp"
# explain reads an asset as compile does: the patch it holds, with the force `compile` of the
# original material gives (within the 16-bit heights' 0.5 %), never as material text (E0102).
"$sp" export examples/corduroy.hmat --format glb -o "$out/corduroy-fmt.glb" 2>/dev/null
test "$(head -c 4 "$out/corduroy-fmt.glb")" = glTF
want=$("$sp" compile examples/corduroy.hmat -o "$out/corduroy-explain.patch" --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["compiled_max_lateral_force_N"])')
for asset in "$out/corduroy.gltf" "$out/corduroy-fmt.glb"; do
  "$sp" explain "$asset" > "$out/explain.txt" 2> "$out/explain.err"
  if grep -q E0102 "$out/explain.err"; then echo "explain read $asset as material text"; exit 1; fi
  grep -q "material   corduroy" "$out/explain.txt"
  "$sp" explain "$asset" --json 2>/dev/null | python3 -c "
import json, sys
j = json.load(sys.stdin)
f = j['program']['compiled_max_lateral_force_N']
print('explain $(basename "$asset"): %.6g N, compile of the material: %.6g N' % (f, $want))
sys.exit(0 if j['ok'] and j['kind'] == 'patch' and abs(f - $want) <= 0.005 * $want else 1)"
done
"$sp" explain "$out/sampler.gltf" > "$out/explain-sampler.txt" 2>/dev/null
grep -q "workspace '.*' of .*, 7 patch(es)" "$out/explain-sampler.txt"
# --format glb wants a .glb name (binary under .gltf would be taken for JSON): usage, nothing written.
set +e
"$sp" export examples/corduroy.hmat --format glb -o "$out/binary-named.gltf" 2>/dev/null
rc=$?
set -e
test "$rc" -eq 2 && test ! -e "$out/binary-named.gltf"
# Hostile: half an asset.
head -c 3000 "$out/corduroy.gltf" > "$out/cut.gltf"
set +e
"$sp" compile "$out/cut.gltf" -o "$out/cut.patch" 2> "$out/cut.err"
rc=$?
set -e
cat "$out/cut.err"
test "$rc" -eq 1 && grep -q "error\[E0711\]" "$out/cut.err" && test ! -e "$out/cut.patch"
echo "gltf.cli: ok"
