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

# Real-time runs here check what a run does (its exit, its report, its stop on a signal), not how
# punctual this machine is: CI machines are loaded, and a 50 ms stall of the servo thread (with or
# without SCHED_FIFO) stops a run (deadline_missed, exit 1). So they take a guard of 10 minutes;
# the guard itself is tested on a scripted clock (StopCauses.DeadlineMissedForLongerThanAllowed).
RT=(--deadline-guard 600000)

# compile --dump prints one phase's output, as the golden files per phase hold it, and writes nothing.
expect_exit 0 "compile --dump resolved" -- "$sp" compile examples/corduroy.hmat --dump resolved
cmp -s "$tmp/out" tests/golden/stages/examples/corduroy.resolved && ok || bad "--dump resolved differs from the golden resolved material"
expect_exit 0 "compile --dump syntax" -- "$sp" compile -e "grating period 2 mm; roughness 0.4" --dump syntax
has "$tmp/out" '^1:1 grating period=2 mm \[0.002\]$' "the syntax of an -e expression"
expect_exit 1 "compile --dump tokens of a broken statement" -- "$sp" compile -e 'grating period "x' --dump tokens
has "$tmp/err" 'E0' "the lexer's error is reported"
expect_exit 2 "compile --dump with -o" -- "$sp" compile examples/corduroy.hmat --dump syntax -o "$tmp/dump.patch"
[ ! -e "$tmp/dump.patch" ] && [ ! -e examples/corduroy.patch ] && ok || bad "compile --dump wrote a patch"
# The main job: compile the example, inspect it, play it on the simulated joystick.
expect_exit 0 "compile example" -- "$sp" compile examples/corduroy.hmat -o "$tmp/c.patch"
[ -s "$tmp/c.patch" ] && ok || bad "compile wrote no patch"
expect_exit 0 "inspect --json" -- "$sp" inspect "$tmp/c.patch" --json
has "$tmp/out" '"compiled_max_lateral_force_N": 1\.705' "inspect shows the compiled force"
has "$tmp/out" '"kind": "grating"' "inspect lists the grating term"
expect_exit 0 "run patch on sim (virtual clock)" -- "$sp" run "$tmp/c.patch" --device sim --virtual-clock --json --trace "$tmp/t.csv"
for key in '"ticks": 2000' '"rate_hz": 1000' '"p50"' '"p99"' '"overruns": 0' '"felt_max_lateral_force_N": 1\.70' '"felt_peak_N": 1\.70' '"felt_roughness": 0\.5[45]' '"compiled_roughness": 0\.55' '"stop_reason": "completed"'; do
  has "$tmp/out" "$key" "run --json"
done
[ "$(wc -l <"$tmp/t.csv")" -eq 2001 ] && ok || bad "trace should hold a header and 2000 ticks"
has "$tmp/t.csv" '^t_s,x_m,y_m,force_x_N,force_y_N$' "trace header"

# Same input, same bytes.
"$sp" compile examples/corduroy.hmat -o "$tmp/c2.patch" >/dev/null 2>&1
cmp -s "$tmp/c.patch" "$tmp/c2.patch" && ok || bad "compiling twice gave different bytes"

# A library entry by name and the real photograph, each compiled and played in real time.
expect_exit 0 "run -e corduroy (real time)" -- "$sp" run -e corduroy --device sim "${RT[@]}" --duration 0.3
has "$tmp/out" 'achieved' "run prints the achieved rate"
has "$tmp/out" 'max force [0-9.]+ N \(texture compiled [0-9.]+ N\)' "run prints the forces felt"

# The thesis' joystick, emulated (issue 15): 900 Hz, positions on 0.0558 mm counts, forces in whole
# joystick units (4.814 mN), tables held; the trace shows the staircase.
expect_exit 0 "emulated sandpaper-1995" -- "$sp" run -e a10p25 --device sandpaper-1995 --virtual-clock --duration 0.5 --json --trace "$tmp/t95.csv"
has "$tmp/out" '"rate_hz_target": 900' "the emulated joystick runs at its own 900 Hz"
has "$tmp/out" '"tables": "sample-and-hold"' "run --json says how the tables were read"
has "$tmp/out" '"warnings": \[' "run --json carries the compiler's warnings"
python3 - "$tmp/t95.csv" <<'PY' && ok || bad "the emulated trace is not on encoder counts and joystick units"
import csv, sys
step, unit = 0.0558e-3, 0.00481417274   # calibration/devices/sandpaper-1995.toml
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 450, len(rows)
for r in rows:
    for v, q in ((float(r["x_m"]), step), (float(r["force_x_N"]), unit)):
        assert abs(v / q - round(v / q)) < 1e-6, (v, q)
# After the 50 ms start ramp: only the seed table's levels.
levels = {round(abs(float(r["force_x_N"])) / unit) for r in rows if float(r["t_s"]) >= 0.05} - {0}
assert 1 <= len(levels) <= 15, levels   # the 8-bit seed's levels, held: a staircase, not a ramp
PY
# Roughness is predicted from the texture's own force: velvet's nap friction adds to what the hand
# meets (the largest |F| is over twice the grating's 0.23 N) but not to its roughness (compiled 0.12).
for how in "--speed 20" "--hand circle --speed 20"; do
  expect_exit 0 "velvet $how" -- "$sp" run -e "like velvet" --device sim --virtual-clock --duration 2 $how --json
  python3 - "$tmp/out" <<'PY' && ok || bad "velvet's roughness counted its friction ($how)"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["felt_max_lateral_force_N"] > 2 * j["compiled_max_lateral_force_N"], j["felt_max_lateral_force_N"]
