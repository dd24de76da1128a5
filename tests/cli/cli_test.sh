#!/usr/bin/env bash
# End-to-end checks of the sandpaper CLI. Usage: cli_test.sh path/to/sandpaper (run from the source tree).
set -u
sp=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
expect_exit() {  # expect_exit CODE DESCRIPTION -- command...
  local want=$1 what=$2; shift 3
  "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  if [ "$got" -eq "$want" ]; then ok; else bad "$what: exit $got, wanted $want"; cat "$tmp/err"; fi
}
has() {  # has FILE REGEX DESCRIPTION
  if grep -Eq -- "$2" "$1"; then ok; else bad "$3: /$2/ not in $1"; head -20 "$1"; fi
}

# The main job: compile the example, inspect it, play it on the simulated joystick.
expect_exit 0 "compile example" -- "$sp" compile examples/corduroy.hmat -o "$tmp/c.patch"
[ -s "$tmp/c.patch" ] && ok || bad "compile wrote no patch"
expect_exit 0 "inspect --json" -- "$sp" inspect "$tmp/c.patch" --json
has "$tmp/out" '"max_lateral_force_N": 1\.705' "inspect shows the compiled force"
has "$tmp/out" '"kind": "grating"' "inspect lists the grating term"
expect_exit 0 "run patch on sim (virtual clock)" -- "$sp" run "$tmp/c.patch" --device sim --virtual-clock --json --trace "$tmp/t.csv"
for key in '"ticks": 2000' '"rate_hz": 1000' '"p50"' '"p99"' '"overruns": 0' '"max_lateral_force_N": 1\.70' '"roughness": 0\.5[45]' '"stop_reason": "completed"'; do
  has "$tmp/out" "$key" "run --json"
done
[ "$(wc -l <"$tmp/t.csv")" -eq 2001 ] && ok || bad "trace should hold a header and 2000 ticks"
has "$tmp/t.csv" '^t_s,x_m,y_m,force_x_N,force_y_N$' "trace header"

# Same input, same bytes.
"$sp" compile examples/corduroy.hmat -o "$tmp/c2.patch" >/dev/null 2>&1
cmp -s "$tmp/c.patch" "$tmp/c2.patch" && ok || bad "compiling twice gave different bytes"

# A library entry by name and the real photograph, each compiled and played in real time.
expect_exit 0 "run -e corduroy (real time)" -- "$sp" run -e corduroy --device sim --duration 0.3
has "$tmp/out" 'achieved' "run prints the achieved rate"
has "$tmp/out" 'max lateral force' "run prints the forces felt"
expect_exit 0 "run gravel example" -- "$sp" run examples/gravel.hmat --device sim --duration 0.3 --hand circle --speed 30 --amplitude 20 --json
has "$tmp/out" '"material": "gravel-path"' "gravel run"
expect_exit 0 "explain --json" -- "$sp" explain -e "like denim-twill; roughness coarse" --json
has "$tmp/out" '"texture.period"' "explain provenance"
has "$tmp/out" '"layer": "perceptual"' "explain layers"
expect_exit 0 "explain text" -- "$sp" explain examples/corduroy.hmat
has "$tmp/out" 'representative +like corduroy' "explain shows the representative layer"
expect_exit 0 "library" -- "$sp" library

