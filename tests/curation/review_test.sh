#!/usr/bin/env bash
# `sandpaper library review` on branches of a library kept in git (docs/LIBRARY.md, "Reviewing a pull
# request"): a branch that adds a good entry passes; branches that add each defect the curator's desk
# fixed fail with its code: a name taken (E0607), an image leaving the library through a link
# (E0612), an image without its licence (E0615), a licence that is not SPDX (E0605), a new warning
# not accepted (W0350); what a person must judge (a measurement, an image) is listed; an unknown
# --base is a usage error (exit 2).
#   review_test.sh SANDPAPER MINI_LIBRARY SHIPPED_LIBRARY
set -uo pipefail
sp=$1 mini=$2 shipped=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
git_() { git -C "$tmp/repo" -c user.name=review-test -c user.email=review-test@example.invalid -c commit.gpgsign=false "$@"; }

mkdir -p "$tmp/repo"
git_ init -q -b main
cp -r "$mini" "$tmp/repo/lib"
git_ add -A && git_ commit -qm base || bad "the base commit failed"
L=(--library "$tmp/repo/lib" --base main --quiet)

good() {
  cat >"$tmp/repo/lib/textiles/wide-rib.hmat" <<'HMAT'
material "wide-rib" {
  describes "a wide-ribbed upholstery cloth"
  family textiles
  licence "CC-BY-SA-4.0 AND CC0-1.0"
  grating period 6 mm hill 50%
  source measurement "ribs counted over 60 mm of a sample: 10 ribs"
  roughness 0.3
  source by-ear "a soft, wide rib"
}
HMAT
}

# On a branch: start from the base, make the change, review; expect exit $1 and, on failure, code $2.
branch() {
  local name=$1 want=$2 code=$3
  git_ checkout -q -f main && git_ clean -qfdx
  git_ checkout -q -b "$name"
  "change_$name"
  "$sp" library review "${L[@]}" >"$tmp/$name.out" 2>"$tmp/$name.err"
  local rc=$?
  [ "$rc" -eq "$want" ] && ok || bad "$name: exit $rc, expected $want: $(cat "$tmp/$name.out" "$tmp/$name.err" | head -30)"
  if [ -n "$code" ]; then
    grep -q "\[$code\]" "$tmp/$name.err" && ok || bad "$name: no $code in: $(head -20 "$tmp/$name.err")"
  fi
}

change_good() { good; git_ add -A && git_ commit -qm "add wide-rib"; }
branch good 0 ""
grep -q "review passed" "$tmp/good.out" && ok || bad "good: not said to pass: $(cat "$tmp/good.out")"
grep -q "1 changed file, 1 entry touched" "$tmp/good.out" && ok || bad "good: the summary: $(cat "$tmp/good.out")"
grep -q 'measurement in textiles/wide-rib.hmat:6 (grating): "ribs counted' "$tmp/good.out" && ok \
  || bad "good: the measurement is not listed for a person: $(cat "$tmp/good.out")"

# Uncommitted work counts too (a contributor reviewing before committing).
change_uncommitted() { good; }
branch uncommitted 0 ""

change_clash() { good; sed -i 's/"wide-rib"/"fine-rib"/' "$tmp/repo/lib/textiles/wide-rib.hmat"; mv "$tmp/repo/lib/textiles/wide-rib.hmat" "$tmp/repo/lib/abrasives/fine-rib.hmat"; }
branch clash 1 E0607
grep -q "abrasives/fine-rib.hmat:1:10: error\[E0607\]: name 'fine-rib' is already the name of textiles/fine-rib.hmat" "$tmp/clash.err" && ok \
  || bad "clash: the error is not the newcomer's: $(grep E0607 "$tmp/clash.err")"

change_link() {
  good
  mkdir -p "$tmp/repo/lib/images" "$tmp/outside"
  printf 'P2\n2 2\n255\n0 255\n255 0\n' >"$tmp/outside/x.pgm"
  ln -s "$tmp/outside/x.pgm" "$tmp/repo/lib/images/x.pgm"
  sed -i 's|  grating period 6 mm hill 50%|  heightmap "../images/x.pgm" size 10 mm|' "$tmp/repo/lib/textiles/wide-rib.hmat"
}
branch link 1 E0612
# The link has no licence file beside it either: said in the same round, not after the image is copied in.
grep -q "\[E0615\]: image '../images/x.pgm' has no licence" "$tmp/link.err" && ok || bad "link: no E0615 with the E0612: $(grep -E 'E06' "$tmp/link.err")"

change_unlicensed() {
  good
  mkdir -p "$tmp/repo/lib/images"
  cp "$shipped/images/gravel.png" "$tmp/repo/lib/images/gravel.png"
  sed -i 's|  grating period 6 mm hill 50%|  heightmap "../images/gravel.png" size 6 mm|' "$tmp/repo/lib/textiles/wide-rib.hmat"
}
branch unlicensed 1 E0615
grep -q "image images/gravel.png (used by wide-rib): look at it" "$tmp/unlicensed.out" && ok \
  || bad "unlicensed: the new image is not listed for a person: $(cat "$tmp/unlicensed.out")"

change_licence() { good; sed -i 's/licence "CC-BY-SA-4.0 AND CC0-1.0"/licence "CC-BY-SA-4.0 and CC0-1.0"/' "$tmp/repo/lib/textiles/wide-rib.hmat"; }
branch licence 1 E0605

change_warning() { good; sed -i 's/grating period 6 mm hill 50%/grating period 1.2 mm hill 50%/' "$tmp/repo/lib/textiles/wide-rib.hmat"; }
branch warning 1 W0350
# Accepting it, with a reason, passes.
change_accepted() { change_warning; sed -i 's/  licence "CC-BY-SA-4.0 AND CC0-1.0"/&\n  accept W0350 "a fine rib: felt weaker when stroked fast, as it should"/' "$tmp/repo/lib/textiles/wide-rib.hmat"; }
branch accepted 0 ""
grep -q "accepted" "$tmp/accepted.out" && ok || bad "accepted: $(cat "$tmp/accepted.out")"

# An unknown base is a clear error, of usage (exit 2): nothing was reviewed.
"$sp" library review --library "$tmp/repo/lib" --base no-such-branch --quiet >/dev/null 2>"$tmp/base.err"
[ $? -eq 2 ] && grep -q "no commit 'no-such-branch'" "$tmp/base.err" && ok || bad "unknown base: $(cat "$tmp/base.err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