assert j["felt_texture_max_N"] <= j["compiled_max_lateral_force_N"] * 1.001, j["felt_texture_max_N"]
assert abs(j["felt_roughness"] - j["compiled_roughness"]) < 0.1 * j["compiled_roughness"], (j["felt_roughness"], j["felt_roughness_from"])
PY
done
expect_exit 0 "a compiled patch on the emulated joystick" -- "$sp" compile -e a10p25 --device sandpaper-1995 -o "$tmp/a95.patch"
expect_exit 0 "sandpaper-play plays it" -- "$sp" run "$tmp/a95.patch" --device sandpaper-1995 --virtual-clock --duration 0.2 --json
has "$tmp/out" '"player": "sandpaper-play"' "the runtime-only player plays the emulated device"
has "$tmp/out" '"position_step_mm": 0\.0558' "the player quantises positions"
expect_exit 2 "the emulated joystick has one rate" -- "$sp" run -e a10p25 --device sandpaper-1995 --rate 1000 --virtual-clock
expect_exit 2 "a USB device is not emulated" -- "$sp" run -e a10p25 --device openffboard-2axis --virtual-clock
expect_exit 0 "explain on sandpaper-1995" -- "$sp" explain -e a10p25 --device sandpaper-1995
has "$tmp/out" 'position samples per period' "explain says what the emulated device's quantisation does"
has "$tmp/out" 'distinct force levels sent' "explain counts the levels the emulated device sends"
has "$tmp/out" 'felt at speed' "explain predicts the force felt at speed"
# A wheel: the patch's millimetres along its rim, in degrees (openffboard-wheel.toml: a 150 mm rim,
# so 180 / (150 pi) = 0.382 deg per mm, and 0.15 N*m per N).
expect_exit 0 "explain on the wheel" -- "$sp" explain -e "grating period 2.5 mm; roughness 0.5" --device openffboard-wheel
has "$tmp/out" 'wheel     one axis along the rim: 1 mm of rim turns the wheel 0\.382 deg \(rim radius 150 mm, 900 deg lock to lock\); 1 N at the rim is 0\.15 N\*m' "explain says how the wheel's millimetres are degrees"
expect_exit 0 "explain --json on the wheel" -- "$sp" explain -e "grating period 2.5 mm; roughness 0.5" --device openffboard-wheel --json
has "$tmp/out" '"deg_per_mm": 0\.3819718' "explain --json gives the wheel's degrees per mm"
expect_exit 0 "explain --json felt_at_speed" -- "$sp" explain -e "grating period 0.7 mm; roughness 0.5" --json
has "$tmp/out" '"felt_at_speed"' "explain --json has felt_at_speed"
has "$tmp/out" '"speed_mm_s": 200' "felt_at_speed lists 200 mm/s"
expect_exit 0 "explain --design-speed" -- "$sp" explain -e "roughness 0.6; grating period 2.5 mm" --design-speed 200
has "$tmp/out" 'remedies at 200 mm/s \(the design speed' "explain measures the remedies at the stated design speed"
has "$tmp/out" 'smoothing [0-9.]+ mm on the grating: [0-9.]+ N, roughness' "explain offers smoothing for the design speed"
expect_exit 0 "explain --design-speed --json" -- "$sp" explain -e "roughness 0.6; grating period 2.5 mm" --design-speed 200 --json
has "$tmp/out" '"design_speed": true' "explain --json marks the design speed's remedies"
# A design speed that is no hand speed is a usage error naming the unit, not ignored and not a
# range whose limit prints with 309 digits (DBL_MAX in full).
for bad_speed in -1 0 nan inf; do
  expect_exit 2 "explain --design-speed $bad_speed" -- "$sp" explain -e "roughness 0.6; grating period 2.5 mm" --design-speed "$bad_speed"
  has "$tmp/err" "--design-speed: must be a finite hand speed above 0 mm/s, not $bad_speed" "explain --design-speed $bad_speed says what a design speed is"
  if grep -Eq '[0-9]{20}' "$tmp/err"; then bad "explain --design-speed $bad_speed prints a 20-digit number"; cat "$tmp/err"; else ok; fi
done
expect_exit 0 "explain a spring" -- "$sp" explain -e "spring 100 N/m"
if grep -q '^maps' "$tmp/out"; then bad "explain of a material without texture prints the roughness maps"; else ok; fi
expect_exit 0 "Appendix B's Bowl by name" -- "$sp" run -e Bowl --device sim --virtual-clock --duration 0.2 --hand circle

# Force laws and physics models (Appendix B, 3.2.2), and thesis stimuli by name.
expect_exit 0 "run the Slick example" -- "$sp" run examples/laws/slick.hmat --device sim --duration 0.5 --hand circle --virtual-clock
has "$tmp/err" 'W0306' "a non-passive law warns"
has "$tmp/out" 'no texture: the roughness map does not apply' "no roughness for force laws"
expect_exit 0 "run the brick" -- "$sp" run examples/laws/brick-on-a-spring.hmat --device sim --duration 0.5 --virtual-clock --json
has "$tmp/out" '"stop_reason": "completed"' "the brick plays to the end"
expect_exit 0 "explain a version-1 stimulus by name" -- "$sp" explain -e barsB15W20_2Fmore
has "$tmp/out" 'thesis stimulus' "explain names the generator"
has "$tmp/out" 'force levels' "explain counts the distinct force levels"
expect_exit 1 "an unknown force law" -- "$sp" compile -e "force Bumpp stiffness 10 N/m"
has "$tmp/err" 'E0211.*Bumpp' "unknown law named"
has "$tmp/err" 'did you mean `Bump`' "law suggestion"
expect_exit 0 "run gravel example" -- "$sp" run examples/gravel.hmat --device sim "${RT[@]}" --duration 0.3 --hand circle --speed 30 --amplitude 20 --json
has "$tmp/out" '"material": "gravel-path"' "gravel run"
expect_exit 0 "explain --json" -- "$sp" explain -e "like denim-twill; roughness coarse" --json
has "$tmp/out" '"texture.period"' "explain provenance"
has "$tmp/out" '"layer": "perceptual"' "explain layers"
expect_exit 0 "explain text" -- "$sp" explain examples/corduroy.hmat
has "$tmp/out" 'representative +like corduroy' "explain shows the representative layer"

# What the thesis found (calibration/knowledge/): believable region, 2.5 mm class, group, JND steps.
expect_exit 0 "explain a Table 8 stimulus" -- "$sp" explain -e a3p25
has "$tmp/out" 'believable +yes: grating' "explain: believable region"
has "$tmp/out" 'period class +transitional .*goes with the textural elements' "explain: the 2.5 mm class"
has "$tmp/out" 'group +flat textured surfaces .*sometimes sorted as rolling hills' "explain: the 6.3.7 group"
has "$tmp/out" 'force JND +[0-9.]+ JND above fine \([0-9.]+ gf\), [0-9.]+ JND below medium' "explain: JND steps to the named levels"
has "$tmp/out" 'force-jnd\.toml' "explain: the JND's source"
has "$tmp/out" 'comparison +minsky1995-fig20 .*p 0\.33.*adds nothing' "explain: what Figure 20 says the period adds"
has "$tmp/out" 'comparison +lederman1972 +slope 0\.25' "explain: Lederman's fingertip slope"
expect_exit 0 "explain --json knowledge" -- "$sp" explain -e a19p100 --json
has "$tmp/out" '"group": "moguls"' "explain --json: the group"
has "$tmp/out" '"believable": true' "explain --json: believability"
has "$tmp/out" '"level_below": \{' "explain --json: the JND neighbours"
expect_exit 0 "explain a wide grating outside Table 8" -- "$sp" explain -e "grating period 20 mm hill 50% amplitude 400 ju"
has "$tmp/out" 'group +moguls' "a grating beyond 10 mm still gets a group"
has "$tmp/out" 'the grouping extrapolates' "explain says when the grouping extrapolates"
expect_exit 0 "a weak wide grating warns" -- "$sp" compile -e "grating period 12 mm amplitude 20 pu"
has "$tmp/err" 'W0330.*low confidence' "W0330 outside the believable region"
expect_exit 0 "explain Noise35" -- "$sp" explain -e Noise35
has "$tmp/out" 'confidence +thesis non-textural Noise35: mean 65 % \(\+/- 38 %\)' "explain: a non-textural's confidence"
expect_exit 0 "library" -- "$sp" library
has "$tmp/out" '^corduroy +textiles +roughness 0.45 ' "library lists each entry with its family and roughness"
has "$tmp/out" '^sandpaper-80-grit .*\[deprecated: use sandpaper-p80\]' "library marks deprecated entries"
expect_exit 0 "explain an entry shows its sources" -- "$sp" explain -e "like pinwale-corduroy"
has "$tmp/out" '^  library corduroy \(library/textiles/corduroy.hmat, CC0-1.0\)' "explain lists the like chain's sourced entries"
has "$tmp/out" '^ +derived: 16 wales per inch, 25.4 mm / 16' "explain shows a source note with its kind"
expect_exit 0 "explain a plain material" -- "$sp" explain -e "grating period 2 mm amplitude 1 N"
grep -q '^sources (' "$tmp/out" && bad "a material with no sourced entries has no sources section" || ok
expect_exit 0 "library --json" -- "$sp" library --json
has "$tmp/out" '"family": "textiles"' "library --json gives families"

