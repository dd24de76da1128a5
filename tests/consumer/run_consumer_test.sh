#!/usr/bin/env bash
# ctest install.consumer: install this build, move the installed prefix elsewhere (relocation), then
# build and run tests/consumer/ against the moved package only, once through find_package(Sandpaper)
# and once through pkg-config; run the installed CLI and player from there; and check the error when
# the data is gone.
# Usage: run_consumer_test.sh BUILD_DIR SOURCE_DIR INSTALL_PREFIX INSTALL_LIBDIR INSTALL_DATA_DIR CXX [CXX_FLAGS]
#   INSTALL_PREFIX, INSTALL_LIBDIR and INSTALL_DATA_DIR are the configured (absolute) ones.
# The install is staged with DESTDIR (as packagers do), so the configured prefix is never written.
# Nothing points the programs at their data: they must find it from where the package lies now.
set -euo pipefail
build=$1 src=$2 prefix=$3 libdir=$4 datadir=$5 cxx=$6 cxxflags=${7:-}

work=$build/tests/consumer-work
rm -rf "$work"
mkdir -p "$work"
stage=$work/stage
fail() { echo "FAIL: $*" >&2; exit 1; }

echo "== install into DESTDIR=$stage (prefix $prefix), then move the prefix to $work/moved"
DESTDIR=$stage cmake --install "$build" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
# Everything below lives under the prefix; keep its layout, change its place.
rel_lib=${libdir#"$prefix"/} rel_data=${datadir#"$prefix"/}
[[ $rel_lib != "$libdir" && $rel_data != "$datadir" ]] || fail "libdir $libdir or datadir $datadir is not under the prefix $prefix"
root=$work/moved
mv "$stage$prefix" "$root"
data=$root/$rel_data
for f in "$root/include/sandpaper/sandpaper.hpp" "$root/$rel_lib/cmake/Sandpaper/SandpaperConfig.cmake" \
         "$root/$rel_lib/pkgconfig/sandpaper.pc" "$data/library" "$data/calibration/levels/roughness-levels.toml" \
         "$root/bin/sandpaper" "$root/bin/sandpaper-play"; do
  [[ -e $f ]] || fail "not installed: $f"
done
[[ -n $(find "$data/library" -name corduroy.hmat) ]] || fail "library entry corduroy not installed"
# Installed stripped, as Debian installs (cmake/install_strip.cmake): no debug sections in the
# programs, the Python module or the static libraries; each program's debug information apart,
# under lib/debug/.build-id by its build id, where gdb finds it. (grep reads readelf's whole output:
# with pipefail, `grep -q` leaving early would fail the pipeline when readelf then got SIGPIPE, as
# it did in a loaded CI run.)
for exe in "$root/bin/sandpaper" "$root/bin/sandpaper-play"; do
  ! readelf -S -W "$exe" | grep ' \.debug_info ' >/dev/null || fail "$exe was installed with its debug information"
  id=$(readelf -n "$exe" | sed -n 's/.*Build ID: \([0-9a-f]*\).*/\1/p')
  [[ -n $id ]] || fail "$exe has no build id"
  debug=$root/$rel_lib/debug/.build-id/${id:0:2}/${id:2}.debug
  [[ -f $debug ]] && readelf -S -W "$debug" | grep ' \.debug_info ' >/dev/null || fail "no debug information for $exe at $debug"
  readelf -x .gnu_debuglink "$exe" | grep "${id:2:8}" >/dev/null || fail "$exe does not name its debug file"
done
for lib in "$root/$rel_lib"/libsandpaper_*.a; do
  ! readelf -S -W "$lib" 2>/dev/null | grep ' \.debug_info ' >/dev/null || fail "$lib was installed with its debug information"
done
installed_mb=$(du -sm --exclude=debug "$root" | cut -f1)
echo "installed: ${installed_mb} MB without the debug files, $(du -sm "$root/$rel_lib/debug" | cut -f1) MB of debug files"
(( installed_mb < 60 )) || fail "the install without its debug files is ${installed_mb} MB: not stripped?"
[[ ! -e $data/calibration/src ]] || fail "calibration's code was installed as data"
unset SANDPAPER_LIBRARY SANDPAPER_CALIBRATION SANDPAPER_DATA_DIR

# The build tree's own answer, from the source tree's data, for comparison.
expected=$("$build/bin/play_material" corduroy) || fail "build tree's play_material corduroy"
expected_force=$(sed -n 's/.*(compiled \([0-9.e+-]*\) N).*/\1/p' <<<"$expected")
[[ -n $expected_force ]] || fail "no compiled force in: $expected"
echo "build tree: $expected"

# The data directories compiled in are NUL-terminated strings; debug information naming source files
# under $src/calibration/include is not a data path, hence the \x00.
no_source_paths() {  # $1: an installed or consumer executable
  local d
  for d in library calibration; do
    if LC_ALL=C grep -a -q -P "\\Q$src/$d\\E\\x00" "$1"; then fail "$1 has the source tree's $d path $src/$d compiled in"; fi
  done
}

check_run() {  # $1: executable, $2: how it was built
  local exe=$1 how=$2 out
  [[ -x $exe ]] || fail "$how: no executable"
  no_source_paths "$exe"
  out=$("$exe" corduroy 2>&1) || fail "$how: run failed: $out"
  echo "$how: $out"
  local reported
  reported=$(sed -n 's/^library //p' <<<"$out")
  [[ -n $reported && $(realpath -m "$reported") == $(realpath -m "$data/library") ]] ||
    fail "$how: does not use the moved package's library $data/library: $out"
  grep -q "^played 500 ticks, .*stop completed$" <<<"$out" || fail "$how: did not play 500 ticks to completion"
  local compiled played
  compiled=$(sed -n 's/.*compiled_max_lateral_force_N \([0-9.e+-]*\).*/\1/p' <<<"$out")
  played=$(sed -n 's/.*felt_max_lateral_force_N \([0-9.e+-]*\),.*/\1/p' <<<"$out")
  awk -v c="$compiled" -v e="$expected_force" -v p="$played" 'BEGIN {
    if (c + 0 <= 0) { print "compiled force not positive: " c; exit 1 }
    if ((c - e) > 1e-4 * e || (e - c) > 1e-4 * e) { print "compiled " c " N differs from the build tree'"'"'s " e " N"; exit 1 }
    if (p + 0 <= 0) { print "no lateral force played"; exit 1 }
    if (p > c * 1.0001) { print "played " p " N above the compiled maximum " c " N"; exit 1 }
  }' || fail "$how: forces"
}

echo "== find_package(Sandpaper) from the moved prefix"
cmake -S "$src/tests/consumer" -B "$work/cmake-build" -DCMAKE_PREFIX_PATH="$root" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="$cxxflags" -DCMAKE_FIND_PACKAGE_NO_SYSTEM_PACKAGE_REGISTRY=ON \
  > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configure against the installed package"; }
grep -q -F "$root" "$work/cmake-build/CMakeCache.txt" || fail "Sandpaper was not found in $root"
grep -i "sandpaper" "$work/configure.log" | grep -i "not exist" && fail "configure warns of a missing Sandpaper path"
grep -q -F "Sandpaper_DATA_DIR=$data" "$work/configure.log" || fail "Sandpaper_DATA_DIR is not the moved package's $data"
cmake --build "$work/cmake-build" -j2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build"; }
check_run "$work/cmake-build/play_by_name" "find_package"

echo "== pkg-config sandpaper from the moved prefix"
export PKG_CONFIG_PATH=$root/$rel_lib/pkgconfig
flags=$(pkg-config --cflags --libs sandpaper) || fail "pkg-config --cflags --libs sandpaper"
inc=$(pkg-config --variable=includedir sandpaper)
[[ $(realpath -m "$inc") == $(realpath -m "$root/include") ]] || fail "pkg-config's includedir $inc is not the install's"
# The flags carry a quoted define: use them as make would (through the shell), hence eval.
eval "\"\$cxx\" -std=c++20 $cxxflags \"\$src/tests/consumer/play_by_name.cpp\" -o \"\$work/play_by_name_pc\" $flags" \
  > "$work/pc-build.log" 2>&1 || { cat "$work/pc-build.log"; fail "build with pkg-config"; }
check_run "$work/play_by_name_pc" "pkg-config"

echo "== a C program (sandpaper/sandpaper.h) through pkg-config, linked by the C++ driver"
cflags=$(pkg-config --cflags sandpaper) libs=$(pkg-config --libs sandpaper)
eval "cc -std=c11 -Wall -Wextra -Werror $cflags -c \"\$src/tests/api/c_api_test.c\" -o \"\$work/c_api_test.o\"" \
  > "$work/c-build.log" 2>&1 || { cat "$work/c-build.log"; fail "compile the C program"; }
eval "\"\$cxx\" \"\$work/c_api_test.o\" -o \"\$work/c_consumer\" $libs -lm" >> "$work/c-build.log" 2>&1 ||
  { cat "$work/c-build.log"; fail "link the C program"; }
no_source_paths "$work/c_consumer"
out=$("$work/c_consumer" 2>&1) || fail "C program: $out"
grep -q "^c api: [0-9]* checks, 0 failed$" <<<"$out" || fail "C program: $out"
echo "C program: $out"

echo "== the installed CLI and player, from the moved prefix"
no_source_paths "$root/bin/sandpaper"
no_source_paths "$root/bin/sandpaper-play"
out=$("$root/bin/sandpaper" compile -e corduroy -o "$work/corduroy.patch" 2>&1) || fail "installed sandpaper compile: $out"
# A picture: the moved program finds its picture module from where it lies (compiler/image_io.hpp).
out=$("$root/bin/sandpaper" compile "$src/examples/grass.hmat" -o "$work/grass.patch" 2>&1) ||
  fail "installed sandpaper compile of a picture: $out"
out=$("$root/bin/sandpaper" run "$work/corduroy.patch" --duration 0.2 --virtual-clock 2>&1) ||
  fail "installed sandpaper run (through the installed sandpaper-play): $out"
echo "sandpaper run: $(tail -1 <<<"$out")"
# The curator's commands, when built (SANDPAPER_TEST_CURATION=ON): the index beside the installed library.
if [[ ${SANDPAPER_TEST_CURATION:-ON} == ON ]]; then
  out=$("$root/bin/sandpaper" library search corduroy 2>&1) || fail "installed sandpaper library search: $out"
  grep -q corduroy <<<"$out" || fail "installed library search does not find corduroy: $out"
fi

# The Python module, when built (SANDPAPER_TEST_PYTHON: the interpreter it was built for): installed
# into the prefix's dist-packages, it finds the data from where it lies.
if [[ -n ${SANDPAPER_TEST_PYTHON:-} ]]; then
  echo "== the Python module, installed, from the moved prefix"
  mod=$(find "$root" -name 'sandpaper*.so' -path '*-packages*' | head -1)
  [[ -n $mod ]] || fail "the Python module was not installed under $root"
  no_source_paths "$mod"
  out=$(cd "$work" && PYTHONPATH=$(dirname "$mod") "$SANDPAPER_TEST_PYTHON" -c '
import sandpaper
lib = sandpaper.Library()
print("library", lib.library_dir)
print("corduroy", lib.compile("corduroy").compiled_max_lateral_force_N)' 2>&1) || fail "import the installed module: $out"
  echo "python: $out"
  reported=$(sed -n 's/^library //p' <<<"$out")
  [[ $(realpath -m "$reported") == $(realpath -m "$data/library") ]] || fail "the installed module does not use $data/library: $out"
fi

echo "== the data gone: one error naming both directories"
mv "$data" "$data.away"
out=$("$work/cmake-build/play_by_name" corduroy 2>&1) && fail "played without its data: $out"
echo "without data: $out"
grep -q -F "no library directory at $data/library (chosen by the package this program was built against)" <<<"$out" &&
  grep -q -F "no calibration directory at $data/calibration" <<<"$out" && grep -q -F "SANDPAPER_DATA_DIR" <<<"$out" ||
  fail "the error does not name both missing directories and the override: $out"
out=$(SANDPAPER_DATA_DIR=$data.away "$work/cmake-build/play_by_name" corduroy 2>&1) || fail "SANDPAPER_DATA_DIR not honoured: $out"
grep -q -F "library $data.away/library" <<<"$out" || fail "SANDPAPER_DATA_DIR not used: $out"
mv "$data.away" "$data"
echo "PASS"
