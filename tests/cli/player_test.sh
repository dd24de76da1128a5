#!/usr/bin/env bash
# The runtime-only player (docs/performance.md, "A player that is only a runtime"):
# sandpaper-play links no compiler or image library, `sandpaper run FILE.patch` hands the run to it,
# and it plays, reports stalls and stops on SIGINT like `sandpaper run`.
#   player_test.sh BIN_DIR SOURCE_DIR
set -u
bin=$1
src=$2
sp="$bin/sandpaper"
play="$bin/sandpaper-play"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

ldd "$play" >"$tmp/ldd" || bad "ldd failed"
grep -qi 'OpenImageIO' "$tmp/ldd" && bad "sandpaper-play links OpenImageIO: $(grep -i OpenImageIO "$tmp/ldd")" || ok
grep -qiE 'opencv|avcodec|gst|Eigen|boost' "$tmp/ldd" && bad "sandpaper-play links an image or statistics library" || ok
grep -q 'libusb-1.0' "$tmp/ldd" && ok || bad "sandpaper-play should link libusb (it plays USB joysticks)"
# The check above can fail: the picture module the full CLI loads does link OpenImageIO.
ldd "$bin/../lib/sandpaper/libsandpaper_image_io.so" | grep -qi 'OpenImageIO' && ok ||
  bad "the ldd check is not seeing libraries (the picture module links OpenImageIO)"

"$sp" compile -e 'roughness 0.6; grating period 2.5 mm' -o "$tmp/g.patch" >/dev/null || bad "compile"
"$sp" run "$tmp/g.patch" --duration 0.2 --json >"$tmp/run.json" 2>"$tmp/err" || bad "run .patch: exit $?"
grep -q '"player": "sandpaper-play"' "$tmp/run.json" && ok || bad "sandpaper run FILE.patch did not hand the run to sandpaper-play: $(grep player "$tmp/run.json")"
grep -q '"stalls": {' "$tmp/run.json" && ok || bad "run --json has no stalls"
grep -q '"stop_cause": "completed"' "$tmp/run.json" && ok || bad "run did not complete"
# A material (not a compiled patch) is still compiled and played by sandpaper itself.
"$sp" run -e 'roughness 0.6; grating period 2.5 mm' --duration 0.2 --json >"$tmp/run2.json" 2>/dev/null || bad "run -e"
grep -q '"player": "sandpaper"' "$tmp/run2.json" && ok || bad "run -e should play in-process"
# A workspace program (.wsp) plays in the player exactly as the workspace compiled in-process does
# (virtual clock: deterministic, so the two reports must agree in every number).
"$sp" compile "$src/examples/workspace/sampler.hws" -o "$tmp/s.wsp" >/dev/null 2>"$tmp/err" || bad "compile -o .wsp: $(cat "$tmp/err")"
"$sp" run "$tmp/s.wsp" --virtual-clock --json >"$tmp/wsp.json" 2>"$tmp/err" || bad "run .wsp: $(tail -2 "$tmp/err")"
"$sp" run "$src/examples/workspace/sampler.hws" --virtual-clock --json >"$tmp/hws.json" 2>/dev/null || bad "run .hws"
# Every key but "player" equal, as numbers and strings (jq, not Python: the core build has none).
jq -e -n --slurpfile a "$tmp/wsp.json" --slurpfile b "$tmp/hws.json" \
  '$a[0].player == "sandpaper-play" and $b[0].player == "sandpaper" and $a[0].touched_patches > 1
   and ($a[0] | del(.player)) == ($b[0] | del(.player))' >/dev/null && ok ||
  bad "the .wsp run differs from the .hws run: $(jq -n -c --slurpfile a "$tmp/wsp.json" --slurpfile b "$tmp/hws.json" \
    '[$a[0] | to_entries[] | select(.value != $b[0][.key]) | {(.key): [.value, $b[0][.key]]}]')"
# The player refuses what it cannot play, with the way out.
"$play" "$src/examples/corduroy.hmat" >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && ok || bad "sandpaper-play of a .hmat: exit $rc, wanted 2"
grep -q 'compile it first' "$tmp/err" && ok || bad "sandpaper-play should say to compile first: $(cat "$tmp/err")"
"$play" "$tmp/g.patch" --spin-margin 5000 >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q 'spin margin' "$tmp/err" && ok || bad "a spin margin over a period must be refused (exit $rc)"
# Ctrl-C: the run stops at its next tick with exit 0; the signal goes once the handlers are installed
# (SigCgt in /proc), never after a guessed sleep.
"$sp" run "$tmp/g.patch" --duration 0 >"$tmp/sig.out" 2>"$tmp/sig.err" &
pid=$!
for _ in $(seq 3000); do
  exe=$(readlink "/proc/$pid/exe" 2>/dev/null)
  mask=$(awk '/^SigCgt:/{print $2}' "/proc/$pid/status" 2>/dev/null)
  [ "${exe##*/}" = sandpaper-play ] && [ -n "$mask" ] && (( (0x$mask & 0x4002) == 0x4002 )) && break
  sleep 0.01
done
kill -INT "$pid"
wait "$pid"; rc=$?
[ "$rc" -eq 0 ] && ok || bad "SIGINT to a run until stopped: exit $rc, wanted 0"
grep -q 'until Ctrl-C' "$tmp/sig.out" && ok || bad "a run with --duration 0 should say it plays until Ctrl-C"
grep -q 'stopped: stopped by signal' "$tmp/sig.out" && ok || bad "SIGINT is the stop cause: $(tail -2 "$tmp/sig.out")"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