# Bad input: a clear diagnostic, non-zero exit, and the existing output untouched.
echo keep >"$tmp/out.patch"
expect_exit 1 "conflicting file" -- "$sp" compile tests/golden/diagnostics/conflict.hmat -o "$tmp/out.patch"
has "$tmp/err" 'conflict.hmat:4:3: error\[E0302\]' "diagnostic with file:line:col"
[ "$(cat "$tmp/out.patch")" = keep ] && ok || bad "a failed compile changed its output file"
[ "$(ls -A "$tmp" | grep -c tmp-)" -eq 0 ] && ok || bad "temporary files left behind"
expect_exit 1 "unknown name" -- "$sp" run -e velvet --device sim
has "$tmp/err" 'E0301' "unknown library entry"
expect_exit 1 "missing file" -- "$sp" compile no/such/file.hmat
expect_exit 1 "missing image" -- "$sp" compile tests/golden/diagnostics/missing-image.hmat -o "$tmp/x.patch"
[ ! -e "$tmp/x.patch" ] && ok || bad "a failed compile created its output"
expect_exit 1 "failed compile --json" -- "$sp" compile -e "grating period 2 mm" --json
has "$tmp/out" '"ok": false' "json failure object"
expect_exit 2 "rate out of range" -- "$sp" run -e corduroy --device sim --rate 800
has "$tmp/err" '900' "rate error names the range"
expect_exit 2 "unknown device" -- "$sp" compile -e corduroy --device phantom
expect_exit 2 "unwritable trace is refused before playing" -- "$sp" run -e corduroy --virtual-clock --trace /nonexistent-dir/t.csv
expect_exit 0 "spring only" -- "$sp" run -e "spring 200 N/m" --device sim --virtual-clock --json
has "$tmp/out" '"roughness": null' "no roughness without a texture"
printf 'SNDPATCHgarbage' >"$tmp/broken.patch"
expect_exit 1 "corrupt patch" -- "$sp" inspect "$tmp/broken.patch"

# Real images: the stylus-relief and grass examples play; `array` writes Sandpaper's array files.
expect_exit 0 "run brick-relief (depth + press)" -- "$sp" run examples/brick-relief.hmat --device sim --virtual-clock --hand circle --speed 20 --amplitude 30 --json
has "$tmp/out" '"material": "brick-relief"' "brick-relief run"
has "$tmp/out" '"stop_reason": "completed"' "brick-relief completes"
expect_exit 0 "explain brick-relief" -- "$sp" explain examples/brick-relief.hmat
has "$tmp/out" 'texture.max_lateral_force.*press 2 N x steepest slope' "the stylus force is computed and explained"
expect_exit 0 "run grass" -- "$sp" run examples/grass.hmat --device sim --duration 0.3
expect_exit 0 "array with shade" -- "$sp" array library/images/brick.png --size 80mm --sampling 0.4mm --invert -o "$tmp/b.depth" --shade "$tmp/b.shade"
[ "$(wc -c <"$tmp/b.depth")" -eq $((200 * 200 + 4)) ] && ok || bad ".depth should be 200 x 200 + 4 bytes"
[ "$(wc -c <"$tmp/b.shade")" -eq $((200 * 200 + 4)) ] && ok || bad ".shade should be 200 x 200 + 4 bytes"
[ "$(head -c 4 "$tmp/b.depth" | od -An -tx1 | tr -d ' \n')" = 00c800c8 ] && ok || bad ".depth header is big-endian 200, 200"
expect_exit 0 "compile the written .depth" -- "$sp" compile -e "heightmap \"$tmp/b.depth\" size 80 mm depth 0.5 mm press 2 N" --json
has "$tmp/out" '"ok": true' ".depth compiles as a height map"
expect_exit 1 ".shade is not heights" -- "$sp" compile -e "heightmap \"$tmp/b.shade\" size 80 mm amplitude 1 N"
has "$tmp/err" 'E0406' ".shade refused"
cp "$tmp/b.depth" "$tmp/keep.depth"
expect_exit 1 "array of a missing image" -- "$sp" array no/such.png --size 80mm -o "$tmp/b.depth"
has "$tmp/err" "E0401.*no/such.png" "array names the unreadable file"
cmp -s "$tmp/b.depth" "$tmp/keep.depth" && ok || bad "a failed array changed its output"
expect_exit 1 "array of an unknown channel" -- "$sp" array tests/golden/diagnostics/images/channels.exr --size 10mm --channel Z -o "$tmp/c.depth"
has "$tmp/err" "its channels are R, G, B, height" "array lists the channels"
expect_exit 2 "array output not .depth" -- "$sp" array library/images/brick.png --size 80mm -o "$tmp/b.png"
expect_exit 2 "array size without unit" -- "$sp" array library/images/brick.png --size 80 -o "$tmp/b.depth"
[ "$(ls -A "$tmp" | grep -c tmp-)" -eq 0 ] && ok || bad "temporary files left behind"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
