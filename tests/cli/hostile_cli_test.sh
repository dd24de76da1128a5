#!/usr/bin/env bash
# Hostile files and interrupted runs, as a user meets them (issue 16): exit codes (1 for wrong input,
# with a message, never a raw library exception), library images outside the library, no machine
# path in a patch, and what a kill -9 leaves behind. Usage: hostile_cli_test.sh path/to/sandpaper SOURCE_DIR
set -uo pipefail
sp=$1
src=$2
tmp=$(mktemp -d)
trap 'kill -9 $(jobs -p) 2>/dev/null; rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fails=$((fails + 1)); }
check() {  # check "what" expected_status actual_status
  if [ "$2" = "$3" ]; then ok "$1"; else bad "$1 (exit $3, expected $2)"; fi
}
has() {  # has "what" file pattern
  if grep -q -- "$3" "$2"; then ok "$1"; else bad "$1: no '$3' in $2:"; head -c 2000 "$2"; fi
}

# A patch with a valid checksum whose size is NaN: a bad file (exit 1), not a usage error (2).
"$sp" compile -e "grating period 2 mm amplitude 1 N" -o "$tmp/g.patch" >/dev/null 2>&1
python3 - "$tmp/g.patch" "$tmp/nan.patch" <<'PY'
import struct, sys, zlib
b = bytearray(open(sys.argv[1], 'rb').read())
p = 32
for _ in range(5):  # name, describes, device, device_file, command_unit
    n = struct.unpack_from('<I', b, p)[0]; p += 4 + n
p += 8 + 8 + 8 + 8 + 1  # newtons_per_command_unit[2], command_max, max_force_N, calibrated
struct.pack_into('<d', b, p, float('nan'))  # size_m[0]
struct.pack_into('<I', b, 24, zlib.crc32(bytes(b[32:])) & 0xffffffff)
open(sys.argv[2], 'wb').write(bytes(b))
PY
"$sp" run "$tmp/nan.patch" --duration 0.1 >"$tmp/out" 2>"$tmp/err"; check "run: a NaN-size patch is exit 1" 1 $?
has "and the message says what is wrong" "$tmp/err" "size is not positive and finite"
"$sp" inspect "$tmp/nan.patch" >"$tmp/out" 2>"$tmp/err"; check "inspect: the same" 1 $?

# Run length: a stated maximum, and a run that keeps every tick in memory is bounded in ticks
# (--duration 100000 --virtual-clock used to take 7 GB).
"$sp" run -e "grating period 2 mm amplitude 1 N" --duration 1e300 >"$tmp/out" 2>"$tmp/err"; check "an absurd --duration is a usage error" 2 $?
has "that says the limit" "$tmp/err" "to 86400 s"
"$sp" run -e "grating period 2 mm amplitude 1 N" --duration 2100 --virtual-clock >"$tmp/out" 2>"$tmp/err"; check "a virtual-clock run over 2^21 ticks is refused" 2 $?
has "with the longest it may be" "$tmp/err" "2097152 ticks: 2097.15 s at 1000 Hz"

# Memory that runs out within the limits is the input's doing: exit 1, said plainly (std::bad_alloc
# used to exit 2). 100 MB of address space runs a short virtual-clock run; 2,000 s of kept ticks
# (about 150 MB) does not. A sanitizer's runtime reserves terabytes of address space, so not there.
if ldd "$sp" 2>/dev/null | grep -q 'lib[at]san'; then
  ok "out of memory: skipped under a sanitizer"
else
  (ulimit -v 100000; "$sp" run -e "grating period 2 mm amplitude 1 N" --duration 0.1 --virtual-clock >"$tmp/out" 2>"$tmp/err")
  check "a short run fits in 100 MB of address space" 0 $?
  (ulimit -v 100000; "$sp" run -e "grating period 2 mm amplitude 1 N" --duration 2000 --virtual-clock >"$tmp/out" 2>"$tmp/err")
  check "memory running out is exit 1" 1 $?
  has "with a message that says so" "$tmp/err" "out of memory: the input needs more memory than this machine has"
fi

# Non-UTF-8 source: a diagnostic at its place, and --json still prints JSON (it used to throw).
printf 'material "m" {\n  describes "caf\xe9"\n  grating period 2 mm amplitude 1 N\n}\n' >"$tmp/latin1.hmat"
"$sp" compile "$tmp/latin1.hmat" --json >"$tmp/out" 2>"$tmp/err"; check "non-UTF-8 source is exit 1" 1 $?
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["diagnostics"][0]["code"]=="E0104", d' "$tmp/out" \
  && ok "--json prints a E0104 diagnostic" || bad "--json output is not JSON with E0104"