# Bad input: a clear diagnostic, non-zero exit, and the existing output untouched.
echo keep >"$tmp/out.patch"
expect_exit 1 "conflicting file" -- "$sp" compile tests/golden/diagnostics/conflict.hmat -o "$tmp/out.patch"
has "$tmp/err" 'conflict.hmat:4:3: error\[E0302\]' "diagnostic with file:line:col"
[ "$(cat "$tmp/out.patch")" = keep ] && ok || bad "a failed compile changed its output file"
[ -z "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '*tmp-*')" ] && ok || bad "temporary files left behind"
expect_exit 1 "unknown name" -- "$sp" run -e unobtainium --device sim
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
expect_exit 2 "a command without its subcommand is a usage error" -- "$sp" calibrate
expect_exit 2 "an unknown option is a usage error" -- "$sp" compile -e corduroy --bogus
expect_exit 0 "--help" -- "$sp" --help
expect_exit 0 "spring only" -- "$sp" run -e "spring 200 N/m" --device sim --virtual-clock --json
has "$tmp/out" '"felt_roughness": null' "no roughness without a texture"
has "$tmp/out" '"felt_peak_N": null' "no felt peak without a grating"
printf 'SNDPATCHgarbage' >"$tmp/broken.patch"
expect_exit 1 "corrupt patch" -- "$sp" inspect "$tmp/broken.patch"

# Workspaces of patches (thesis Appendix B): compile, explain, play on the simulated joystick.
expect_exit 0 "compile workspace" -- "$sp" compile examples/workspace/sampler.hws -o "$tmp/ws.json"
has "$tmp/ws.json" '"format": "sandpaper-workspace"' "workspace JSON format"
has "$tmp/ws.json" '"patch_count": 7' "workspace JSON patch count"
has "$tmp/ws.json" '"material": "a19p100"' "workspace JSON holds the patch programs"
expect_exit 0 "compile workspace --json" -- "$sp" compile examples/workspace/periods.hws -o "$tmp/p.json" --json
has "$tmp/out" '"ok": true' "workspace compile --json"
expect_exit 0 "explain workspace" -- "$sp" explain examples/workspace/sampler.hws
has "$tmp/out" 'patch 7 +"roughness 0.3; grating period 5 mm" +at 0 mm, 0 mm' "explain lists the patches"
has "$tmp/out" 'material a19p100; maximum lateral force 3.659 N' "explain gives each patch's force"
has "$tmp/out" 'roughness order' "explain lists the workspace's roughness order"
has "$tmp/out" '^ +[0-9]+\.[0-9]+ JND$' "explain gives JND steps between neighbours"
expect_exit 0 "a workspace with two materials within one JND" -- "$sp" compile tests/golden/workspace/within-one-jnd.hws -o "$tmp/close.json"
has "$tmp/err" 'W0503.*patch 2.*patch 1.*force JND' "W0503 names both patches"
expect_exit 0 "run workspace (virtual clock)" -- "$sp" run examples/workspace/sampler.hws --device sim --virtual-clock --json --trace "$tmp/ws.csv"
for key in '"touched_patches": 7' '"patch_count": 7' '"stop_reason": "completed"' '"direction_deg": 0.0' '"ticks": [0-9]+'; do
  has "$tmp/out" "$key" "run workspace --json"
done
has "$tmp/ws.csv" '^t_s,x_m,y_m,force_x_N,force_y_N,patch$' "workspace trace header"
has "$tmp/ws.csv" ',7$' "the trace names the front patch"
expect_exit 0 "run workspace, circle hand" -- "$sp" run examples/workspace/sampler.hws --device sim --virtual-clock --hand circle --amplitude 60 --duration 2
has "$tmp/out" 'patches +[1-7] of 7 touched' "run reports the patches touched"
has "$tmp/out" 'max \|F\|' "run reports the force per patch"
expect_exit 0 "run workspace (real time)" -- "$sp" run examples/workspace/cloths.hws --device sim "${RT[@]}" --duration 0.3
has "$tmp/out" 'achieved' "workspace real-time run"
expect_exit 1 "workspace with a patch outside" -- "$sp" compile tests/golden/workspace/outside.hws -o "$tmp/bad.json"
has "$tmp/err" 'outside.hws:4:23: error\[E0507\]' "outside diagnostic"
[ ! -e "$tmp/bad.json" ] && ok || bad "a failed workspace compile wrote its output"
expect_exit 1 "workspace material error --json" -- "$sp" run tests/golden/workspace/material-error.hws --json
has "$tmp/out" '"ok": false' "workspace json failure object"
has "$tmp/err" 'note: in the material of patch 1' "material errors point at the patch"

