#!/usr/bin/env bash
# The README's main command builds what it runs (compile and play one shipped example), not the test
# suite: its configure and build steps, replayed in a scratch folder as a dry run, compile nothing of
# tests/, bench/, fuzz/, usb-lab/ or bindings/, yet do build the CLI's code and sandpaper-play.
#   main_command_test.sh SOURCE_DIR CMAKE
set -uo pipefail
src=$1 cmake=$2
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cmd=$(awk '/<!-- main-command -->/{getline; sub(/^ +/, ""); print; exit}' "$src/README.md")
if [ -z "$cmd" ]; then
  bad "no main command in README.md"
  echo "$pass passed, $fail failed"
  exit 1
fi
configure_preset=$(grep -oE 'cmake --preset [A-Za-z0-9_-]+' <<<"$cmd" | head -1 | awk '{print $3}')
build=$(grep -oE 'cmake --build --preset [A-Za-z0-9_-]+( --target [A-Za-z0-9_ -]+)?' <<<"$cmd" | head -1)
targets=$(sed -nE 's/.*--target ([A-Za-z0-9_ -]+)$/\1/p' <<<"$build" | xargs)
[ -n "$configure_preset" ] && [ -n "$build" ] && ok "it configures preset '$configure_preset' and builds: ${targets:-all}" \
  || bad "cannot read its configure and build steps: $cmd"
[ -n "$targets" ] && ok "it names the targets it builds" || bad "it builds every target (no --target)"

if "$cmake" -S "$src" --preset "$configure_preset" -B "$tmp/b" >"$tmp/configure.log" 2>&1; then
  ok "preset $configure_preset configures"
else
  bad "preset $configure_preset does not configure: $(tail -5 "$tmp/configure.log")"
fi
# A dry run of the same build: make prints each object it would compile (-k: past the archives
# a dry run does not make).
# shellcheck disable=SC2086
"$cmake" --build "$tmp/b" ${targets:+--target $targets} -- -n -k >"$tmp/plan.log" 2>&1
objects=$(grep -oE 'Building C(XX)? object [^"]+' "$tmp/plan.log" | awk '{print $4}' | sort -u)
count=$(grep -c . <<<"$objects")
[ "$count" -gt 20 ] && ok "the dry run plans $count objects" || bad "the dry run plans $count objects: $(tail -5 "$tmp/plan.log")"
extra=$(grep -E '^(tests|bench|fuzz|usb-lab|bindings)/' <<<"$objects" | sed -E 's|/CMakeFiles/([^/]+)\.dir/.*| \1|' | sort -u | tr '\n' ';')
[ -z "$extra" ] && ok "none of them for tests, benchmarks, fuzzing, the USB lab or Python" || bad "it also builds: $extra"
# The programs' own steps (a dry run stops short of linking: the archives they need are not made).
for target in sandpaper_cli sandpaper-play; do
  grep -qE "apps/CMakeFiles/$target\.dir/build\.make apps/CMakeFiles/$target\.dir/build" "$tmp/plan.log" \
    && ok "it builds $target" || bad "it does not build $target"
done

echo "$pass passed, $fail failed"