if grep -q "json.exception" "$tmp/err"; then bad "a raw nlohmann exception reached the user"; else ok "no raw library exception"; fi

# A file name that is not UTF-8 (Linux names are bytes): --json still prints JSON, the name with
# U+FFFD (F26; it stopped with nlohmann's type_error 316, exit 2). A CSV field that is not UTF-8 is
# refused at its line (F25; the same raw exception before).
cp "$src/examples/corduroy.hmat" "$tmp/caf"$'\xe9'".hmat"
"$sp" compile "$tmp/caf"$'\xe9'".hmat" -o "$tmp/cafe.patch" --json >"$tmp/out" 2>"$tmp/err"; check "a Latin-1 file name compiles with --json" 0 $?
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["ok"], d' "$tmp/out" && ok "and prints JSON" || bad "--json output is not JSON"
if grep -q "json.exception" "$tmp/err"; then bad "a raw nlohmann exception reached the user"; else ok "no raw library exception"; fi
# The name is in the program too (its provenance's locations): written with U+FFFD, it reads back
# (F42; the reader refused the program with "a string that is not UTF-8", exit 1).
"$sp" inspect "$tmp/cafe.patch" >"$tmp/out" 2>"$tmp/err"; check "the program compiled from a Latin-1 file name reads back" 0 $?
grep -q "caf"$'\xef\xbf\xbd'".hmat" "$tmp/out" && ok "naming the file with U+FFFD" || bad "inspect does not name the file with U+FFFD"
sed 's/^S01,/M'$'\xfc''ller,/' "$src/examples/calibration/roughness-responses.csv" >"$tmp/latin1.csv"
grep -q $'\xfc' "$tmp/latin1.csv" || bad "the test CSV has no Latin-1 subject (the example's first subject is not S01?)"
"$sp" calibrate fit "$tmp/latin1.csv" --json >"$tmp/out" 2>"$tmp/err"; check "calibrate fit: a Latin-1 subject is exit 1" 1 $?
has "naming the line and the byte" "$tmp/err" "is not UTF-8; save the file as UTF-8"
cp "$src/examples/calibration/roughness-responses.csv" "$tmp/r"$'\xe9'"sum"$'\xe9'".csv"
"$sp" calibrate fit "$tmp/r"$'\xe9'"sum"$'\xe9'".csv" -o "$tmp/fitted-x.toml" --json >"$tmp/out" 2>"$tmp/err"; check "calibrate fit from a Latin-1 file name" 0 $?
python3 -c 'import sys,tomllib; tomllib.load(open(sys.argv[1],"rb"))' "$tmp/fitted-x.toml" 2>"$tmp/err" && ok "writes a map that is TOML (UTF-8)" || { bad "the map is not valid TOML:"; cat "$tmp/err"; }

# A library entry named in Latin-1: `library catalog` stopped with the raw type_error 316, exit 2
# (F30). The entry is reported (E0614) and the build refused like any broken entry, exit 1.
cp -r "$src/tests/compiler/data/library-small" "$tmp/latin1-lib"
cp "$tmp/latin1-lib/cloth/rib.hmat" "$tmp/latin1-lib/cloth/caf"$'\xe9'".hmat"
"$sp" library catalog --library "$tmp/latin1-lib" -o "$tmp/latin1-catalog" --quiet >"$tmp/out" 2>"$tmp/err"; check "library catalog: a Latin-1 entry file is exit 1" 1 $?
has "with E0614 naming it" "$tmp/err" "error\[E0614\]: the file's path is not UTF-8"
if grep -q "json.exception" "$tmp/err"; then bad "a raw nlohmann exception reached the user"; else ok "no raw library exception"; fi

# A material file that is a device or a FIFO is refused at once (it used to hang).
mkfifo "$tmp/fifo.hmat"
timeout 20 "$sp" compile "$tmp/fifo.hmat" -o "$tmp/x.patch" >"$tmp/out" 2>"$tmp/err"; check "a FIFO is exit 1, without blocking" 1 $?
printf 'material "z" {\n  heightmap "/dev/zero" size 50 mm\n  roughness 0.5\n}\n' >"$tmp/zero.hmat"
timeout 20 "$sp" compile "$tmp/zero.hmat" -o "$tmp/x.patch" >"$tmp/out" 2>"$tmp/err"; check "heightmap /dev/zero is exit 1, without hanging" 1 $?
has "E0401 says why" "$tmp/err" "not a regular file"