# Movies and shuffles (thesis Appendix B).
expect_exit 0 "movie show" -- "$sp" movie show examples/workspace/session.movie
has "$tmp/out" '3 frames' "movie show counts the frames"
expect_exit 0 "movie shuffle" -- "$sp" movie shuffle examples/workspace/session.movie --seed 7 --date 1995-06-01 --time 14:30:00 -o "$tmp/a.shuffle"
"$sp" movie shuffle examples/workspace/session.movie --seed 7 --date 1995-06-01 --time 14:30:00 -o "$tmp/b.shuffle" >/dev/null 2>&1
cmp -s "$tmp/a.shuffle" "$tmp/b.shuffle" && ok || bad "the same seed gave different shuffles"
has "$tmp/a.shuffle" '^Movie: .*examples/workspace/session.movie$' "shuffle header names the movie"
has "$tmp/a.shuffle" '^Date: 1995-06-01$' "shuffle date"
has "$tmp/a.shuffle" '^Time: 14:30:00$' "shuffle time"
[ "$(sed -n 4p "$tmp/a.shuffle")" = "" ] && ok || bad "a blank line must follow the header"
[ "$(tail -n +5 "$tmp/a.shuffle" | awk '{print $1}' | sort | tr '\n' ' ')" = "1 2 3 " ] && ok || bad "shuffle indices are not 1..3"
expect_exit 0 "movie show shuffle" -- "$sp" movie show "$tmp/a.shuffle"
has "$tmp/out" 'matches the movie' "a shuffle is checked against its movie"
mkdir -p "$tmp/m" && cp examples/workspace/*.hws examples/workspace/session.movie "$tmp/m/"
expect_exit 0 "movie shuffle, default name" -- "$sp" movie shuffle "$tmp/m/session.movie" --seed 3 --date 2024-02-29 --time 09:05:00
[ -s "$tmp/m/session-20240229-090500.shuffle" ] && ok || bad "default shuffle name"
has "$tmp/m/session-20240229-090500.shuffle" '^Movie: session.movie$' "shuffle beside its movie names it plainly"
sed -i 's/^1 /9 /' "$tmp/m/session-20240229-090500.shuffle"
expect_exit 1 "a damaged shuffle" -- "$sp" movie show "$tmp/m/session-20240229-090500.shuffle"
has "$tmp/err" 'E0523' "damaged shuffle diagnostic"
expect_exit 2 "bad --date" -- "$sp" movie shuffle examples/workspace/session.movie --seed 1 --date 1995-02-30 -o "$tmp/x.shuffle"
for _ in $(seq 1 101); do echo "sampler.hws"; done >"$tmp/m/long.movie"
expect_exit 1 "a movie over 100 frames" -- "$sp" movie show "$tmp/m/long.movie"
has "$tmp/err" 'long.movie:101:1: error\[E0511\]' "frame limit diagnostic"
echo "nowhere.hws" >"$tmp/m/missing.movie"
expect_exit 1 "a movie naming a missing workspace" -- "$sp" movie shuffle "$tmp/m/missing.movie" --seed 1
has "$tmp/err" 'E0512' "missing frame diagnostic"
# Real images: the stylus-relief and grass examples play; `array` writes Sandpaper's array files.
expect_exit 0 "run brick-relief (depth + press)" -- "$sp" run examples/brick-relief.hmat --device sim --virtual-clock --hand circle --speed 20 --amplitude 30 --json
has "$tmp/out" '"material": "brick-relief"' "brick-relief run"
has "$tmp/out" '"stop_reason": "completed"' "brick-relief completes"
expect_exit 0 "explain brick-relief" -- "$sp" explain examples/brick-relief.hmat
has "$tmp/out" 'texture.max_lateral_force.*press 2 N x steepest slope' "the stylus force is computed and explained"
expect_exit 0 "run grass" -- "$sp" run examples/grass.hmat --device sim "${RT[@]}" --duration 0.3
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

# Perceptual words beyond roughness (issue 4): every output that uses a provisional map says so.
expect_exit 0 "compile perceptual words --json" -- "$sp" compile examples/perceptual-words.hmat -o "$tmp/pw.patch" --json
has "$tmp/out" '"code": "W0320"' "compile --json carries the provisional warning"
has "$tmp/out" 'provisional map bumpiness-provisional \(calibration/maps/bumpiness-provisional.toml\)' "the warning names map and file"
has "$tmp/out" '"code": "W0321"' "compile --json carries the real-material warning"
has "$tmp/out" '"source": "[^"]* via harper-stevens1964 \(calibration/maps/harper-stevens1964.toml\)"' "provenance names map and file"
has "$tmp/err" 'warning\[W0320\]: `bumpiness 0.6`' "compile prints the warning"
expect_exit 0 "inspect the perceptual patch" -- "$sp" inspect "$tmp/pw.patch"
has "$tmp/out" 'warning W0320' "the patch file keeps the warning"
expect_exit 0 "run the perceptual patch" -- "$sp" run "$tmp/pw.patch" --device sim --virtual-clock --duration 0.2
has "$tmp/err" 'warning\[W0320\]: .*bumpiness-provisional' "run of a .patch shows its provisional warnings"
has "$tmp/err" 'warning\[W0321\]: .*harper-stevens1964' "and its real-material warnings"
for pair in "softness 0.7:harper-stevens1964" "viscosity 0.5:stevens-guirao1964" "slipperiness 0.6:ekman1965"; do
  text=${pair%%:*}; map=${pair##*:}
  expect_exit 0 "explain $text" -- "$sp" explain -e "$text"
  has "$tmp/out" "calibration $map, calibration/maps/$map.toml" "explain names the map of $text"
  has "$tmp/out" "source: " "explain names the source of $text"
  has "$tmp/out" "domain: .*real material" "explain names the domain of $text"
  if grep -q W0320 "$tmp/out" "$tmp/err"; then bad "$text warned provisional"; else ok; fi
  expect_exit 0 "explain $text --json" -- "$sp" explain -e "$text" --json
  has "$tmp/out" "\"citation\": \"" "explain --json gives the citation of $text"
  has "$tmp/out" "\"apparatus\": \"real material\"" "explain --json gives the domain of $text"
  if grep -q W0320 "$tmp/out"; then bad "$text --json warned provisional"; else ok; fi
done
if grep -q W0306 "$tmp/out" "$tmp/err"; then bad "slipperiness (friction) warned non-passive"; else ok; fi
expect_exit 0 "run viscosity on sim" -- "$sp" run -e "viscosity 0.5" --device sim --virtual-clock --duration 0.5 --hand circle --json
has "$tmp/err" 'W0321.*stevens-guirao1964' "run shows the real-material warning"
has "$tmp/out" '"stop_reason": "completed"' "viscosity plays"
expect_exit 0 "roughness alone" -- "$sp" compile -e "grating period 2 mm; roughness 0.5" --json
if grep -q W0320 "$tmp/out" "$tmp/err"; then bad "the measured roughness map warned provisional"; else ok; fi
expect_exit 1 "viscosity above its map" -- "$sp" compile -e "viscosity 1.5"
has "$tmp/err" 'E0303.*top of the stevens-guirao1964' "above the domain is an error"
has "$tmp/err" 'extrapolate' "the error says how to go beyond"
expect_exit 1 "misspelt perceptual word" -- "$sp" compile -e "stickyness 0.3"
has "$tmp/err" 'did you mean `stickiness`' "perceptual word suggestion"
expect_exit 1 "softness and spring in one file" -- "$sp" compile -e "softness 0.5; spring 40 N/m"
has "$tmp/err" 'E0302' "perceptual and physical for one parameter conflict"

[ -z "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '*tmp-*')" ] && ok || bad "temporary files left behind"

# Calibration fits (issue 4): a map from magnitude estimates, a device file from force-gauge readings
# (the examples are synthetic; examples/calibration/ says how they were made).
expect_exit 0 "calibrate fit" -- "$sp" calibrate fit examples/calibration/roughness-responses.csv
has "$tmp/out" '^R squared = [0-9.]+%   R squared \(adjusted\) = [0-9.]+%$' "fit reports R^2 as Figure 19"
has "$tmp/out" '^s = [0-9.]+ with 30 - 2 = 28 degrees of freedom$' "fit reports s and df"
has "$tmp/out" '^log force +0\.[0-9]+ ' "fit reports the slope"
has "$tmp/out" '^log period (adds nothing significant|is significant)' "fit says whether period adds anything"
expect_exit 0 "calibrate fit --json -o" -- "$sp" calibrate fit examples/calibration/roughness-responses.csv --json -o "$tmp/fitted.toml"
for key in slope slope_se intercept intercept_se r2 r2_adj s df f n_stimuli n_subjects period; do
  has "$tmp/out" "^  \"$key\": " "fit --json has $key"
done
has "$tmp/out" '"df": 28,' "fit --json df"
has "$tmp/fitted.toml" '^schema = "sandpaper-map/1"$' "fitted map schema"
has "$tmp/fitted.toml" '^reference = "3\.7358 N"$' "fitted map ratio scale at the strongest stimulus"
mkdir -p "$tmp/cal" && cp -r calibration/* "$tmp/cal/" && sed -i 's/^use = "compile"/use = "comparison"/' "$tmp/cal/maps/minsky1995-fig19.toml"
cp "$tmp/fitted.toml" "$tmp/cal/maps/fitted.toml"
expect_exit 0 "compile through the fitted map" -- "$sp" explain -e "roughness 0.5; grating period 2 mm" --calibration "$tmp/cal"
# Named by a path that opens from here: the copy is not under the current folder, so it is absolute.
has "$tmp/out" "\\(fitted \\($tmp/cal/maps/fitted.toml\\)\\)" "the fitted map is the compile map, by a path that opens from here"
printf 'subject,stimulus,force_N,period_mm,response\nA,s1,0.2,1,2\nA,s2,0.8,2,-5\nA,s3,3.2,5,9\n' >"$tmp/neg.csv"
cp "$tmp/fitted.toml" "$tmp/fitted.keep"
expect_exit 1 "calibrate fit refuses a negative estimate" -- "$sp" calibrate fit "$tmp/neg.csv" -o "$tmp/fitted.toml"
has "$tmp/err" 'neg.csv:3: error: response is -5' "refusal names file:line"
cmp -s "$tmp/fitted.toml" "$tmp/fitted.keep" && ok || bad "a refused fit changed its output file"
printf 'subject,stimulus,force_N,period_mm,response\nA,s1,0.2,1,2\nA,s2,0.8,2,5\n' >"$tmp/two.csv"
expect_exit 1 "calibrate fit refuses two stimuli" -- "$sp" calibrate fit "$tmp/two.csv" --json -o "$tmp/two.toml"
has "$tmp/err" 'too few stimuli: 2 distinct stimuli; .*at least 3' "too few stimuli says what is missing"
has "$tmp/out" '"ok": false' "refusal --json object"
[ ! -e "$tmp/two.toml" ] && ok || bad "a refused fit created its output"
expect_exit 1 "calibrate fit of a missing file" -- "$sp" calibrate fit no/such.csv
expect_exit 0 "calibrate device" -- "$sp" calibrate device examples/calibration/openffboard-readings.csv --base calibration/devices/openffboard-2axis.toml -o "$tmp/cal/devices/openffboard-2axis.toml" --json
for key in newtons_per_command_unit offset_N r2 max_residual_percent_fs residuals; do
  has "$tmp/out" "\"$key\": " "device --json has $key"
done
has "$tmp/cal/devices/openffboard-2axis.toml" '^status = "calibrated"$' "device file is calibrated"
has "$tmp/cal/devices/openffboard-2axis.toml" '^product_id = (65456|0xFFB0)$' "device file keeps the [usb] IDs"
expect_exit 0 "compile for the calibrated device" -- "$sp" explain -e corduroy --device openffboard-2axis --calibration "$tmp/cal"
has "$tmp/out" "openffboard-2axis \\($tmp/cal/devices/openffboard-2axis.toml\\): maximum force 8\\.352 N, .*calibrated\$" "the calibrated device's reach"
has "$tmp/out" 'commands on the bus at 1000 Hz' "explain reads commands once per bus interval (the device file's out_interval)"
cp "$tmp/out" "$tmp/explain-bus"
expect_exit 0 "explain with a slower bus" -- "$sp" explain -e corduroy --device openffboard-2axis --calibration "$tmp/cal" --command-rate 150
has "$tmp/out" 'commands on the bus at 150 Hz' "explain takes the command rate it is given"
# Corduroy at 50 mm/s: a 150 Hz bus passes on less of the ridges' peaks than a 1000 Hz one.
at50() { sed -n 's/^  50 mm\/s  \([0-9.]*\) N .*/\1/p' "$1"; }
awk -v slow="$(at50 "$tmp/out")" -v fast="$(at50 "$tmp/explain-bus")" 'BEGIN { exit !(slow > 0 && slow < 0.97 * fast) }' \
  && ok || bad "a slower bus lowers the device's output at 50 mm/s ($(at50 "$tmp/out") vs $(at50 "$tmp/explain-bus") N)"
