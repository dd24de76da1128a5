#!/usr/bin/env bash
# Installs the Debian 12 packages Sandpaper builds and tests with, if any is missing.
# Everything comes from Debian's archive; nothing is downloaded at build time.
set -euo pipefail
pkgs=(
  build-essential cmake pkg-config          # toolchain (CMake >= 3.25: bookworm has 3.25.1)
  libopenimageio-dev openimageio-tools      # images as height maps (OpenImageIOConfig.cmake checks its tools exist)
  libglm-dev                                # 2-vectors in the runtime
  libusb-1.0-0-dev                          # USB force-feedback devices (runtime issue)
  libevdev-dev                              # force feedback through the kernel's input event nodes (docs/DEVICES.md)
  libcli11-dev libfmt-dev                   # command line, formatting
  nlohmann-json3-dev libtomlplusplus-dev    # JSON output, TOML calibration files
  zlib1g-dev                                # CRC-32 of patch programs
  libpng-dev                                # the catalog's and studio's PNG pictures, without loading OpenImageIO
  libeigen3-dev libboost-math-dev           # least squares and t/F distributions for calibration fits
  libsqlite3-dev                            # the library index (`sandpaper library index`; FTS5 full text)
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium python3                          # the library catalog's and the studio's browser tests (tests/*/browser_test.py)
  neovim                                    # the language server's test with a real editor (tests/lsp/neovim_test.py)
  libcpp-httplib-dev                        # the studio's HTTP server (studio/, docs/STUDIO.md)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module (bindings/python, docs/PYTHON.md)
  jq                                        # JSON in the CLI's shell tests (tests/cli/)
  dpkg-dev file                             # the Debian package: cpack -G DEB's dpkg-shlibdeps (cmake/Packaging.cmake)
  qemu-system-x86                           # the USB lab's guest: docs/USB_PID.md "In the lab" (usb-lab/guest/lab.py)
  linux-image-amd64 kmod                    # the USB lab's guest kernel and its modules (dummy_hcd, usb_f_fs, usbhid)
  linux-source-6.1 linux-headers-amd64      # the lab's own dummy_hcd with 1 ms frames (usb-lab/bus/)
  busybox-static                            # the USB lab's guest userland (its initramfs: usb-lab/guest/initramfs.py)
)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Node.js and npm build the studio's page (CodeMirror 6 bundled by esbuild; studio/web). Debian's
# nodejs and npm when the machine has neither.
if ! command -v npm >/dev/null 2>&1; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
  echo "installing: nodejs npm"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends nodejs npm
fi
# The page's packages, exactly as the committed lockfile pins them, from the npm registry; again only
# when the lockfile changed since the last install. No install scripts run (esbuild finds its binary
# in its platform package).
web="$(cd "$(dirname "$0")/.." && pwd)/studio/web"
stamp="$web/node_modules/.sandpaper-lock"
if ! cmp -s "$web/package-lock.json" "$stamp" 2>/dev/null; then
  echo "installing the studio page's npm packages (npm ci)"
  (cd "$web" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
  cp "$web/package-lock.json" "$stamp"
fi
# The glTF checks' packages (Khronos' gltf-validator and ajv for ctest gltf.validate; glTF-Transform's
# core, functions, extensions and CLI for ctest gltf.transform; docs/GLTF.md), the
# same way: pinned by tests/gltf/package-lock.json, installed when it changed.
gltf_checks="$(cd "$(dirname "$0")/.." && pwd)/tests/gltf"
stamp="$gltf_checks/node_modules/.sandpaper-lock"
if ! cmp -s "$gltf_checks/package-lock.json" "$stamp" 2>/dev/null; then
  echo "installing the glTF checks' npm packages (npm ci)"
  (cd "$gltf_checks" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
  cp "$gltf_checks/package-lock.json" "$stamp"
fi
