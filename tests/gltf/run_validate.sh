#!/usr/bin/env bash
# ctest gltf.validate: export a grating material, a height-map image material, a roughness level and
# a workspace with the built `sandpaper export --format gltf` (the last two also as .glb), then check them with glTF-Validator
# and ajv (validate.mjs). Exit 77 (ctest SKIP_RETURN_CODE) only when node or tests/gltf/node_modules
# is absent; CI installs them (tools/install-deps.sh runs `npm ci` here).
# Usage: run_validate.sh SANDPAPER_BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
sandpaper="$1" src="$2" out="$3"
here="$src/tests/gltf"
if ! command -v node >/dev/null 2>&1; then
  echo "SKIPPED: node is not installed (tools/install-deps.sh installs it)"
  exit 77
fi
if [ ! -d "$here/node_modules/gltf-validator" ] || [ ! -d "$here/node_modules/ajv" ]; then
  echo "SKIPPED: $here/node_modules is absent; run \`npm ci\` there (tools/install-deps.sh does)"
  exit 77
fi
mkdir -p "$out"
cd "$src"
"$sandpaper" export examples/corduroy.hmat --format gltf -o "$out/corduroy.gltf"
"$sandpaper" export examples/gravel.hmat --format gltf -o "$out/gravel.gltf"
"$sandpaper" export -e "roughness coarse" --format gltf -o "$out/coarse.gltf"
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/sampler.gltf"
"$sandpaper" export examples/gravel.hmat --format gltf -o "$out/gravel.glb"
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/sampler.glb"
node "$here/validate.mjs" "$out/corduroy.gltf" "$out/gravel.gltf" "$out/coarse.gltf" "$out/sampler.gltf" "$out/gravel.glb" "$out/sampler.glb"
