#!/usr/bin/env bash
# ctest install.deb: make the Debian package of this build (cpack -G DEB, cmake/Packaging.cmake) and
# check it from outside, without installing anything on this machine:
#   - its name, control fields and Depends (dpkg-shlibdeps' runtime libraries, OpenImageIO among them);
#   - its files: programs, data, headers, libraries, CMake package, sandpaper.pc, Python module, all
#     under usr/, none naming the build or source tree;
#   - unpacked (dpkg-deb -x) into a throwaway root: the CLI compiles and searches with the data beside
#     it (not the source tree's), a user who cannot write there searches once the postinst's index is
#     built, and /usr/bin/python3 imports the module from the root's dist-packages;
#   - apt-get --simulate install of the .deb on an empty dpkg status (a machine with nothing
#     installed): every dependency resolves from the Debian archive this machine's apt knows.
# Usage: deb_package_test.sh BUILD_DIR SOURCE_DIR VERSION [PYTHON]
#   PYTHON: the interpreter the module was built for, when the module is built (SANDPAPER_PYTHON).
set -euo pipefail
build=$1 src=$2 version=$3 python=${4:-}

work=$build/tests/deb-work
[[ ! -e $work ]] || chmod -R u+w "$work"  # a previous run's root is read-only
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
for tool in cpack dpkg-deb dpkg-shlibdeps file; do
  command -v "$tool" >/dev/null || fail "$tool not found (dpkg-dev, file: tools/install-deps.sh)"
done
unset SANDPAPER_LIBRARY SANDPAPER_CALIBRATION SANDPAPER_DATA_DIR SANDPAPER_LIBRARY_INDEX

echo "== cpack -G DEB"
# cpack first runs the build tool's `preinstall` target, which for Makefiles is the whole build (`all`).
# This test packages the tree as it was built and must not build it: CPACK_CMAKE_GENERATOR names a
# generator that has no preinstall step, and cpack goes straight to the install rules (cmake_install.cmake,
# as `cmake --install` runs them). Everything else is the build's own CPackConfig.cmake.
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" -D CPACK_CMAKE_GENERATOR=Ninja \
  > "$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
arch=$(dpkg --print-architecture)
deb=$work/out/sandpaper_${version}_${arch}.deb
[[ -f $deb ]] || { ls -la "$work/out"; fail "no $deb"; }
echo "package: $(basename "$deb"), $(stat -c %s "$deb") bytes"

echo "== control"
info=$(dpkg-deb --info "$deb")
field() { dpkg-deb --field "$deb" "$1"; }
[[ $(field Package) == sandpaper ]] || fail "Package is not sandpaper: $info"
[[ $(field Version) == "$version" ]] || fail "Version is not $version: $info"
[[ $(field Architecture) == "$arch" ]] || fail "Architecture is not $arch: $info"
[[ -n $(field Maintainer) && -n $(field Description) && -n $(field Section) ]] || fail "Maintainer, Description or Section missing: $info"
depends=$(field Depends)
echo "Depends: $depends"
[[ -n $depends ]] || fail "empty Depends"
# What dpkg-shlibdeps found the programs link: these names carry the library's soname version.
for dep in 'libopenimageio[0-9.]+' 'libusb-1\.0-0' 'libstdc\+\+6' 'libc6'; do
  grep -q -E "(^|, )$dep( |,|$)" <<<"$depends" || fail "Depends lacks $dep: $depends"
done
if [[ -n $python ]]; then
  pyver=$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')
  grep -q -F "python3 (>= $pyver)" <<<"$depends" && grep -q -F "python3-numpy" <<<"$depends" ||
    fail "Depends lacks python3 (>= $pyver) or python3-numpy: $depends"
fi
# (Here-strings, not pipes into grep -q: under pipefail a grep that stops early fails the pipe.)
control_files=$(dpkg-deb --ctrl-tarfile "$deb" | tar -t)
# The postinst indexes the library for `library search`: only a package with the curator's tools has one.
curation=${SANDPAPER_TEST_CURATION:-ON}
if [[ $curation == ON ]]; then
  grep -q -x -e './postinst' <<<"$control_files" && grep -q -x -e './prerm' <<<"$control_files" || fail "no postinst or prerm: $control_files"
  postinst=$(dpkg-deb -I "$deb" postinst)
  grep -q "sandpaper library index" <<<"$postinst" || fail "the postinst does not index the library: $postinst"
else
  # (CPack's own postinst may run ldconfig; it must not run a command this package lacks.)
  if grep -q -x -e './postinst' <<<"$control_files"; then
    postinst=$(dpkg-deb -I "$deb" postinst)
    grep -q "library index" <<<"$postinst" && fail "a package without the curator's tools indexes the library: $postinst"
  fi
fi