expect_exit 2 "a command rate out of range" -- "$sp" explain -e corduroy --device openffboard-2axis --command-rate 0
expect_exit 0 "calibrate device, text" -- "$sp" calibrate device examples/calibration/openffboard-readings.csv
has "$tmp/out" 'largest residual [0-9.]+ N = [0-9.]+ % of full scale' "device linearity"
expect_exit 2 "calibrate device -o needs --base" -- "$sp" calibrate device examples/calibration/openffboard-readings.csv -o "$tmp/d.toml"
printf 'command,force_N\n1000,0.85\n1000,0.86\n1000,0.84\n' >"$tmp/one.csv"
cp "$tmp/cal/devices/openffboard-2axis.toml" "$tmp/dev.keep"
expect_exit 1 "calibrate device refuses one command level" -- "$sp" calibrate device "$tmp/one.csv" --base calibration/devices/openffboard-2axis.toml -o "$tmp/cal/devices/openffboard-2axis.toml"
has "$tmp/err" 'one.csv:2: error: .*one command level' "one command level says what is missing"
cmp -s "$tmp/cal/devices/openffboard-2axis.toml" "$tmp/dev.keep" && ok || bad "a refused device fit changed its output file"
[ "$(find "$tmp" -name '*tmp-*' | wc -l)" -eq 0 ] && ok || bad "calibrate left temporary files behind"

