#!/usr/bin/env bash
# ctest install.consumer: install this build, then build and run tests/consumer/ against the
# installed package only, once through find_package(Sandpaper) and once through pkg-config.
# Usage: run_consumer_test.sh BUILD_DIR SOURCE_DIR INSTALL_PREFIX INSTALL_LIBDIR INSTALL_DATA_DIR CXX [CXX_FLAGS]
#   INSTALL_PREFIX, INSTALL_LIBDIR and INSTALL_DATA_DIR are the configured (absolute) ones.
# The install is staged with DESTDIR (as packagers do), so the configured prefix is never written.
# The installed libraries look for their data in INSTALL_DATA_DIR, compiled in: the first run checks
# that this is what they report, the others point SANDPAPER_LIBRARY/CALIBRATION at the staged copy.
set -euo pipefail
build=$1 src=$2 prefix=$3 libdir=$4 datadir=$5 cxx=$6 cxxflags=${7:-}

work=$build/tests/consumer-work
rm -rf "$work"
mkdir -p "$work"
stage=$work/stage
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== install into DESTDIR=$stage (prefix $prefix)"
DESTDIR=$stage cmake --install "$build" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
root=$stage$prefix
for f in "$root/include/sandpaper/sandpaper.hpp" "$stage$libdir/cmake/Sandpaper/SandpaperConfig.cmake" \
         "$stage$libdir/pkgconfig/sandpaper.pc" "$stage$datadir/library" \
         "$stage$datadir/calibration/levels/roughness-levels.toml"; do
  [[ -e $f ]] || fail "not installed: $f"
done
[[ -n $(find "$stage$datadir/library" -name corduroy.hmat) ]] || fail "library entry corduroy not installed"
[[ ! -e $stage$datadir/calibration/src ]] || fail "calibration's code was installed as data"

# The build tree's own answer, from the source tree's data, for comparison.
expected=$("$build/bin/play_material" corduroy) || fail "build tree's play_material corduroy"
expected_force=$(sed -n 's/.*(compiled \([0-9.e+-]*\) N).*/\1/p' <<<"$expected")
[[ -n $expected_force ]] || fail "no compiled force in: $expected"
echo "build tree: $expected"

check_run() {  # $1: executable, $2: how it was built
  local exe=$1 how=$2 out
  [[ -x $exe ]] || fail "$how: no executable"
  # Nothing of the source tree's data may be compiled in.
  if grep -a -q -F "$src/library" "$exe"; then fail "$how: $exe contains the source tree's library path $src/library"; fi
  # Without the environment, the installed default: the configured data directory.
  out=$(env -u SANDPAPER_LIBRARY -u SANDPAPER_CALIBRATION "$exe" corduroy 2>&1) || true
  grep -q -F "$datadir/library" <<<"$out" || fail "$how: does not use the installed library directory $datadir/library: $out"
  # With the environment pointing at the staged install: plays corduroy.
  out=$(SANDPAPER_LIBRARY=$stage$datadir/library SANDPAPER_CALIBRATION=$stage$datadir/calibration "$exe" corduroy 2>&1) ||
    fail "$how: run failed: $out"
  echo "$how: $out"
  grep -q -F "library $stage$datadir/library" <<<"$out" || fail "$how: library directory not reported"
  grep -q "^played 500 ticks, .*stop completed$" <<<"$out" || fail "$how: did not play 500 ticks to completion"
  local compiled played
  compiled=$(sed -n 's/.*compiled_max_lateral_force_N \([0-9.e+-]*\).*/\1/p' <<<"$out")
  played=$(sed -n 's/.*max_lateral_force_N \([0-9.e+-]*\),.*/\1/p' <<<"$out")
  awk -v c="$compiled" -v e="$expected_force" -v p="$played" 'BEGIN {
    if (c + 0 <= 0) { print "compiled force not positive: " c; exit 1 }
    if ((c - e) > 1e-4 * e || (e - c) > 1e-4 * e) { print "compiled " c " N differs from the build tree'"'"'s " e " N"; exit 1 }
    if (p + 0 <= 0) { print "no lateral force played"; exit 1 }
    if (p > c * 1.0001) { print "played " p " N above the compiled maximum " c " N"; exit 1 }
  }' || fail "$how: forces"
}

echo "== find_package(Sandpaper)"
cmake -S "$src/tests/consumer" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$root" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="$cxxflags" -DCMAKE_FIND_PACKAGE_NO_SYSTEM_PACKAGE_REGISTRY=ON \
  > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configure against the installed package"; }
grep -q -F "$root" "$work/cmake-build/CMakeCache.txt" || fail "Sandpaper was not found in $root"
cmake --build "$work/cmake-build" -j2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build"; }
check_run "$work/cmake-build/play_by_name" "find_package"

echo "== pkg-config sandpaper"
export PKG_CONFIG_PATH=$stage$libdir/pkgconfig
flags=$(pkg-config --cflags --libs sandpaper) || fail "pkg-config --cflags --libs sandpaper"
inc=$(pkg-config --variable=includedir sandpaper)
[[ $(realpath -m "$inc") == $(realpath -m "$root/include") ]] || fail "pkg-config's includedir $inc is not the install's"
# shellcheck disable=SC2086  # flags are words
"$cxx" -std=c++20 $cxxflags "$src/tests/consumer/play_by_name.cpp" -o "$work/play_by_name_pc" $flags \
  > "$work/pc-build.log" 2>&1 || { cat "$work/pc-build.log"; fail "build with pkg-config"; }
check_run "$work/play_by_name_pc" "pkg-config"
echo "PASS"