# An image whose header claims more than the file holds is refused within the image budget: a
# 620-byte OpenEXR file whose Software string claims 1.9 GB took 1.9 GB before E0401 (F18), and a
# 447-byte PNG whose text chunk claims 1.8 GB took 1.8 GB (F20). Both OpenEXR files are refused by
# the header walk before OpenEXR Core maps their claims (F44), so the message is the walk's.
for claim in exr-header-string-claiming-1.9-GB.exr exr-attribute-claiming-994-MB-in-513-bytes.exr \
             png-text-chunk-claiming-1.8-GB.png; do
  python3 - "$sp" "$src/fuzz/regressions/image/$claim" "$tmp" >"$tmp/out" <<'PY'
import resource, subprocess, sys
sp, image, tmp = sys.argv[1:4]
r = subprocess.run([sp, 'compile', '-e', f'heightmap "{image}" size 20 mm amplitude 1 N', '-o', f'{tmp}/claim.patch'],
                   capture_output=True, text=True)
peak_mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024  # kB on Linux
print(f"exit {r.returncode} peak {peak_mib} MiB {r.stderr.strip()[:300]}")
PY
  read -r _ claim_status _ claim_peak _ <"$tmp/out"
  check "$claim is exit 1" 1 "$claim_status"
  has "with E0401" "$tmp/out" "E0401"
  case $claim in *.exr) has "named by the header walk" "$tmp/out" "the OpenEXR header is cut short: its attribute" ;; esac
  if [ "${claim_peak:-99999}" -le 512 ]; then ok "within 512 MiB (peak ${claim_peak} MiB)"; else bad "peak ${claim_peak} MiB reading $claim"; fi
done

# A file is opened only by the reader its extension names: OpenImageIO's fallback through every
# reader it has reached its RLA reader, which aborted the process on this 1 KB file (F21).
rla=$src/fuzz/regressions/image/rla-header-named-tga-aborts-openimageio.tga
"$sp" compile -e "heightmap \"$rla\" size 20 mm amplitude 1 N" -o "$tmp/rla.patch" >"$tmp/out" 2>"$tmp/err"
check "an RLA header named .tga is exit 1, not an abort" 1 $?
has "read as TGA, and refused" "$tmp/err" "E0401"
cp "$rla" "$tmp/heights.rla"
"$sp" compile -e "heightmap \"$tmp/heights.rla\" size 20 mm amplitude 1 N" -o "$tmp/rla.patch" >"$tmp/out" 2>"$tmp/err"
check "an .rla file is exit 1" 1 $?
has "naming the formats read" "$tmp/err" "not a height-map image format by its extension (PNG, TIFF, OpenEXR"

# No absolute machine path enters a patch, even when the user gives absolute paths.
sed "s|\"../library/images/grass.png\"|\"$src/library/images/grass.png\"|" "$src/examples/grass.hmat" >"$tmp/grass.hmat"
"$sp" compile "$tmp/grass.hmat" -o "$tmp/grass.patch" >/dev/null 2>&1; check "an absolute image path compiles" 0 $?
"$sp" inspect "$tmp/grass.patch" --json >"$tmp/grass.json" 2>&1
if grep -q -e "$tmp" -e "$src" "$tmp/grass.json"; then bad "an absolute path is in the patch:"; grep -e "$tmp" -e "$src" "$tmp/grass.json" | head -3
else ok "the patch names no absolute path"; fi

