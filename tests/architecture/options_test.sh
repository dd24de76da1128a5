#!/usr/bin/env bash
# The core preset configures on a machine without Node/npm, Chromium or Python on PATH and without
# SQLite or Python found, and generates a build of the core that names none of them; each room's
# option turned off alone (the others as the release preset has them) still generates a build.
# Configure and generate only: a room left out whose target is still linked fails the generate step
# (CMAKE_LINK_LIBRARIES_ONLY_TARGETS); building the variants is done by hand (docs/performance.md).
#   options_test.sh SOURCE_DIR CMAKE
set -uo pipefail
src=$1 cmake=$2
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# A PATH of every program this machine has, less Node, npm, Chromium, Python and esbuild.
mkdir "$tmp/bin"
IFS=: read -ra dirs <<<"$PATH"
for d in "${dirs[@]}"; do
  for f in "$d"/*; do
    name=${f##*/}
    case $name in
      node | nodejs | npm | npx | corepack | chromium* | chrome* | google-chrome* | python* | pip* | pytest* | esbuild) continue ;;
    esac
    [ -x "$f" ] && [ ! -d "$f" ] && [ ! -e "$tmp/bin/$name" ] && ln -s "$f" "$tmp/bin/$name"
  done
done
hidden=yes
for p in node npm chromium python3 esbuild; do
  PATH=$tmp/bin command -v "$p" >/dev/null && hidden=no
done
[ $hidden = yes ] && ok "node, npm, chromium, python3 and esbuild are off PATH" || bad "a hidden program is still on PATH"

core=$tmp/core
if PATH=$tmp/bin "$cmake" -S "$src" --preset core -B "$core" -DCMAKE_DISABLE_FIND_PACKAGE_SQLite3=ON \
    -DCMAKE_DISABLE_FIND_PACKAGE_Python3=ON -DCMAKE_DISABLE_FIND_PACKAGE_Python=ON \
    -DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON >"$tmp/core.log" 2>&1; then
  ok "the core preset configures without them"
else
  bad "the core preset does not configure without them:"$'\n'"$(tail -20 "$tmp/core.log")"
fi
if [ -f "$core/CMakeCache.txt" ]; then
  hits=$(find "$core" \( -name Makefile -o -name '*.make' -o -name build.ninja -o -name CTestTestfile.cmake \) -print0 \
         | xargs -0 grep -ohiE 'esbuild|sqlite|python|node_modules|chromium|pybind11' | sort -u | tr '\n' ' ')
  [ -z "$hits" ] && ok "the core build and its tests name none of them" || bad "the core build names: $hits"
  for t in sandpaper sandpaper-play sandpaper_api sandpaper_player compiler_tests runtime_tests; do
    [ -n "$(find "$core" -type d -name "$t.dir" -print -quit)" ] && ok "core builds $t" || bad "core has no target $t"
  done
  for t in sandpaper_curation sandpaper_catalog sandpaper_studio sandpaper_experiment sandpaper_lsp sandpaper_gltf sandpaper_http sandpaper_shapes sandpaper_scenes; do
    [ -n "$(find "$core" -type d -name "$t.dir" -print -quit)" ] && bad "core builds $t" || ok "core leaves out $t"
  done
fi

# Each option off alone; a room another needs takes that one with it (a note, not an error).
for opt in CURATION LSP GLTF STUDIO EXPERIMENTS PYTHON USB_LAB SHAPES; do
  dir=$tmp/no-$opt
  if "$cmake" -S "$src" --preset release -B "$dir" "-DSANDPAPER_$opt=OFF" >"$dir.log" 2>&1; then
    ok "SANDPAPER_$opt=OFF alone configures and generates its build"
    # The CLI's files that differ between builds (SANDPAPER_WITH_<ROOM>) compile with this one's
    # definitions; the rest of the tree is the same code in every build, or left out whole.
    for f in apps/sandpaper/main.cpp apps/sandpaper/input.cpp; do
      command=$(jq -r --arg f "$src/$f" '[.[] | select(.file == $f)][0].command' "$dir/compile_commands.json")
      where=$(jq -r --arg f "$src/$f" '[.[] | select(.file == $f)][0].directory' "$dir/compile_commands.json")
      if [ "$command" = null ]; then bad "SANDPAPER_$opt=OFF: no compile command for $f"; continue; fi
      if (cd "$where" && eval "$command -fsyntax-only") >"$dir.cc.log" 2>&1; then
        ok "SANDPAPER_$opt=OFF: $f compiles"
      else
        bad "SANDPAPER_$opt=OFF: $f does not compile: $(grep -m3 error "$dir.cc.log")"
      fi
    done
  else
    bad "SANDPAPER_$opt=OFF: $(tail -15 "$dir.log")"
  fi
  rm -rf "$dir"
done
grep -q 'SANDPAPER_STUDIO is off: it needs SANDPAPER_CURATION and SANDPAPER_LSP' "$tmp/no-CURATION.log" \
  && ok "turning curation off says the studio goes with it" || bad "no note that the studio went with curation"

echo "$pass passed, $fail failed"
