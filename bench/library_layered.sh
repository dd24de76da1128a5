#!/usr/bin/env bash
# One-entry updates of a layered library's catalog and index, walking and told the file (`--changed`)
# (docs/performance.md, "A layered library"): a small lab root (three entries, one hiding a world entry) in front of a generated
# world library. The catalog's record is seeded (bench/catalog_seed.py --hashes), since drawing a
# 100,000-entry catalog takes hours; the first run then draws what the seed could not know.
# Prints "<world> <what> <wall> s <user> u <system> s <max RSS> KB" per run (/usr/bin/time), three each.
#   bench/library_layered.sh BUILD_BIN_DIR /tmp/g10k [/tmp/g100k ...]
set -euo pipefail
bin=$1
shift
B=$bin/sandpaper
here=$(cd "$(dirname "$0")" && pwd)
T='%e s %U u %S s %M KB'
timed() {  # $1: label; the rest: the command (its output dropped, the time line kept)
  local label=$1
  shift
  /usr/bin/time -f "$label $T" "$@" 2>&1 >/dev/null | tail -1
}
for world in "$@"; do
  n=$(basename "$world")
  work=$(mktemp -d "/tmp/layered-$n-XXXX")
  lab=$work/lab cat=$work/catalog
  mkdir -p "$lab"
  printf 'id = "lab"\nname = "a lab"\nversion = "0.1.0"\n' >"$lab/library.toml"
  printf 'material "our-grating" {\n  like gen-grating-000019\n  describes "our swatch"\n  roughness 0.5\n}\n' >"$lab/our-grating.hmat"
  printf 'material "our-spring" {\n  describes "our spring"\n  spring 150 N/m\n}\n' >"$lab/our-spring.hmat"
  printf 'material "gen-grating-000009" {\n  overrides\n  describes "the lab'"'"'s own"\n  grating period 2 mm\n  roughness 0.4\n}\n' \
    >"$lab/gen-grating-000009.hmat"
  timed "$n layered-index-first" "$B" library index --library "$lab:$world" --quiet
  "$bin/sandpaper_layered_inputs" "$lab" "$world" >"$work/hashes.tsv"
  python3 "$here/catalog_seed.py" --hashes "$work/hashes.tsv" "$lab/.index/library.sqlite" "$world/.index/library.sqlite" "$cat" >/dev/null
  timed "$n layered-catalog-after-seed" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet
  sleep 3  # past the 2 s window in which a file's stamp is racy (curation/src/stamps.hpp)
  for i in 1 2 3; do timed "$n layered-catalog-none" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet; done
  for i in 1 2 3; do
    echo "# touched c$i" >>"$lab/our-grating.hmat"
    timed "$n layered-catalog-lab-one" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet
  done
  for i in 1 2 3; do
    echo "# touched d$i" >>"$lab/our-grating.hmat"
    timed "$n layered-catalog-lab-one-changed" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet --changed "$lab/our-grating.hmat"
  done
  for i in 1 2 3; do
    echo "# touched i$i" >>"$lab/our-grating.hmat"
    timed "$n layered-index-lab-one" "$B" library index --library "$lab:$world" --quiet
  done
  f=$world/gen-gratings/000/gen-grating-000029.hmat
  for i in 1 2 3; do
    echo "# touched w$i" >>"$f"
    timed "$n layered-catalog-world-one" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet
  done
  for i in 1 2 3; do
    echo "# touched v$i" >>"$f"
    timed "$n layered-catalog-world-one-changed" "$B" library catalog --library "$lab:$world" -o "$cat" --quiet --changed "$f"
  done
  "$B" library catalog --library "$lab:$world" -o "$cat" >"$work/out" 2>/dev/null
  echo "$n last: $(cat "$work/out")"
  rm -rf "$work"
done
