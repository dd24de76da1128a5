#!/usr/bin/env bash
# A raise site's code is checked against the table when it compiles (schema::Code): E0202 compiles,
# E9999 (in no table) and W0302 spelt lower-case do not, and the compiler's message names the table.
#   code_check_test.sh CXX SOURCE_DIR
set -uo pipefail
cxx=$1 src=$2
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $1"; }
bad() { fail=$((fail + 1)); echo "FAILED: $1"; }
compile() {
  "$cxx" -std=c++20 -fsyntax-only -I"$src/schema/include" -I"$src/compiler/include" "-DRAISE=\"$1\"" \
    "$src/tests/compiler/diagnostic_code/raises.cpp" 2>&1
}
out=$(compile E0202) && ok "a registered code compiles" || bad "E0202 did not compile: $out"
for code in E9999 w0302 E030; do
  out=$(compile "$code")
  rc=$?
  [ $rc -ne 0 ] && ok "$code does not compile" || bad "$code compiled"
  grep -q 'not a diagnostic code of schema/include/sandpaper/schema/diagnostic_code_table.hpp' <<<"$out" \
    && ok "the compiler's message for $code names the table" || bad "no pointer to the table for $code: $(head -5 <<<"$out")"
done
echo "$pass passed, $fail failed"
