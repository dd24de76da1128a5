#!/usr/bin/env bash
# OpenImageIO is loaded only for pictures (compiler/include/sandpaper/compiler/image_io.hpp): the
# CLI links none of its ~260 libraries, commands without a picture never load it, and a missing or
# foreign module is an internal error (exit 3) that says where it looked and how to mend it.
#   image_module_test.sh BIN_DIR SOURCE_DIR
set -u
bin=$1
src=$2
sp="$bin/sandpaper"
module="$bin/../lib/sandpaper/libsandpaper_image_io.so"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

ldd "$sp" >"$tmp/ldd" || bad "ldd sandpaper failed"
grep -qiE 'OpenImageIO|opencv|avcodec' "$tmp/ldd" && bad "sandpaper links the picture libraries: $(grep -iE 'OpenImageIO|opencv|avcodec' "$tmp/ldd" | head -3)" || ok
ldd "$module" | grep -q 'libOpenImageIO' && ok || bad "the module $module does not link OpenImageIO (or ldd sees nothing)"

# With no module at all, what needs no picture still works...
export SANDPAPER_IMAGE_IO="$tmp/absent.so"
"$sp" compile "$src/examples/corduroy.hmat" -o "$tmp/c.patch" >/dev/null 2>"$tmp/err" && ok || bad "compile corduroy without the module: $(cat "$tmp/err")"
"$sp" inspect "$tmp/c.patch" >/dev/null 2>"$tmp/err" && ok || bad "inspect without the module: $(cat "$tmp/err")"
# ...and a picture is an internal error naming the place it looked and the way out.
"$sp" compile "$src/examples/grass.hmat" -o "$tmp/g.patch" >"$tmp/out" 2>"$tmp/err"; rc=$?
[ "$rc" -eq 3 ] && ok || bad "a picture without the module: exit $rc, wanted 3: $(cat "$tmp/err")"
grep -q "internal error" "$tmp/err" && grep -qF "$tmp/absent.so: No such file" "$tmp/err" && grep -q "set SANDPAPER_IMAGE_IO" "$tmp/err" && ok ||
  bad "the error should name where it looked and how to mend it: $(cat "$tmp/err")"
[ ! -e "$tmp/g.patch" ] && ok || bad "a patch was written although the picture could not be read"
# A shared library that is not the module (no table) is refused, not called.
other=$(ldconfig -p | awk '/libz\.so\.1 /{print $NF; exit}')
SANDPAPER_IMAGE_IO="$other" "$sp" compile "$src/examples/grass.hmat" -o "$tmp/g.patch" >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 3 ] && grep -q "built for another Sandpaper" "$tmp/err" && ok || bad "$other as the module: exit $rc: $(cat "$tmp/err")"
unset SANDPAPER_IMAGE_IO

# With the module beside the build, the picture compiles.
"$sp" compile "$src/examples/grass.hmat" -o "$tmp/g.patch" >/dev/null 2>"$tmp/err" && [ -s "$tmp/g.patch" ] && ok ||
  bad "compile grass.hmat with the module: $(cat "$tmp/err")"
echo "image module: $pass passed, $fail failed"
