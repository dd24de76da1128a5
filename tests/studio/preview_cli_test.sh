#!/usr/bin/env bash
# `sandpaper preview` from the command line: every example material writes its files; bad input
# changes nothing and exits as the README says (1 wrong input, 2 usage).
set -uo pipefail
sp="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
ok() { echo "ok   $1"; pass=$((pass + 1)); }
bad() { echo "FAIL $1"; fail=$((fail + 1)); }
for f in examples/*.hmat examples/laws/*.hmat; do
  out="$tmp/$(basename "$f" .hmat)"
  if "$sp" preview "$f" -o "$out" >/dev/null 2>&1 && [ -s "$out/scan.svg" ] && [ -s "$out/preview.json" ]; then
    if grep -q '"height"' "$out/preview.json"; then
      if [ -s "$out/height.png" ] && [ -s "$out/field.png" ]; then ok "preview $f"; else bad "preview $f: pictures missing"; fi
    else
      ok "preview $f (no position-dependent force: plot only)"
    fi
  else
    bad "preview $f"
  fi
done
"$sp" preview -e "grating period 2.5 mm amplitude 1 N" -o "$tmp/side" --side 128 >/dev/null 2>&1
python3 - "$tmp/side/height.png" <<'PY' && ok "--side 128 gives a 128-pixel picture" || bad "--side 128"
import struct, sys
with open(sys.argv[1], "rb") as f:
    head = f.read(24)
w, h = struct.unpack(">II", head[16:24])
sys.exit(0 if head[:8] == b"\x89PNG\r\n\x1a\n" and max(w, h) == 128 else 1)
PY
mkdir -p "$tmp/keep" && echo "mine" > "$tmp/keep/height.png"
"$sp" preview -e "grating period 2.5 mm hill 150%" -o "$tmp/keep" >/dev/null 2>&1; rc=$?
if [ $rc -eq 1 ] && [ "$(cat "$tmp/keep/height.png")" = mine ]; then ok "a broken material exits 1 and writes nothing"; else bad "broken material: exit $rc"; fi
touch "$tmp/file"
"$sp" preview examples/corduroy.hmat -o "$tmp/file" >/dev/null 2>&1; rc=$?
[ $rc -eq 2 ] && ok "-o on a file exits 2" || bad "-o on a file: exit $rc"
"$sp" preview examples/workspace/sampler.hws -o "$tmp/ws" >/dev/null 2>&1; rc=$?
[ $rc -eq 2 ] && ok "a workspace is refused with a pointer to the studio" || bad "workspace: exit $rc"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