# A library entry may not reach outside its library: `library check` says so, and `like` refuses it.
mkdir -p "$tmp/lib/cloth" "$tmp/lib/images"
cp "$src/library/images/brick.png" "$tmp/brick.png"
cp "$src/library/images/brick.png" "$tmp/lib/images/brick.png"
entry() {  # entry NAME IMAGE
  printf 'material "%s" {\n  family cloth\n  describes "test entry"\n  licence "CC0-1.0"\n  heightmap "%s" size 50 mm\n  source by-ear "test"\n  roughness 0.5\n  source by-ear "test"\n}\n' "$1" "$2" >"$tmp/lib/cloth/$1.hmat"
}
entry inside "../images/brick.png"
entry absolute "$tmp/brick.png"
entry climbing "../../brick.png"
# A link inside the library that leads out of it, and a folder link that does: each as much outside as "..".
ln -s "$tmp/brick.png" "$tmp/lib/images/linked.png"
mkdir -p "$tmp/outside-images" && cp "$tmp/brick.png" "$tmp/outside-images/brick.png"
ln -s "$tmp/outside-images" "$tmp/lib/images/elsewhere"
entry linked "../images/linked.png"
entry linked-folder "../images/elsewhere/brick.png"
printf 'name = "hostile"\nversion = "0.1.0"\n[[families]]\nid = "cloth"\ntitle = "Cloth"\n' >"$tmp/lib/library.toml"
"$sp" library check --library "$tmp/lib" --quiet >"$tmp/out" 2>"$tmp/err"; check "library check: escapes are errors" 1 $?
has "the absolute path is reported" "$tmp/err" "cloth/absolute.hmat:5:.*E0612"
has "the climbing path is reported" "$tmp/err" "cloth/climbing.hmat:5:.*E0612"
has "an image that is a link leading out is reported" "$tmp/err" "cloth/linked.hmat:5:.*E0612.*symbolic link"
has "an image under a folder link leading out is reported" "$tmp/err" "cloth/linked-folder.hmat:5:.*E0612.*symbolic link"
if grep -q "inside.hmat.*E0612" "$tmp/err"; then bad "an image inside the library was reported"; else ok "an image inside the library is fine"; fi
"$sp" compile --library "$tmp/lib" -e "like absolute" -o "$tmp/x.patch" >"$tmp/out" 2>"$tmp/err"; check "like an escaping entry: exit 1" 1 $?
has "the error names the image" "$tmp/err" "brick.png. is outside the library"
"$sp" compile --library "$tmp/lib" -e "like linked" -o "$tmp/x.patch" >"$tmp/out" 2>"$tmp/err"; check "like an entry whose image links out: exit 1" 1 $?
has "the compiler follows the link too" "$tmp/err" "linked.png. is outside the library (symbolic links followed)"
"$sp" compile --library "$tmp/lib" -e "like inside" -o "$tmp/x.patch" >"$tmp/out" 2>"$tmp/err"; check "like an entry inside: compiles" 0 $?
rm "$tmp/lib/cloth/absolute.hmat" "$tmp/lib/cloth/climbing.hmat" "$tmp/lib/cloth/linked.hmat" "$tmp/lib/cloth/linked-folder.hmat"

# Temporaries of killed runs are cleaned by the next run. Synthetic ones first: a PID above the
# kernel's pid_max cannot be running.
"$sp" library index --library "$tmp/lib" --index "$tmp/idx/library.sqlite" --quiet >/dev/null 2>&1
head -c 1000000 /dev/urandom >"$tmp/idx/library.sqlite.tmp-99999999"
"$sp" library index --library "$tmp/lib" --index "$tmp/idx/library.sqlite" --quiet >/dev/null 2>&1; check "index rebuilds" 0 $?
[ ! -e "$tmp/idx/library.sqlite.tmp-99999999" ]; check "a dead run's index temporary is removed" 0 $?
"$sp" library catalog --library "$tmp/lib" -o "$tmp/site" --quiet >/dev/null 2>&1; check "catalog builds" 0 $?
mkdir -p "$tmp/.site.new-99999999-1/entries" "$tmp/.site.old-99999999-2"
"$sp" library catalog --library "$tmp/lib" -o "$tmp/site" --quiet >/dev/null 2>&1; check "catalog rebuilds" 0 $?
[ -z "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '.site.*')" ]; check "a dead run's catalog temporaries are removed" 0 $?

# A real kill -9 in the middle of a catalog of the shipped library: the previous catalog stays whole
# at its place, and the next run leaves no temporaries. The run's temporary folder appearing is the
# signal that it is under way.
cp "$tmp/site/index.html" "$tmp/index.before"
"$sp" library catalog -o "$tmp/site" --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -n "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '.site.new-*')" ] && [ -n "$(ls -A "$tmp"/.site.new-*/entries 2>/dev/null)" ] && break
  kill -0 $pid 2>/dev/null || break
  read -rt 0.1 <> <(:) || true
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
cmp -s "$tmp/index.before" "$tmp/site/index.html"; check "after kill -9 the previous catalog is whole" 0 $?
"$sp" library catalog --library "$tmp/lib" -o "$tmp/site" --quiet >/dev/null 2>&1; check "the next run succeeds" 0 $?
[ -z "$(find "$tmp" -mindepth 1 -maxdepth 1 -name '.site.*')" ]; check "and leaves no temporaries of the killed run" 0 $?

echo "hostile files: $fails failed"
exit $((fails > 0))
