#!/usr/bin/env bash
# A clone has no ../shared: the release preset configures a copy of the tree with nothing beside it,
# says in one line that the USB lab is off and how to turn it on, and ctest's summary names each of
# the lab's tests as not run. Configure only; the README's commands in such a clone are run by hand
# (docs/performance.md gives their times).
#   without_shared_test.sh SOURCE_DIR CMAKE CTEST
set -uo pipefail
src=$1 cmake=$2 ctest=$3
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The tree as a clone has it: tracked files and new ones not ignored, no build folders, no ../shared.
copy=$tmp/sandpaper
mkdir "$copy"
if git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  (cd "$src" && git ls-files -z --cached --others --exclude-standard | xargs -0 -I{} cp --parents -P {} "$copy/" 2>/dev/null)
else
  (cd "$src" && tar --exclude='./build*' --exclude='*/node_modules' -cf - .) | (cd "$copy" && tar -xf -)
fi
# What tools/install-deps.sh would have installed in the clone: the npm packages.
for d in studio/web tests/gltf; do
  [ -d "$src/$d/node_modules" ] && ln -s "$src/$d/node_modules" "$copy/$d/node_modules"
done
[ ! -e "$tmp/shared" ] && [ -f "$copy/CMakeLists.txt" ] && ok "a copy of the tree with no ../shared beside it" \
  || bad "the copy is not as a clone has it"

if "$cmake" -S "$copy" --preset release >"$tmp/configure.log" 2>&1; then
  ok "the release preset configures"
else
  bad "the release preset does not configure:"$'\n'"$(tail -20 "$tmp/configure.log")"
fi
lines=$(grep -c 'USB lab: off' "$tmp/configure.log")
[ "$lines" = 1 ] && ok "configure says once that the USB lab is off" || bad "'USB lab: off' said $lines times"
grep 'USB lab: off' "$tmp/configure.log" | grep -q -- '-DSANDPAPER_OPENFFBOARD_DIR=.*160af9107db2606150f01586d6c092b6be065d7c' \
  && ok "and how to turn it on (SANDPAPER_OPENFFBOARD_DIR at the firmware's commit)" \
  || bad "the line does not say how to turn it on: $(grep 'USB lab' "$tmp/configure.log")"
[ -z "$(find "$copy/build" -type d -name 'openffboard_firmware.dir' -print -quit)" ] \
  && ok "the firmware is not in the build" || bad "the build still compiles the firmware"

# Nothing needs building to read the summary: the lab's tests are registered disabled.
"$ctest" --test-dir "$copy/build" -R "^(usb-lab\.|architecture\.include_arrows$)" >"$tmp/ctest.log" 2>&1
for t in enumerate bus play hidraw evdev direction studio experiment fault-unplug fault-reset fault-stale fault-sigint fault-stall fault-late \
    hidraw-unplug hidraw-reset hidraw-stale hidraw-sigint evdev-unplug evdev-reset evdev-sigint evdev-uncalibrated \
    wheel-hidraw wheel-evdev wheel-usb wheel-evdev-unplug sidewinder-evdev firmware hid_pid_device scripted_hand; do
  grep -qE "usb-lab\.$t \(Disabled\)" "$tmp/ctest.log" && ok "the summary names usb-lab.$t as not run" \
    || bad "usb-lab.$t is not named as not run: $(tail -5 "$tmp/ctest.log")"
done
grep -q "tests failed" "$tmp/ctest.log" && grep -q "0 tests failed" "$tmp/ctest.log" \
  && ok "and counts none of them failed" || bad "ctest: $(grep -i 'tests' "$tmp/ctest.log" | tail -2)"

echo "$pass passed, $fail failed"