# USB force-feedback devices (docs/USB_PID.md). This test machine has no USB joystick: both
# commands must say so and exit 2 (environment), naming the devices they look for.
expect_exit 2 "devices, none present" -- "$sp" devices
has "$tmp/err" 'no USB force-feedback device' "devices says there is none"
has "$tmp/err" 'known devices: openffboard-2axis \(1209:ffb0\)' "devices names the known IDs"
expect_exit 2 "run --device usb, none present" -- "$sp" run -e corduroy --device usb --duration 0.1
has "$tmp/err" 'run --device usb: no USB force-feedback device' "run --device usb says why"
# The device factory refuses what a real joystick cannot do before it searches USB.
expect_exit 2 "run --device usb --virtual-clock" -- "$sp" run -e corduroy --device usb --virtual-clock --duration 0.1
has "$tmp/err" 'run --device usb: --virtual-clock plays the simulated joystick' "a USB run says it runs in real time"
expect_exit 2 "run --device usb --hand-model dynamic" -- "$sp" run -e corduroy --device usb --hand-model dynamic --duration 0.1
has "$tmp/err" 'a USB joystick is moved by the hand holding it' "a USB run refuses a simulated hand"
expect_exit 2 "run on a device named by its USB calibration, none present" -- "$sp" run -e corduroy --device openffboard-2axis --duration 0.1
has "$tmp/err" 'no USB force-feedback device found' "a device with a [usb] table is looked for on USB"
# hidraw (docs/DEVICES.md): found among /sys/class/hidraw, a node named by path refused by name.
expect_exit 2 "run --device hidraw, none present" -- "$sp" run -e corduroy --device hidraw --duration 0.1
has "$tmp/err" 'run --device hidraw: no hidraw node of a known force-feedback device' "run --device hidraw says why"
has "$tmp/err" 'known devices: openffboard-2axis \(1209:ffb0\)' "and names the known IDs"
expect_exit 2 "run --device hidraw:PATH, no such node" -- "$sp" run -e corduroy --device hidraw:/dev/hidraw-none --duration 0.1
has "$tmp/err" 'no hidraw node /dev/hidraw-none' "a hidraw path that is no node is named"
expect_exit 2 "run --device hidraw --virtual-clock" -- "$sp" run -e corduroy --device hidraw --virtual-clock --duration 0.1
has "$tmp/err" '--virtual-clock plays the simulated joystick' "a hidraw run runs in real time"
# Stopping: SIGINT to a running real-time run stops it within a tick, exit 0, the cause reported.
# The signal goes once the process has its handlers (SigCgt in /proc, SIGINT and SIGTERM bits), not
# after a guessed sleep: under load start-up alone can take longer than any sleep.
wait_for_stop_handlers() {
  local pid=$1 mask
  for _ in $(seq 3000); do
    # A run that has already ended (a zombie until `wait`) will never catch the signal: say so now.
    grep -q '^State:.*Z' "/proc/$pid/status" 2>/dev/null && { echo "the run ended before its signal:"; cat "$tmp/sig.out" "$tmp/sig.err"; return 1; }
    mask=$(awk '/^SigCgt:/{print $2}' "/proc/$pid/status" 2>/dev/null) || return 1
    [ -n "$mask" ] && (( (0x$mask & 0x4002) == 0x4002 )) && return 0
    sleep 0.01
  done
  return 1
}
"$sp" run -e corduroy --device sim "${RT[@]}" --duration 30 >"$tmp/sig.out" 2>"$tmp/sig.err" &
run_pid=$!
wait_for_stop_handlers "$run_pid"
kill -INT "$run_pid"
wait "$run_pid"; got=$?
[ "$got" -eq 0 ] && ok || bad "SIGINT: exit $got, wanted 0"
# It stopped at the signal, not at the end of its 30 s (30,000 ticks at 1 kHz).
ticks=$(sed -nE 's/^ *loop +([0-9]+) ticks.*/\1/p' "$tmp/sig.out")
[ -n "$ticks" ] && [ "$ticks" -lt 30000 ] && ok || bad "SIGINT: the run went on to ${ticks:-?} ticks"
has "$tmp/sig.out" 'stopped: stopped by signal' "SIGINT is reported as the stop cause"
"$sp" run -e corduroy --device sim "${RT[@]}" --duration 30 --json >"$tmp/sig.out" 2>"$tmp/sig.err" &
run_pid=$!
wait_for_stop_handlers "$run_pid"
kill -TERM "$run_pid"
wait "$run_pid"; got=$?
[ "$got" -eq 0 ] && ok || bad "SIGTERM: exit $got, wanted 0"
has "$tmp/sig.out" '"stop_cause": "stop_requested"' "SIGTERM names stop_requested"
# Real-time priority: granted, or said once on stderr; never on the virtual clock.
expect_exit 0 "real-time run" -- "$sp" run -e corduroy --device sim "${RT[@]}" --duration 0.2 --json
if grep -q '"realtime_scheduling": false' "$tmp/out"; then
  [ "$(grep -c 'note: running without real-time priority' "$tmp/err")" -eq 1 ] && ok || bad "the no-real-time note must appear exactly once"
else
  grep -q 'note: running without real-time priority' "$tmp/err" && bad "note printed although SCHED_FIFO was granted" || ok
fi
expect_exit 0 "virtual clock run" -- "$sp" run -e corduroy --device sim --duration 0.2 --virtual-clock
grep -q 'real-time priority' "$tmp/err" && bad "the virtual clock printed the real-time note" || ok
# Live figures with --live (stderr), none without it when stderr is not a terminal.
expect_exit 0 "run --live" -- "$sp" run -e corduroy --device sim "${RT[@]}" --duration 1.5 --live
has "$tmp/err" '^live  t [0-9.]+ s  period p50' "--live prints figures"
expect_exit 0 "run without --live" -- "$sp" run -e corduroy --device sim "${RT[@]}" --duration 0.2
grep -q '^live' "$tmp/err" && bad "live figures without --live on a pipe" || ok
# The trace comes from the telemetry ring, in the same format: one row per tick.
expect_exit 0 "trace from the ring" -- "$sp" run -e corduroy --device sim "${RT[@]}" --duration 0.3 --trace "$tmp/rt.csv"
[ "$(head -1 "$tmp/rt.csv")" = "t_s,x_m,y_m,force_x_N,force_y_N" ] && ok || bad "trace header changed"
[ "$(($(wc -l <"$tmp/rt.csv") - 1))" -eq 300 ] && ok || bad "trace should hold 300 ticks"
# The dynamic hand and the replay device (docs/RUNTIME.md): a replayed trace reproduces every tick.
expect_exit 0 "run on the dynamic hand" -- "$sp" run -e corduroy --virtual-clock --hand-model dynamic --duration 0.5 --trace "$tmp/dyn.csv"
has "$tmp/out" 'device   dynamic hand \(0.554 kg, 135 N/m, 6.45 N\*s/m\)' "the dynamic hand is named"
expect_exit 0 "replay a trace" -- "$sp" run -e corduroy --virtual-clock --replay "$tmp/dyn.csv" --trace "$tmp/again.csv"
cmp -s "$tmp/dyn.csv" "$tmp/again.csv" && ok || bad "a replayed trace should reproduce the recorded one byte for byte"
expect_exit 2 "replay at another rate is refused with the trace's rate" -- "$sp" run -e corduroy --virtual-clock --replay "$tmp/dyn.csv" --rate 2000
has "$tmp/err" 'recorded at 1000 Hz, not 2000 Hz; replay it with --rate 1000' "replay names the rate to use"
printf 'time,x\n' >"$tmp/bad.csv"
expect_exit 1 "a malformed trace is refused" -- "$sp" run -e corduroy --replay "$tmp/bad.csv"
expect_exit 2 "workspaces do not take --replay" -- "$sp" run examples/workspace/sampler.hws --replay "$tmp/dyn.csv"

