#!/usr/bin/env bash
# `sandpaper library index|search|show|near` over a layered path (issue 18; docs/LIBRARY.md,
# "Layered libraries"): a lab's root on top of a generated world library. Each root gets its own
# index; the lab's entry hides the world's of the same name; the JSON says which root an entry is from.
#   layered_cli_test.sh SANDPAPER LIBRARY_GEN
set -uo pipefail
sp=$1 gen=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1"; }

python3 "$gen" 60 "$tmp/world" --seed 5 >/dev/null || bad "the generator failed"
n="gen-grating-000001"  # a generated grating that "describes" corduroy
[ -f "$tmp/world/gen-gratings/000/$n.hmat" ] || bad "the generated library has no $n"
mkdir -p "$tmp/lab/cloth"
printf 'id = "lab"\nname = "a lab"\nversion = "0.1.0"\n[families.cloth]\ntitle = "Cloth"\n' >"$tmp/lab/library.toml"
printf 'material "%s" {\n  overrides\n  family cloth\n  describes "our corduroy swatch"\n  like world:%s\n  roughness 0.7\n}\n' "$n" "$n" \
  >"$tmp/lab/cloth/$n.hmat"
path="$tmp/lab:$tmp/world"

"$sp" library index --library "$path" --quiet --json >"$tmp/index.json" 2>"$tmp/index.err" || { bad "index failed"; cat "$tmp/index.err"; }
json "$tmp/index.json" 'j["ok"] and [r["root"] for r in j["roots"]] == ["lab", "world"] and j["roots"][0]["entries"] == 1' \
  && ok || bad "index: $(cat "$tmp/index.json")"
[ -f "$tmp/lab/.index/library.sqlite" ] && [ -f "$tmp/world/.index/library.sqlite" ] && ok || bad "an index in each root"

"$sp" library search corduroy --library "$path" --quiet --json >"$tmp/search.json" || bad "search failed"
json "$tmp/search.json" 'any(h["root"] == "lab" and h["name"] == "'$n'" for h in j) and not any(h["root"] == "world" and h["name"] == "'$n'" for h in j) and len(j) == 5' \
  && ok || bad "search: the lab's $n, not the world's it hides: $(head -c 600 "$tmp/search.json")"

"$sp" library show "world:$n" --library "$path" --quiet --json >"$tmp/show.json" || bad "show world:$n failed"
json "$tmp/show.json" 'j["root"] == "world" and j["name"] == "'$n'"' && ok || bad "show world:$n: $(head -c 300 "$tmp/show.json")"
"$sp" library show "$n" --library "$path" --quiet >"$tmp/show.txt" || bad "show $n failed"
grep -q "hides world:$n" "$tmp/show.txt" && ok || bad "show does not say what the lab's $n hides: $(head -8 "$tmp/show.txt")"
grep -q "($tmp/world/gen-gratings/000/$n.hmat:[0-9]*:[0-9]*)" "$tmp/show.txt" && ok || bad "show: no provenance from the world's file, named where it is"

"$sp" library near "$n" --library "$path" --quiet --json --limit 5 >"$tmp/near.json" || bad "near failed"
json "$tmp/near.json" 'j["from"] == "lab:'$n'" and len(j["nearest"]) == 5 and all(n["root"] == "world" for n in j["nearest"])' \
  && ok || bad "near: $(head -c 400 "$tmp/near.json")"

"$sp" library search corduroy --library "$path" --index "$tmp/x.sqlite" --quiet >/dev/null 2>"$tmp/err.txt"
[ $? -eq 2 ] && grep -q "leave --index out" "$tmp/err.txt" && ok || bad "--index with a layered path: $(cat "$tmp/err.txt")"

# An edit in the lab makes its index stale; the next query rebuilds it.
sed -i 's/roughness 0.7/roughness 0.8/' "$tmp/lab/cloth/$n.hmat"
touch -d '+2 seconds' "$tmp/lab/cloth"
"$sp" library show "$n" --library "$path" --json >"$tmp/show2.json" 2>"$tmp/show2.err" || bad "show after an edit failed"
json "$tmp/show2.json" 'abs(j["compiled_roughness"] - 0.8) < 1e-9' && ok || bad "the edit was not seen: $(cat "$tmp/show2.err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
