#!/usr/bin/env bash
# Queries over a layered path agree with the compiler (docs/LIBRARY.md, "Queries see what the
# compiler sees"): a lab's `corduroy` (hill 40 %, roughness 0.8) over a copy of the shipped library
# changes every world entry built `like corduroy` on that path. `library show`, `search` and `near`
# must give what `explain` gives for them over the same path, before and after `library index`.
#   layered_agrees_test.sh SANDPAPER LIBRARY_DIR
set -uo pipefail
sp=$1 shipped=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1"; }

mkdir -p "$tmp/world" "$tmp/lab/textiles"
(cd "$shipped" && tar --exclude=.index -cf - .) | (cd "$tmp/world" && tar -xf -)
# A world entry that takes its roughness from corduroy (the lab's, on this path).
cat >"$tmp/world/textiles/corduroy-offcut.hmat" <<'HMAT'
material "corduroy-offcut" {
  describes "an offcut of wide-wale corduroy"
  family textiles
  licence "CC0-1.0"
  like corduroy
}
HMAT
printf 'name = "a lab"\nid = "lab"\nversion = "0.1.0"\n' >"$tmp/lab/library.toml"
sed -e 's/hill 60%/hill 40%/' -e 's/^  roughness 0.45/  roughness 0.8/' -e 's/^material "corduroy" {/&\n  overrides/' \
  "$shipped/textiles/corduroy.hmat" >"$tmp/lab/textiles/corduroy.hmat"
grep -q "hill 40%" "$tmp/lab/textiles/corduroy.hmat" && grep -q "roughness 0.8" "$tmp/lab/textiles/corduroy.hmat" || bad "the lab's corduroy was not written"
path="$tmp/lab:$tmp/world"

# explain's numbers over the path, of each entry's own file: the reference every query is held to.
for e in pinwale-corduroy corduroy-offcut; do
  "$sp" explain "$tmp/world/textiles/$e.hmat" --library "$path" --json >"$tmp/explain-$e.json" 2>/dev/null || bad "explain $e failed"
done
json "$tmp/explain-pinwale-corduroy.json" 'abs(j["provenance"]["texture.hill"]["value"] - 0.4) < 1e-12' && ok \
  || bad "explain does not see the lab's hill 40 % (the test's premise)"

for round in "index built by the first query" "after library index"; do
  # Provenance of show = explain's, parameter by parameter (value and layer).
  for e in pinwale-corduroy corduroy-offcut; do
    "$sp" library show "$e" --library "$path" --quiet --json >"$tmp/show.json" 2>"$tmp/show.err" || bad "$round: show $e failed: $(cat "$tmp/show.err")"
    python3 - "$tmp/show.json" "$tmp/explain-$e.json" <<'PY' && ok || bad "$round: show $e disagrees with explain"
import json, sys
show, explain = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
want = {k: (v["value"], v["layer"]) for k, v in explain["provenance"].items()}
got = {r["parameter"]: (r["value_si"], r["layer"]) for r in show["provenance"]}
bad = [k for k in want if k not in got or abs(got[k][0] - want[k][0]) > 1e-9 * max(1, abs(want[k][0])) or got[k][1] != want[k][1]]
for k in bad: print(f"  {k}: show {got.get(k)} explain {want[k]}")
if abs(show["compiled_roughness"] - explain["compiled_roughness"]) > 1e-9: bad.append("roughness"); print("  roughness", show["compiled_roughness"], explain["compiled_roughness"])
if abs(show["compiled_max_lateral_force_N"] - explain["compiled_max_lateral_force_N"]) > 1e-9: bad.append("force")
if show["root"] != "library" and show["root"] != "world": bad.append("root " + show["root"])
sys.exit(1 if bad else 0)
PY
  done
  # search: a bound around explain's roughness for the offcut (0.8, the lab's corduroy) finds it.
  "$sp" library search --roughness 0.79..0.81 --library "$path" --quiet --json >"$tmp/search.json" 2>/dev/null
  json "$tmp/search.json" 'any(h["name"] == "corduroy-offcut" and h["root"] == "world" and abs(h["compiled_roughness"] - 0.8) < 1e-9 for h in j)' \
    && ok || bad "$round: search --roughness 0.79..0.81 does not find world:corduroy-offcut: $(head -c 400 "$tmp/search.json")"
  "$sp" library search offcut --library "$path" --quiet --json >"$tmp/search2.json" 2>/dev/null
  json "$tmp/search2.json" 'len(j) == 1 and abs(j[0]["compiled_roughness"] - 0.8) < 1e-9' \
    && ok || bad "$round: search offcut: $(head -c 400 "$tmp/search2.json")"
  # near: the offcut is the lab's corduroy over this path, 0 JND apart; the world's corduroy is hidden.
  "$sp" library near corduroy --library "$path" --quiet --json --limit 3 >"$tmp/near.json" 2>/dev/null
  json "$tmp/near.json" 'j["from"] == "lab:corduroy" and j["nearest"][0]["name"] == "corduroy-offcut" and j["nearest"][0]["distance_jnd"] < 1e-9 and not any(n["name"] == "corduroy" for n in j["nearest"])' \
    && ok || bad "$round: near corduroy: $(head -c 500 "$tmp/near.json")"
  "$sp" library index --library "$path" --quiet >/dev/null 2>&1 || bad "library index failed"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
