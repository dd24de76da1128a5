#!/usr/bin/env bash
# Every room's commands are listed by `sandpaper --help`; a built room's command runs (its --help),
# and one whose room was left out says which option builds it, exits 2 and writes nothing.
#   rooms_test.sh SANDPAPER curation=ON|OFF gltf=... studio=... lsp=... experiments=...
set -uo pipefail
sp=$1
shift
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

declare -A option=([curation]=SANDPAPER_CURATION [gltf]=SANDPAPER_GLTF [studio]=SANDPAPER_STUDIO [lsp]=SANDPAPER_LSP
                   [experiments]=SANDPAPER_EXPERIMENTS)
declare -A commands=([curation]="library preview" [gltf]="export" [studio]="studio" [lsp]="lsp" [experiments]="experiment")
"$sp" --help >"$tmp/help" 2>&1
for c in compile explain run inspect; do
  grep -qE "^  $c( |$)" "$tmp/help" && ok "--help lists $c" || bad "--help does not list $c"
done
for arg in "$@"; do
  room=${arg%%=*}
  built=${arg#*=}
  for c in ${commands[$room]}; do
    grep -qE "^  $c( |$)" "$tmp/help" && ok "--help lists $c" || bad "--help does not list $c"
    case $built in
      ON | on | 1 | TRUE | true)
        "$sp" "$c" --help >"$tmp/out" 2>&1 && ok "$c runs (--help)" || bad "$c --help failed: $(head -3 "$tmp/out")"
        grep -q 'built without' "$tmp/out" && bad "$c says it is not built though $room is" || ok "$c is built" ;;
      *)
        (cd "$tmp" && "$sp" "$c" somefile.hmat -o out --help >"$tmp/out" 2>&1)
        rc=$?
        [ $rc -eq 2 ] && ok "$c without $room exits 2" || bad "$c without $room exited $rc"
        grep -qF "sandpaper $c: this sandpaper was built without" "$tmp/out" && grep -qF -- "-D${option[$room]}=ON" "$tmp/out" \
          && ok "$c names ${option[$room]}" || bad "$c's message: $(cat "$tmp/out")"
        [ -z "$(ls "$tmp")" ] || [ "$(ls "$tmp")" = "$(printf 'help\nout')" ] && ok "$c wrote nothing" || bad "$c wrote: $(ls "$tmp")" ;;
    esac
  done
  if [ "$room" = gltf ] && [[ $built != ON && $built != on ]]; then
    printf '{"asset":{"version":"2.0"}}' >"$tmp/a.gltf"
    "$sp" compile "$tmp/a.gltf" -o "$tmp/a.patch" >"$tmp/out" 2>&1
    rc=$?
    [ $rc -eq 2 ] && grep -qF -- "-DSANDPAPER_GLTF=ON" "$tmp/out" && [ ! -e "$tmp/a.patch" ] \
      && ok "compiling a .gltf without glTF says which option reads it" || bad "compile a.gltf: exit $rc, $(cat "$tmp/out")"
    rm -f "$tmp/a.gltf"
  fi
done
echo "$pass passed, $fail failed"