echo "== files"
dpkg-deb --contents "$deb" > "$work/contents.txt"
# The path is the last field; no installed file name has a space.
awk '{print $NF}' "$work/contents.txt" | sed 's|^\./|/|' > "$work/paths.txt"
echo "$(wc -l < "$work/paths.txt") entries"
has() { grep -q -x -E "$1" "$work/paths.txt" || fail "not in the package: $1"; }
has '/usr/bin/sandpaper'
has '/usr/bin/sandpaper-play'
has '/usr/lib(/[^/]+)?/sandpaper/libsandpaper_image_io\.so'
has '/usr/lib(/[^/]+)?/libsandpaper_image_io\.a'
has '/usr/share/sandpaper/library/.+/corduroy\.hmat'
has '/usr/share/sandpaper/calibration/levels/roughness-levels\.toml'
has '/usr/share/sandpaper/calibration/devices/sim\.toml'
has '/usr/include/sandpaper/sandpaper\.hpp'
has '/usr/include/sandpaper/sandpaper\.h'
has '/usr/include/sandpaper/package_location\.h'
has '/usr/lib(/[^/]+)?/libsandpaper_api\.a'
# Debian ships debug information in a -dbgsym package of its own: none in this one.
! grep -q -E '/lib/debug/' "$work/paths.txt" || fail "the package holds debug files: $(grep -E '/lib/debug/' "$work/paths.txt" | head -3)"
has '/usr/lib(/[^/]+)?/cmake/Sandpaper/SandpaperConfig\.cmake'
has '/usr/lib(/[^/]+)?/cmake/Sandpaper/SandpaperTargets\.cmake'
has '/usr/lib(/[^/]+)?/pkgconfig/sandpaper\.pc'
has '/usr/lib/udev/rules\.d/70-sandpaper\.rules'
if [[ -n $python ]]; then
  has '/usr/lib/python3/dist-packages/sandpaper\..*\.so'
  grep -q -E '^/usr/lib/python3\.[0-9]+/' "$work/paths.txt" && fail "a file under /usr/lib/python3.X, not Debian's /usr/lib/python3/dist-packages"
fi
grep -v -E '^/usr(/|$)' "$work/paths.txt" && fail "files outside /usr (above)"
grep -F -e "$build" -e "$src" -e "/_CPack_Packages/" "$work/paths.txt" && fail "file paths naming the build or source tree (above)"
grep -E '/\.index(/|$)|/calibration/(src|include)(/|$)|CMakeLists\.txt$' "$work/paths.txt" &&
  fail "the library index, calibration's code or a CMakeLists.txt packaged (above)"
# Each entry once (a file installed twice would be listed twice).
[[ -z $(sort "$work/paths.txt" | uniq -d) ]] || fail "entries listed twice: $(sort "$work/paths.txt" | uniq -d)"

echo "== unpacked into $work/root"
root=$work/root
dpkg-deb -x "$deb" "$root"
data=$root/usr/share/sandpaper
# Text the package installs must not point into this machine's trees (the .pc, the CMake package,
# package_location.h find the prefix relative to themselves).
grep -r -l -F -e "$build" -e "$src" "$root/usr/include" "$root"/usr/lib*/ --include='*.cmake' --include='*.pc' --include='*.h' \
  --include='*.hpp' && fail "installed text naming the build or source tree (above)"
# The data directories compiled in are NUL-terminated strings (as run_consumer_test.sh checks).
for exe in "$root/usr/bin/sandpaper" "$root/usr/bin/sandpaper-play" $(find "$root" -name 'sandpaper*.so'); do
  for d in library calibration; do
    if LC_ALL=C grep -a -q -P "\\Q$src/$d\\E\\x00" "$exe"; then fail "$exe has the source tree's $d path compiled in"; fi
  done
done

# The udev rules that let the seat's user play without root (docs/DEVICES.md "No root"): udev syntax,
# a hidraw rule for each USB device the packaged calibration names, one for force-feedback event devices.
out=$(python3 "$src/tests/runtime/devices/udev_rules_test.py" "$root/usr/lib/udev/rules.d/70-sandpaper.rules" \
  "$data/calibration" 2>&1) || fail "the packaged udev rules: $out"
echo "udev rules: $(tail -1 <<<"$out")"

