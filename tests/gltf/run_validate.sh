#!/usr/bin/env bash
# ctest gltf.validate: export a grating material, a height-map image material, a roughness level and
# a workspace with the built `sandpaper export --format gltf` (the last two also as .glb), then check them with glTF-Validator
# and ajv (validate.mjs). Exit 77 (ctest SKIP_RETURN_CODE) only when node or tests/gltf/node_modules
# is absent; CI installs them (tools/install-deps.sh runs `npm ci` here).
# Usage: run_validate.sh SANDPAPER_BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
sandpaper="$1" src="$2" out="$3"
here="$src/tests/gltf"
. "$here/need_node.sh"
need_node gltf-validator ajv
mkdir -p "$out"
cd "$src"
"$sandpaper" export examples/corduroy.hmat --format gltf -o "$out/corduroy.gltf"
"$sandpaper" export examples/gravel.hmat --format gltf -o "$out/gravel.gltf"
"$sandpaper" export -e "roughness coarse" --format gltf -o "$out/coarse.gltf"
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/sampler.gltf"
"$sandpaper" export examples/gravel.hmat --format gltf -o "$out/gravel.glb"
"$sandpaper" export examples/workspace/sampler.hws --format gltf -o "$out/sampler.glb"
node "$here/validate.mjs" "$out/corduroy.gltf" "$out/gravel.gltf" "$out/coarse.gltf" "$out/sampler.gltf" "$out/gravel.glb" "$out/sampler.glb"