# Library curation (docs/LIBRARY.md) on a copy of the mini library: check, index, search, show, near.
cp -r tests/curation/data/mini "$tmp/lib"
L=(--library "$tmp/lib")
I=(--index "$tmp/idx/library.sqlite")
expect_exit 0 "library check passes on the mini library" -- "$sp" library check "${L[@]}"
has "$tmp/err" '^checked 5 entries on 7 devices \(uncalibrated, W0331: haply-inverse3, novint-falcon, openffboard-2axis, openffboard-wheel\): 0 errors, 0 warnings, 15 accepted$' "check prints its summary"
expect_exit 0 "library check --quiet" -- "$sp" library check "${L[@]}" --quiet
[ -s "$tmp/err" ] && bad "check --quiet printed progress" || ok
expect_exit 0 "library check --json" -- "$sp" library check "${L[@]}" --json --quiet
has "$tmp/out" '"ok": true' "check --json"
expect_exit 0 "library index" -- "$sp" library index "${L[@]}" "${I[@]}"
has "$tmp/out" '^indexed 5 entries of curation test library 0.1.0 into ' "index says what it wrote"
expect_exit 0 "search by alias" -- "$sp" library search grit-80 "${L[@]}" "${I[@]}"
has "$tmp/out" '^coarse-grit +abrasives +roughness 0.8 +"coarse sandpaper, sharp grains" +\(alias grit-80\)' "search names the alias"
expect_exit 0 "search by roughness and family" -- "$sp" library search --roughness 0.4..0.6 --family textiles "${L[@]}" "${I[@]}"
[ "$(wc -l <"$tmp/out")" -eq 1 ] && has "$tmp/out" '^ribbed-cloth ' "roughness range and family" || bad "one textile in 0.4..0.6"
expect_exit 1 "search with no match exits 1, like grep" -- "$sp" library search velvet "${L[@]}" "${I[@]}"
has "$tmp/err" '^no entries match$' "no match said"
# The shipped library: cork says `roughness 0.22`, polished steel and glossy paper 0.05; window glass
# and the thesis' non-textural stimuli have no texture, so no roughness.
expect_exit 0 "a bound equal to the written roughness finds it" -- "$sp" library search --roughness 0.22..0.22 --index "$tmp/shipped.sqlite"
has "$tmp/out" '^cork +woods +roughness 0.22 ' "0.22..0.22 finds cork (roughness 0.22)"
expect_exit 0 "an upper bound takes in the value written" -- "$sp" library search --roughness ..0.05 --index "$tmp/shipped.sqlite"
has "$tmp/out" '^polished-steel ' "..0.05 finds polished-steel (roughness 0.05)"
has "$tmp/out" '^glossy-paper ' "..0.05 finds glossy-paper (roughness 0.05)"
if grep -Eq '^(window-glass|v1-Nothing|pencil-eraser) ' "$tmp/out"; then bad "a roughness range lists untextured entries"; else ok; fi
# check says every warning the compiler gives an entry, on every device (as explain does): cork's
# image texture extrapolates the roughness map (W0304), velvet's fine pile is read weaker at 100 mm/s
# (W0350). The shipped entries accept them with their reasons, so a copy without its `accept` lines.
cp -r library "$tmp/unaccepted"
find "$tmp/unaccepted" -name '*.hmat' -exec sed -i '/^ *accept /d' {} +
expect_exit 0 "library check on the shipped library, its accepts taken out" -- "$sp" library check --library "$tmp/unaccepted" --quiet
has "$tmp/err" 'woods/cork\.hmat:[0-9]+:[0-9]+: warning\[W0304\]' "check shows W0304 for an image texture"
has "$tmp/err" 'textiles/velvet\.hmat:[0-9]+:[0-9]+: warning\[W0350\]: .*servo on sandpaper-1995' "check shows W0350 on the 1995 joystick"
has "$tmp/err" 'textiles/velvet\.hmat:[0-9]+:[0-9]+: warning\[W0350\]: .*servo on sim' "check shows W0350 on sim"
# As shipped, every warning is accepted in its entry with a reason, and counted so.
expect_exit 0 "library check --werror on the shipped library" -- "$sp" library check --library library --werror
has "$tmp/err" ' 0 warnings, [0-9]+ accepted' "the shipped library's warnings are all accepted"
expect_exit 0 "untextured entries say so" -- "$sp" library search window glass --index "$tmp/shipped.sqlite"
has "$tmp/out" '^window-glass +glass +untextured ' "window-glass is listed as untextured, not roughness 0.00"
expect_exit 2 "a bad roughness range is a usage error" -- "$sp" library search --roughness 0.6 "${L[@]}" "${I[@]}"
has "$tmp/err" 'write A\.\.B, A\.\. or \.\.B' "the range's form is given"
expect_exit 0 "show by alias" -- "$sp" library show rib-cloth "${L[@]}" "${I[@]}"
has "$tmp/out" 'patch\.width +95 mm' "library show prints lengths as explain does"
if grep -Eq '0\.095 m|[0-9] rad' "$tmp/out"; then bad "library show prints raw SI"; else ok; fi
has "$tmp/out" '^ribbed-cloth  \(alias rib-cloth\)' "show names the entry"
has "$tmp/out" 'source derived "8 ribs per inch: 25.4 mm / 8"' "show prints the sources"
has "$tmp/out" 'maximum lateral force  1\.3[0-9]* N' "show prints the force"
# The resolution's columns (parameter, value, layer, where) line up on every row, whatever the
# widest cell: fine-rib's rows have layers 'representative' (inherited from rib-cloth) and 'physical'.
expect_exit 0 "show an entry built on another" -- "$sp" library show fine-rib "${L[@]}" "${I[@]}"
python3 - "$tmp/out" >"$tmp/columns" <<'PY'
import re, sys
rows, on = [], False
for line in open(sys.argv[1]):
    line = line.rstrip("\n")
    if line.startswith("resolution"): on = True; continue
    if on and line.startswith("  ") and not line.startswith("      source"):
        rows.append([m.start() for m in re.finditer(r"\S+(?: \S+)*", line)])