# Run from elsewhere, so that nothing is found relative to the working directory.
cd "$work"
sp=$root/usr/bin/sandpaper
out=$("$sp" compile "$src/examples/corduroy.hmat" -o "$work/corduroy.patch" 2>&1) || fail "unpacked sandpaper compile: $out"
echo "compile: $out"
[[ -s $work/corduroy.patch ]] || fail "no patch written"
# A picture: the program loads the package's picture module from beside itself (compiler/image_io.hpp).
out=$("$sp" compile "$src/examples/grass.hmat" -o "$work/grass.patch" 2>&1) || fail "unpacked sandpaper compile of a picture: $out"
out=$("$sp" run "$work/corduroy.patch" --duration 0.2 --virtual-clock 2>&1) || fail "unpacked sandpaper run (through sandpaper-play beside it): $out"
echo "run: $(tail -1 <<<"$out")"
# The data it used is the root's: take an entry, then a device, away there and it must notice.
entry=$(find "$data/library" -name corduroy.hmat | head -1)
mv "$entry" "$entry.away"
out=$("$sp" compile -e corduroy -o "$work/x.patch" 2>&1) && fail "compiled corduroy with $entry gone: the library used is not the root's"
grep -q "no library entry named 'corduroy'" <<<"$out" || fail "unexpected error without $entry: $out"
mv "$entry.away" "$entry"
mv "$data/calibration/devices/sim.toml" "$work/sim.toml.away"
out=$("$sp" compile -e corduroy -o "$work/x.patch" 2>&1) && fail "compiled for sim with $data/calibration/devices/sim.toml gone: the calibration used is not the root's"
grep -q "unknown device 'sim'" <<<"$out" || fail "unexpected error without sim.toml: $out"
mv "$work/sim.toml.away" "$data/calibration/devices/sim.toml"

# `library search` reads an index beside the library; under /usr only root writes there, so the
# postinst builds it (`sandpaper library index`). Do what it does, then search as someone who cannot
# write: nobody when this runs as root, else this user with the root made read-only.
if [[ $curation == ON ]]; then
  "$sp" library index --quiet > "$work/index.log" 2>&1 || { cat "$work/index.log"; fail "unpacked sandpaper library index"; }
  [[ -f $data/library/.index/library.sqlite ]] || fail "the index was not built beside the root's library ($data/library/.index)"
  chmod -R a-w "$root"
  trap 'chmod -R u+w "$root" 2>/dev/null || true' EXIT
  as_user=()
  if [[ $(id -u) == 0 ]]; then
    if id nobody >/dev/null 2>&1 && command -v setpriv >/dev/null &&
       setpriv --reuid=nobody --regid=nogroup --clear-groups test -x "$sp" 2>/dev/null; then
      as_user=(setpriv --reuid=nobody --regid=nogroup --clear-groups)
    else
      echo "SKIP: the search as a user who cannot write (no nobody/setpriv, or $root not reachable by nobody)"
    fi
  fi
  if [[ $(id -u) != 0 || ${#as_user[@]} -gt 0 ]]; then
    out=$(HOME=/nonexistent "${as_user[@]}" "$sp" library search corduroy 2>&1) || fail "library search without write access: $out"
    grep -q corduroy <<<"$out" || fail "library search does not find corduroy: $out"
    echo "search without write access: $(head -1 <<<"$out")"
  fi
fi

if [[ -n $python ]]; then
  echo "== the Python module from the root's dist-packages"
  out=$(PYTHONPATH=$root/usr/lib/python3/dist-packages "$python" -c '
import sandpaper
print("module", sandpaper.__file__)
lib = sandpaper.Library()
print("library", lib.library_dir)
print("corduroy", lib.compile("corduroy").compiled_max_lateral_force_N)' 2>&1) || fail "import the packaged module: $out"
  echo "$out"
  grep -q -F "module $root/usr/lib/python3/dist-packages/" <<<"$out" || fail "imported another sandpaper module: $out"
  reported=$(sed -n 's/^library //p' <<<"$out")
  [[ $(realpath -m "$reported") == $(realpath -m "$data/library") ]] || fail "the packaged module does not use $data/library: $out"
fi

echo "== apt-get --simulate install on a machine with nothing installed"
if ! command -v apt-get >/dev/null; then
  echo "SKIP: no apt-get"
elif ! grep -q -E 'Candidate: [0-9]' <<<"$(apt-cache policy libc6 2>/dev/null)"; then
  echo "SKIP: apt knows no archive (no package lists: apt-get update)"
else
  : > "$work/empty-status"
  # Dir::State::status: an empty dpkg database, so apt must find every dependency in the archive.
  # A simulation writes nothing and needs no root.
  if apt-get --simulate -o Dir::State::status="$work/empty-status" -o Debug::NoLocking=1 install "$deb" \
       > "$work/apt-simulate.log" 2>&1; then
    grep -q -E '^Inst sandpaper \('"$version" "$work/apt-simulate.log" || { cat "$work/apt-simulate.log"; fail "apt would not install sandpaper"; }
    for p in $(tr ',' '\n' <<<"$depends" | sed -E 's/^ *([^ ]+).*/\1/' | sort -u); do
      grep -q -F "Inst $p (" "$work/apt-simulate.log" || fail "apt would not install the dependency $p"
    done
    echo "apt resolves it: $(grep -c '^Inst ' "$work/apt-simulate.log") packages on an empty system, $(grep '^Inst sandpaper ' "$work/apt-simulate.log")"
  else
    cat "$work/apt-simulate.log"
    fail "apt-get --simulate install $deb"
  fi
fi
echo "PASS"
