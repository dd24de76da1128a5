# Sourced by the glTF checks' scripts: exits 77 (ctest SKIP_RETURN_CODE) unless node and each package
# named ("gltf-validator", "@gltf-transform/core", ...) are installed in tests/gltf/node_modules,
# which tools/install-deps.sh installs from the lockfile (`npm ci`). $here is tests/gltf.
need_node() {
  if ! command -v node >/dev/null 2>&1; then
    echo "SKIPPED: node is not installed (tools/install-deps.sh installs it)"
    exit 77
  fi
  for package in "$@"; do
    if [ ! -d "$here/node_modules/$package" ]; then
      echo "SKIPPED: $here/node_modules/$package is absent; run \`npm ci\` there (tools/install-deps.sh does)"
      exit 77
    fi
  done
}
