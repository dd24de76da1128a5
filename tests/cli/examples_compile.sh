#!/usr/bin/env bash
# Every example material file and workspace compiles with the shipped library and calibration,
# without errors. Usage: examples_compile.sh path/to/sandpaper (run from the source tree).
set -u
sp=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0 fail=0
while IFS= read -r f; do
  n=$((n + 1))
  if ! "$sp" compile "$f" -o "$tmp/out" >"$tmp/log" 2>&1; then
    fail=$((fail + 1))
    echo "FAIL: $f"
    cat "$tmp/log"
  fi
done < <(find examples -name '*.hmat' -o -name '*.hws' | sort)
echo "$n example files, $fail failed"
[ "$n" -gt 0 ] && [ "$fail" -eq 0 ]