layers = {len(r) for r in rows}
starts = {tuple(r[:4]) for r in rows}
print("ok" if len(rows) > 3 and layers == {4} and len(starts) == 1 else "misaligned: %r" % sorted(starts))
PY
has "$tmp/columns" '^ok$' "show's resolution columns line up"
expect_exit 1 "show an unknown name" -- "$sp" library show ribbed-clth "${L[@]}" "${I[@]}"
has "$tmp/err" "did you mean 'ribbed-cloth'" "show suggests a name"
expect_exit 0 "near" -- "$sp" library near ribbed-cloth --limit 2 "${L[@]}" "${I[@]}"
has "$tmp/out" '^ +[0-9.]+  reference-grating +[0-9.]+ JND stronger' "near lists the nearest with why"
# The index survives a failed rebuild, and search notices a stale index and rebuilds it.
cp "$tmp/idx/library.sqlite" "$tmp/idx.before"
printf 'material "broken" {\n  describes "x"\n  family textiles\n  licence "CC0-1.0"\n  grating period 2 mm\n  source by-ear "x"\n  roughness 5\n  source by-ear "x"\n}\n' >"$tmp/lib/textiles/broken.hmat"
expect_exit 1 "a failed rebuild exits 1" -- "$sp" library index "${L[@]}" "${I[@]}"
has "$tmp/err" 'E0303' "the compiler's reason is shown"
has "$tmp/err" 'index not written.*is unchanged' "the index is said to be unchanged"
cmp -s "$tmp/idx/library.sqlite" "$tmp/idx.before" && ok || bad "a failed rebuild changed the index"
expect_exit 0 "search answers from the previous index while the library is broken" -- "$sp" library search ribbed "${L[@]}" "${I[@]}"
has "$tmp/err" 'answering from the previous index' "search says the index is the previous one"
has "$tmp/out" '^ribbed-cloth ' "the previous index still finds ribbed-cloth"
cmp -s "$tmp/idx/library.sqlite" "$tmp/idx.before" && ok || bad "search over a broken library changed the index"
expect_exit 1 "library check fails on the broken entry" -- "$sp" library check "${L[@]}" --quiet
has "$tmp/err" 'broken.hmat:1:10: error\[E0610\]' "check names the entry that does not compile"
rm "$tmp/lib/textiles/broken.hmat"
printf 'material "ribbed-twin" {\n  describes "x"\n  family textiles\n  licence "CC0-1.0"\n  grating period 3 mm hill 60%%\n  source by-ear "x"\n  roughness 0.46\n  source by-ear "x"\n}\n' >"$tmp/lib/textiles/ribbed-twin.hmat"
expect_exit 0 "a JND collision is a warning" -- "$sp" library check "${L[@]}" --quiet
has "$tmp/err" 'warning\[W0601\]: .ribbed-twin. may feel the same as .ribbed-cloth.' "W0601 names both"
expect_exit 1 "--werror makes warnings fail" -- "$sp" library check "${L[@]}" --werror
has "$tmp/err" '1 warning, 15 accepted \(--werror: warnings fail\)' "werror said"
rm "$tmp/lib/textiles/ribbed-twin.hmat"
sed -i 's/^  source derived "8 ribs per inch: 25.4 mm \/ 8"$//' "$tmp/lib/textiles/ribbed-cloth.hmat"
expect_exit 1 "library check fails on a missing source" -- "$sp" library check "${L[@]}" --quiet
has "$tmp/err" 'ribbed-cloth.hmat:6:3: error\[E0606\]: `grating` carries numbers but has no `source`' "missing source located"
expect_exit 0 "search rebuilds a stale index" -- "$sp" library search fine-rib "${L[@]}" "${I[@]}"
has "$tmp/err" 'is stale .* building it' "search says it rebuilds"
expect_exit 2 "a missing root of a layered library path" -- "$sp" compile --library /no/such/lab:library -e "like corduroy" -o "$tmp/missing-root.patch"
has "$tmp/err" 'no library folder at /no/such/lab' "the missing root is named"
[ ! -e "$tmp/missing-root.patch" ] && ok || bad "a compile with a missing library root wrote a patch"
# The shipped library is root `world` in a layered path (its library.toml's id), as docs/LIBRARY.md
# writes it, whatever its folder is called; a root id the path does not have lists the ones it has.
expect_exit 0 "like world:corduroy under the example lab" -- "$sp" compile --library examples/lab-library:library -e "like world:corduroy" -o "$tmp/world.patch"
expect_exit 1 "like ROOT:NAME with an unknown root" -- "$sp" compile --library examples/lab-library:library -e "like wrld:corduroy" -o "$tmp/wrld.patch"
has "$tmp/err" "no library root 'wrld' \(in 'wrld:corduroy'\): the library path's roots are 'lab', 'world'" "the unknown root's error lists the roots"
has "$tmp/err" 'did you mean `world:corduroy`' "the unknown root's error names the nearest"
expect_exit 2 "check --root with an unknown id" -- "$sp" library check --library examples/lab-library:library --root wrld --quiet
has "$tmp/err" "no root named 'wrld' in the library path: its roots are 'lab', 'world'" "check --root lists the roots"
expect_exit 0 "library with no subcommand still lists" -- "$sp" library
has "$tmp/out" 'roughness' "library lists entries"

# The safety stops are the same options on every command that plays (player/include/sandpaper/player/safety_guards.hpp).
expect_exit 2 "studio: --watchdog is a USB option" -- "$sp" studio examples/corduroy.hmat --watchdog 500 --listen 127.0.0.1:0
has "$tmp/err" '--watchdog applies to --device usb' "studio says why --watchdog is refused"
expect_exit 2 "experiment run: --watchdog is a USB option" -- "$sp" experiment run examples/experiments/force-jnd.toml \
  --subject S --observer simulated:exponent=0.76 --watchdog 500 -o "$tmp/exp-watchdog"
has "$tmp/err" '--watchdog applies to --device usb' "experiment says why --watchdog is refused"
[ -e "$tmp/exp-watchdog" ] && bad "a refused experiment made its results folder" || ok
# hidraw in the studio and in live experiments: through the factory, no node here (docs/DEVICES.md).
expect_exit 2 "studio --device hidraw:PATH, no such node" -- "$sp" studio examples/corduroy.hmat --device hidraw:/dev/hidraw-none --listen 127.0.0.1:0
has "$tmp/err" 'studio --device hidraw:/dev/hidraw-none: no hidraw node /dev/hidraw-none' "the studio names the node"
expect_exit 2 "experiment run --device hidraw, none present" -- "$sp" experiment run examples/experiments/force-jnd.toml \
  --subject S --observer simulated:exponent=0.76 --device hidraw -o "$tmp/exp-hidraw"
has "$tmp/err" 'experiment --device hidraw: no hidraw node of a known force-feedback device' "an experiment looks for the hidraw node"
[ -e "$tmp/exp-hidraw" ] && bad "an experiment without its joystick made its results folder" || ok
expect_exit 2 "studio: a velocity limit out of range" -- "$sp" studio examples/corduroy.hmat --velocity-limit 0
# --uncalibrated in the studio and live experiments: an input event node alone, through the factory.
expect_exit 2 "studio --uncalibrated on the simulated joystick" -- "$sp" studio examples/corduroy.hmat --uncalibrated --listen 127.0.0.1:0
has "$tmp/err" 'studio --device sim: --uncalibrated plays an input event node' "the studio says what --uncalibrated is for"
expect_exit 2 "studio --uncalibrated, no such node" -- "$sp" studio examples/corduroy.hmat --device evdev:/dev/input/event-none --uncalibrated --listen 127.0.0.1:0
has "$tmp/err" '/dev/input/event-none' "the studio names the event node"
expect_exit 2 "experiment run --uncalibrated through hidraw" -- "$sp" experiment run examples/experiments/force-jnd.toml \
  --subject S --observer simulated:exponent=0.76 --device hidraw --uncalibrated -o "$tmp/exp-uncal"
has "$tmp/err" 'experiment --device hidraw: --uncalibrated plays an input event node' "an experiment says what --uncalibrated is for"
[ -e "$tmp/exp-uncal" ] && bad "a refused experiment made its results folder" || ok

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
