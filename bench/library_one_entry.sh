#!/usr/bin/env bash
# One-entry updates and queries on generated libraries (docs/performance.md, "The library at scale"):
# for each LIBRARY:CATALOG:ENTRY given, three runs each of `library catalog` after appending a comment
# to ENTRY (an entry nothing is built on), `library index` after the same, `library index` with
# nothing changed, `library catalog` after `library index`, and `library search`, `show` and `near`.
# First, the one-entry runs with `--changed FILE` (index-changed, index-changed-none, catalog-changed); with
# ONE_ENTRY_ONLY_CHANGED=1 only those.
# Prints "<library> <what> <wall> s <user> u <system> s <max RSS> KB" per run (/usr/bin/time).
#   bench/library_one_entry.sh BIN /tmp/g1k:/tmp/cat1k:gen-gratings/000/gen-grating-000009.hmat ...
# The libraries come from tools/library_gen.py; a catalog may be seeded by bench/catalog_seed.py.
set -euo pipefail
B=$1
shift
T='%e s %U u %S s %M KB'
timed() {  # $1: label; the rest: the command (its output dropped, the time line kept)
  local label=$1
  shift
  /usr/bin/time -f "$label $T" "$@" 2>&1 >/dev/null | tail -1
}
for spec in "$@"; do
  IFS=: read -r lib cat entry <<<"$spec"
  f=$lib/$entry
  name=$(basename "$entry" .hmat)
  n=$(basename "$lib")
  "$B" library index --library "$lib" --quiet >/dev/null
  "$B" library catalog --library "$lib" -o "$cat" --quiet >/dev/null
  sleep 3  # past the 2 s window in which a file's stamp is racy (curation/src/stamps.hpp)
  # Told which file changed (`--changed`): nothing walked.
  for i in 1 2 3; do echo "# touched l$i" >>"$f"; timed "$n index-changed" "$B" library index --library "$lib" --quiet --changed "$f"; done
  for i in 1 2 3; do timed "$n index-changed-none" "$B" library index --library "$lib" --quiet --changed "$f"; done
  for i in 1 2 3; do
    echo "# touched m$i" >>"$f"
    timed "$n catalog-changed" "$B" library catalog --library "$lib" -o "$cat" --quiet --changed "$f"
  done
  [ -n "${ONE_ENTRY_ONLY_CHANGED:-}" ] && continue
  for i in 1 2 3; do echo "# touched c$i" >>"$f"; timed "$n catalog-one" "$B" library catalog --library "$lib" -o "$cat" --quiet; done
  for i in 1 2 3; do echo "# touched i$i" >>"$f"; timed "$n index-one" "$B" library index --library "$lib" --quiet; done
  sleep 3
  for i in 1 2 3; do timed "$n index-none" "$B" library index --library "$lib" --quiet; done
  for i in 1 2 3; do
    echo "# touched a$i" >>"$f"
    "$B" library index --library "$lib" --quiet >/dev/null
    timed "$n catalog-after-index" "$B" library catalog --library "$lib" -o "$cat" --quiet
  done
  for i in 1 2 3; do timed "$n search" "$B" library search corduroy --library "$lib"; done
  for i in 1 2 3; do timed "$n show" "$B" library show "$name" --library "$lib"; done
  for i in 1 2 3; do timed "$n near" "$B" library near "$name" --library "$lib"; done
done
for i in 1 2 3; do timed "start-up --help" "$B" --help; done
