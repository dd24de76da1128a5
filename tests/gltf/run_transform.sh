#!/usr/bin/env bash
# ctest gltf.transform: a standard glTF pipeline keeps Sandpaper's haptics when it registers the
# MPEG_haptic_material extension (interop/gltf-transform). The built `sandpaper export --format gltf`
# writes a grating, a height-map image material and a workspace. glTF-Transform from the npm
# registry rewrites each, images as files beside the asset, two ways, each with and without the
# extension: a script that reads, dedups, prunes and writes (transform.mjs: script-with/,
# script-without/), and the command-line tool's `gltf-transform copy` (with `--config
# gltf-transform.config.mjs`: cli-with/; without: cli-without/). `sandpaper compile` reads them back.
# With the extension every asset compiles to the program the original compiles to (same force
# tables, forces, roughness, patch places); without it the haptics are gone (E0713).
# Exit 77 (ctest SKIP_RETURN_CODE) only when node or tests/gltf/node_modules is absent.
# Usage: run_transform.sh SANDPAPER_BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
sandpaper="$1" src="$2" out="$3"
here="$src/tests/gltf"
. "$here/need_node.sh"
need_node @gltf-transform/core @gltf-transform/functions @gltf-transform/extensions @gltf-transform/cli
rm -rf "$out"
mkdir -p "$out/src" "$out/script-with" "$out/script-without" "$out/cli-with" "$out/cli-without"
# The extension resolves @gltf-transform/* from where it lies: a copy of it beside this folder's packages.
cp -r "$src/interop/gltf-transform" "$out/ext"
ln -s "$here/node_modules" "$out/ext/node_modules"
cd "$src"
"$sandpaper" export examples/corduroy.hmat --format gltf -o "$out/src/corduroy.gltf"
"$sandpaper" export examples/gravel.hmat --format gltf -o "$out/src/gravel.gltf"
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/src/sampler.gltf"
node "$here/transform.mjs" "$out/ext/mpeg-haptic-material.js" "$out" "$out/src/corduroy.gltf" "$out/src/gravel.gltf" "$out/src/sampler.gltf"
cli="$here/node_modules/.bin/gltf-transform"
for name in corduroy gravel sampler; do
  "$cli" copy "$out/src/$name.gltf" "$out/cli-with/$name.gltf" --config "$out/ext/gltf-transform.config.mjs"
  "$cli" copy "$out/src/$name.gltf" "$out/cli-without/$name.gltf"
done
# And binary: glTF-Transform writes a .glb (images in its BIN chunk) from Sandpaper's .glb.
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/src/sampler-binary.glb"
"$cli" copy "$out/src/sampler-binary.glb" "$out/cli-with/sampler-binary.glb" --config "$out/ext/gltf-transform.config.mjs"
"$cli" copy "$out/src/sampler-binary.glb" "$out/cli-without/sampler-binary.glb"
"$sandpaper" compile "$out/src/sampler-binary.glb" -o "$out/src/sampler-binary.out" --json > "$out/src/sampler-binary.json"
failed=0
for name in corduroy gravel sampler sampler-binary; do
  ext=gltf hows="script cli"
  [ "$name" = sampler-binary ] && ext=glb hows=cli
  [ "$name" = sampler-binary ] || "$sandpaper" compile "$out/src/$name.gltf" -o "$out/src/$name.out" --json > "$out/src/$name.json"
  for how in $hows; do
  if "$sandpaper" compile "$out/$how-with/$name.$ext" -o "$out/$how-with/$name.out" --json > "$out/$how-with/$name.json"; then
    if python3 - "$out/src/$name.json" "$out/$how-with/$name.json" "$sandpaper" "$out/src/$name.out" "$out/$how-with/$name.out" <<'PY'
import json, subprocess, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
sp, pa, pb = sys.argv[3:6]
def program(out):
    # A material: inspect --json --tables (every term with its force tables, as the runtime plays
    # them). A workspace: its program file, JSON, each patch's program and place. Provenance and
    # warnings name the asset's path, which differs, and are left out.
    try:
        r = subprocess.run([sp, "inspect", out, "--json", "--tables"], capture_output=True, text=True, check=True)
        j = json.loads(r.stdout)
    except subprocess.CalledProcessError:
        j = json.load(open(out))
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k not in ("provenance", "warnings")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    return strip(j)
A, B = program(pa), program(pb)
same = A == B and json.dumps(A).count("force_N") > 0
print(("ok    " if same else "FAIL  ") + f"{pa} and {pb}: the same programs (forces, roughness, force tables, places)")
sys.exit(0 if same else 1)
PY
    then :; else failed=$((failed + 1)); fi
  else
    echo "FAIL  $out/$how-with/$name.$ext does not compile"; cat "$out/$how-with/$name.json"; failed=$((failed + 1))
  fi
  if "$sandpaper" compile "$out/$how-without/$name.$ext" -o "$out/$how-without/$name.out" 2> "$out/$how-without/$name.err"; then
    echo "FAIL  without the extension ($how) $name still compiled: the test cannot tell"; failed=$((failed + 1))
  elif grep -q 'E0713' "$out/$how-without/$name.err"; then
    echo "ok    without the extension ($how), glTF-Transform drops $name's haptics (E0713)"
  else
    echo "FAIL  without the extension ($how): $(head -1 "$out/$how-without/$name.err")"; failed=$((failed + 1))
  fi
  done
done
echo "$failed failed"
[ "$failed" -eq 0 ]
