#!/usr/bin/env python3
"""Browser test of `sandpaper library catalog` (docs/CATALOG.md): writes the catalog of the shipped
library, opens index.html from file:// in headless Chromium, reads every entry page by page, filters by
family, by a roughness range, by licence and by source kind and checks exactly which entries remain,
orders them by roughness, ticks three and compares them side by side (pictures at one scale, the
numbers, force plots on shared axes), follows a link to an entry page and checks what it shows, and
that its similar entries are those `sandpaper library near` gives. (index_scale_browser_test.py tries
the index with 100,000 entries.)

The expected entries come from the library itself, not from the catalog: roughness from
`sandpaper library --json` (which compiles each entry on its own), families from the entries' files.
Screenshots: <out>/index-filtered.png, <out>/entry.png, <out>/compare.png.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1).
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser, chromium_for_test  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def expected_entries(sandpaper, library):
    """{name: {"roughness": float|None, "family": str}} from the library, independently of the catalog."""
    out = subprocess.run([sandpaper, "library", "--json", "--library", str(library)], check=True,
                         capture_output=True, text=True).stdout
    entries = {}
    for e in json.loads(out):
        textured = e.get("compiled_max_lateral_force_N", 0) > 0
        entries[e["name"]] = {"roughness": e["compiled_roughness"] if textured else None, "family": e.get("family")}
    # `family WORD`, `licence "..."` and the kinds of `source` notes as written in each entry's own
    # file (none of them is inherited through `like`).
    for f in library.rglob("*.hmat"):
        if f.stem not in entries:
            continue
        text = f.read_text()
        if entries[f.stem]["family"] is None:
            m = re.search(r"^\s*family\s+([A-Za-z0-9_.-]+)", text, re.M)
            entries[f.stem]["family"] = m.group(1) if m else ""
        m = re.search(r'^\s*licence\s+"([^"]*)"', text, re.M)
        entries[f.stem]["licence"] = m.group(1) if m else ""
        entries[f.stem]["sources"] = set(re.findall(r"^\s*source\s+(measurement|standard|publication|derived|by-ear)\b",
                                                    text, re.M))
    return entries


def ordered_names(b):
    """Every entry the filters keep, in the order shown. The index makes only the rows of the page
    shown (100 a page), so this turns the pages with the pager's 'next' button and reads each."""
    names = []
    while True:
        names += page_names(b)
        page, pages = b.evaluate("[Number(document.body.dataset.page), Number(document.body.dataset.pages)]")
        if page >= pages:
            break
        b.click("#pager-bottom .next")
        b.wait_for(f"document.body.dataset.page === '{page + 1}'", f"page {page + 1}")
    return names


def choose(b, select_id, value):
    b.evaluate("(() => { const s = document.getElementById(%s); s.value = %s;"
               " s.dispatchEvent(new Event('change', {bubbles: true})); })()" % (json.dumps(select_id), json.dumps(value)))


def order_licence_and_sources(b, expected, names):
    """Order by roughness, and the licence and source-kind filters, against the entries' own files."""
    choose(b, "order", "roughness")
    got = ordered_names(b)
    rough = lambda n: expected[n]["roughness"]
    textured = sorted((n for n in names if rough(n) is not None), key=lambda n: (rough(n), n))
    check(got[:len(textured)] == textured and set(got[len(textured):]) == {n for n in names if rough(n) is None},
          f"order=roughness lists the textured entries smoothest first, then those without a texture "
          f"(first {got[:4]}, want {textured[:4]})")
    choose(b, "order", "-roughness")
    got = ordered_names(b)
    check(got[:len(textured)] == sorted(textured, key=lambda n: (-rough(n), n)),
          f"order=-roughness lists the roughest first ({got[:4]})")
    check("order=-roughness" in b.evaluate("location.hash"), "the order is kept in the URL hash")
    choose(b, "order", "")

    licences = {}
    for n in names:
        licences.setdefault(expected[n]["licence"], set()).add(n)
    options = b.evaluate("Array.from(document.querySelectorAll('#licence option')).map(o => [o.value, o.textContent])")
    check({v for v, _ in options if v} == {l if l else "(none)" for l in licences},
          f"the licence filter lists the licences the entries state ({[v for v, _ in options]})")
    # The least used licence: a filter that drops most entries.
    rare = min(licences, key=lambda l: (len(licences[l]), l))
    choose(b, "licence", rare if rare else "(none)")
    got = visible_names(b)
    check(got == licences[rare] and len(got) < len(names), f"licence {rare!r}: shows exactly {sorted(licences[rare])}, got {sorted(got)}")
    choose(b, "licence", "")

    for kind in ("measurement", "derived", "by-ear"):
        want = {n for n in names if kind in expected[n]["sources"]}
        check(0 < len(want) < len(names), f"some entries have a {kind} note and some do not ({len(want)})")
        choose(b, "source", kind)
        got = visible_names(b)
        check(got == want, f"source {kind}: shows exactly the {len(want)} entries with such a note ({len(got)} shown"
              + ("" if got == want else f"; missing {sorted(want - got)[:5]}, extra {sorted(got - want)[:5]}") + ")")
    want = {n for n in names if not expected[n]["sources"]}
    choose(b, "source", "none")
    check(visible_names(b) == want, f"source none: the {len(want)} entries without a note")
    choose(b, "source", "")


def compare(b, expected, picks, out):
    """Ticks `picks` in the index, opens the compare page and checks it against the library's numbers."""
    for n in picks:
        b.evaluate("(() => { const f = document.getElementById('q'); f.value = %s;"
                   " f.dispatchEvent(new Event('input', {bubbles: true})); })()" % json.dumps(n))
        b.wait_for(f"!!document.querySelector('#entries tr[data-name=\"{n}\"] td.pick input')", f"{n}'s row")
        b.click(f"#entries tr[data-name=\"{n}\"] td.pick input")
    check(b.evaluate("document.getElementById('compare-bar').hidden") is False, "ticking shows the compare bar")
    check(b.evaluate("document.getElementById('compare-count').textContent").startswith(f"{len(picks)} entries"),
          "the bar counts the ticked entries")
    href = b.evaluate("document.getElementById('compare-go').getAttribute('href')")
    check(urllib.parse.parse_qs(href.split("#", 1)[1]).get("e") == picks, f"the compare link names them in order ({href})")
    b.clear_events()
    b.click("#compare-go")
    b.wait_event("Page.loadEventFired")
    b.wait_for("document.body.dataset.ready === 'true'", "the compare page's script")
    heads = b.evaluate("Array.from(document.querySelectorAll('#compare thead th[data-name]')).map(t => t.dataset.name)")
    check(heads == picks, f"the compare page has a column an entry, in order ({heads})")
    b.wait_for("Array.from(document.querySelectorAll('.compare-picture img')).every(i => i.complete)", "the pictures")
    imgs = b.evaluate("Array.from(document.querySelectorAll('.compare-picture img')).map(i => "
                      "[i.naturalWidth, i.getBoundingClientRect().width, Number(i.dataset.windowMm)])")
    check(len(imgs) == len([n for n in picks if expected[n]["roughness"] is not None]) and
          all(w > 0 and abs(css - imgs[0][1]) < 0.5 and mm == imgs[0][2] for w, css, mm in imgs),
          f"every picture loaded and shows the same square at the same size: one scale ({imgs})")
    rows = b.evaluate("Object.fromEntries(Array.from(document.querySelectorAll('#compare tbody tr')).map(tr =>"
                      " [tr.querySelector('th').textContent, Array.from(tr.querySelectorAll('td')).map(td => td.textContent)]))")
    want = [expected[n]["roughness"] for n in picks]
    got = rows.get("roughness (compiled)", [])
    check(len(got) == len(picks) and all(g.startswith("\u2014") if w is None else abs(float(g) - w) <= 0.0051 * max(w, 0.01)
                                   for g, w in zip(got, want)),
          f"the roughness row gives each entry's compiled roughness to 3 digits ({got} vs {want})")
    check(rows.get("licence") == [expected[n]["licence"] or "not stated" for n in picks], f"the licence row ({rows.get('licence')})")
    ymax = b.evaluate("Array.from(document.querySelectorAll('#plots svg.force-plot')).map(s => s.dataset.yMax)")
    check(len(ymax) == len(picks) and len(set(ymax)) == 1, f"the force plots share one axis ({ymax})")
    peaks = b.evaluate("Array.from(document.querySelectorAll('#plots svg.force-plot polyline.force-along')).map(p =>"
                       " p.getAttribute('points').trim().split(/\\s+/).length)")
    check(all(p > 10 for p in peaks), f"each plot has its curve ({peaks} points)")
    b.screenshot(str(out / "compare.png"), full_page=True)


def similar(b, sandpaper, library, out, name):
    """The entry page's similar entries against `sandpaper library near` over the same library."""
    env = dict(os.environ, SANDPAPER_LIBRARY_INDEX=str(out / "near-index.sqlite"))
    r = subprocess.run([sandpaper, "library", "near", name, "--json", "--limit", "5", "--library", str(library), "--quiet"],
                       capture_output=True, text=True, env=env)
    if not check(r.returncode == 0, f"sandpaper library near {name} exits 0 ({r.stderr.strip()[:200]})"):
        return
    want = [n["name"] for n in json.loads(r.stdout)["nearest"]]
    b.wait_for("document.body.dataset.similar === 'ready'", "the similar entries")
    got = b.evaluate("Array.from(document.querySelectorAll('#similar-list li[data-name]')).map(l => l.dataset.name)")
    check(got == want, f"{name}'s similar entries are `library near`'s, in its order ({got} vs {want})")


def page_names(b):
    return b.evaluate("Array.from(document.querySelectorAll('#entries tbody tr'))"
                      ".filter(tr => !tr.hidden && tr.offsetParent !== null).map(tr => tr.dataset.name)")


def visible_names(b):
    """Every entry the filters keep (ordered_names, as a set), each on one page only."""
    names = ordered_names(b)
    if len(names) != len(set(names)):
        check(False, f"no entry is on two pages ({len(names)} rows, {len(set(names))} names)")
    return set(names)


def shown_roughness(r):
    """The roughness as the index shows it: 3 significant digits."""
    return float("%.3g" % r)


def shown_bound(b, textured):
    """A roughness shown as 0.0982 used as a bound keeps that entry: silk-satin and sandpaper-p400 state
    `roughness very-fine`, 0.09822 (calibration/levels/roughness-levels.toml), shown as 0.0982; the
    library check's `library search --roughness` takes the same bounds (library.roughness_shown_bound)."""
    very_fine = {n for n in ("silk-satin", "sandpaper-p400") if n in textured}
    if not check(len(very_fine) == 2, f"the library has the entries stated very-fine ({sorted(very_fine)})"):
        return
    b.type_into("#rmax", "0.0982")
    got = visible_names(b)
    check(very_fine <= got, f"..0.0982 keeps the entries shown as 0.0982 ({sorted(very_fine)}; got {sorted(got)})")
    b.type_into("#rmin", "0.0982")
    got = visible_names(b)
    check(very_fine <= got and all(shown_roughness(textured[n]) == 0.0982 for n in got),
          f"0.0982..0.0982 keeps exactly the entries shown as 0.0982 ({sorted(got)})")
    b.type_into("#rmin", "0.0983")
    b.evaluate("(() => { const e = document.getElementById('rmax'); e.value = '';"
               " e.dispatchEvent(new Event('input', {bubbles: true})); })()")
    check(not (very_fine & visible_names(b)), "0.0983.. leaves them out")
    b.click("#clear")


def ranking(b, source):
    """The shared table of word searches (tests/curation/data/search_ranking.json): the first three rows
    in the default order are the expected top three, the count line the number of matches when fewer."""
    table = json.loads((source / "tests" / "curation" / "data" / "search_ranking.json").read_text())
    for case in table["queries"]:
        if case["library"] != "world":
            continue  # a layered path: CLI only (library.search_ranking)
        b.type_into("#q", case["q"])
        got = page_names(b)[:3]
        n = b.evaluate("document.querySelectorAll('#entries tbody tr').length")
        check(got == case["top"] and (len(case["top"]) == 3 or n == len(case["top"])),
              f"search {case['q']!r}: first rows {case['top']} (got {got}, {n} rows): {case['why']}")
    b.click("#clear")


def pick_bounds(values):
    """A roughness range that keeps some entries and drops some at both ends, its bounds between values."""
    v = sorted(set(values))
    if len(v) < 3:
        return (v[0] - 0.01, v[-1] + 0.01) if v else (0.0, 1.0)
    lo_i, hi_i = max(1, len(v) // 4), min(len(v) - 2, (3 * len(v)) // 4)
    return round((v[lo_i - 1] + v[lo_i]) / 2, 4), round((v[hi_i] + v[hi_i + 1]) / 2, 4)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--library", required=True, type=pathlib.Path)
    ap.add_argument("--out", required=True, type=pathlib.Path)
    ap.add_argument("--source", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parents[2],
                    help="the repository, for tests/curation/data/search_ranking.json")
    args = ap.parse_args()

    chromium, status = chromium_for_test("the catalog's browser test")
    if status is not None:
        return status

    args.out.mkdir(parents=True, exist_ok=True)
    # A copy of the library in which two entries state other licences than the shipped entries' one
    # (CC0-1.0), so that the licence filter has something to tell apart.
    library = args.out / "library"
    shutil.rmtree(library, ignore_errors=True)
    shutil.copytree(args.library, library, ignore=shutil.ignore_patterns(".index"))
    # The shipped library has no `source measurement` note yet: the tweed gets one, so that the
    # source filter's "measured" keeps one entry rather than none.
    for f, licence, note in (("textiles/tweed.hmat", "CC-BY-4.0", '\n  source measurement "a browser test\'s note"'),
                             ("stones/slate.hmat", "CC-BY-SA-4.0 AND CC0-1.0", "")):
        text = (library / f).read_text()
        if check(re.search(r'^\s*licence\s+"CC0-1.0"', text, re.M) is not None, f"{f} states a licence to change"):
            (library / f).write_text(re.sub(r'^(\s*licence\s+)"CC0-1.0"', lambda m: m.group(1) + f'"{licence}"' + note,
                                            text, count=1, flags=re.M))
    args.library = library
    catalog = args.out / "catalog"
    # Drawn whole: a catalog left by an earlier build would keep pages its record says are current.
    shutil.rmtree(catalog, ignore_errors=True)
    r = subprocess.run([args.sandpaper, "library", "catalog", "-o", str(catalog), "--library", str(args.library),
                        "--quiet"], capture_output=True, text=True)
    if not check(r.returncode == 0, f"sandpaper library catalog exits 0 (got {r.returncode}: {r.stderr.strip()})"):
        return 1
    expected = expected_entries(args.sandpaper, args.library)
    names = set(expected)
    check(len(names) > 0, f"the library lists entries ({len(names)})")

    b = Browser(chromium)
    try:
        index_url = (catalog / "index.html").resolve().as_uri()
        b.navigate(index_url)
        b.wait_for("document.body.dataset.ready === 'true'", "the index's script")
        first = page_names(b)
        check(len(first) == min(100, len(names)), f"the first page shows {min(100, len(names))} rows ({len(first)})")
        shown = visible_names(b)
        check(shown == names, f"index lists every entry: {len(shown)} shown, {len(names)} in the library"
              + ("" if shown == names else f" (missing {sorted(names - shown)}, extra {sorted(shown - names)})"))
        check(b.evaluate("document.getElementById('count').textContent.trim()") == f"{len(names):,} entries",
              "the count line says how many entries")

        # Filter by family: the largest family, chosen from the library's data.
        families = {}
        for n, e in expected.items():
            families.setdefault(e["family"], set()).add(n)
        family = max((f for f in families if f), key=lambda f: (len(families[f]), f), default=None)
        if check(family is not None, f"the library has a family to filter by ({family})"):
            b.evaluate("(() => { const s = document.getElementById('family'); s.value = %s;"
                       " s.dispatchEvent(new Event('change', {bubbles: true})); })()" % json.dumps(family))
            got = visible_names(b)
            check(got == families[family], f"family {family}: shows exactly {sorted(families[family])}, got {sorted(got)}")
            check(f"family={family}" in urllib.parse.unquote(b.evaluate("location.hash")), "the family is kept in the URL hash")
            b.click("#clear")
            check(visible_names(b) == names, "'Show all' clears the filters")

        # Filter by a roughness range typed into the two fields.
        textured = {n: e["roughness"] for n, e in expected.items() if e["roughness"] is not None}
        lo, hi = pick_bounds(list(textured.values()))
        b.type_into("#rmin", str(lo))
        b.type_into("#rmax", str(hi))
        # In when the roughness or the one shown (3 significant digits) is within the bounds.
        want = {n for n, rough in textured.items() if lo <= rough <= hi or lo <= shown_roughness(rough) <= hi}
        got = visible_names(b)
        check(got == want, f"roughness {lo}..{hi}: shows exactly {sorted(want)}, got {sorted(got)}")
        check(0 < len(want) < len(names), f"the range keeps some entries and drops others ({len(want)} of {len(names)})")
        check(b.evaluate("document.getElementById('count').textContent.trim()")
              == f"{len(want):,} of {len(names):,} entries match", "the count line follows the filter")
        h = urllib.parse.parse_qs(b.evaluate("location.hash").lstrip("#"))
        check(h.get("rmin") == [str(lo)] and h.get("rmax") == [str(hi)], f"the range is kept in the URL hash ({h})")
        b.screenshot(str(args.out / "index-filtered.png"))
        b.click("#clear")
        shown_bound(b, textured)
        ranking(b, args.source)
        order_licence_and_sources(b, expected, names)

        # The hash restores the filter on a fresh load (from another page: a hash change alone loads nothing).
        b.navigate("about:blank")
        b.navigate(index_url + "#" + urllib.parse.urlencode({"rmin": lo, "rmax": hi}))
        b.wait_for("document.body.dataset.ready === 'true'", "the index's script after reload")
        check(visible_names(b) == want, "opening index.html#rmin=..&rmax=.. shows the same entries")

        # Follow the link of the first entry shown that has a picture.
        target = b.evaluate("(() => { const tr = Array.from(document.querySelectorAll('#entries tbody tr'))"
                            ".find(tr => !tr.hidden && tr.querySelector('td.thumb img')); return tr && tr.dataset.name; })()")
        if check(target is not None, f"a shown entry has a thumbnail ({target})"):
            b.clear_events()
            b.click(f"#entries tr[data-name=\"{target}\"] td.name a")
            b.wait_event("Page.loadEventFired")
            url = b.evaluate("location.href")
            check(url.endswith(f"/entries/{urllib.parse.quote(target)}.html"), f"the link leads to the entry's page ({url})")
            title = b.evaluate("document.title")
            check(title.startswith(target + " "), f"the page's title names the entry ({title!r})")
            check(b.evaluate("document.querySelector('h1').textContent") == target, "the heading names the entry")
            img = b.evaluate("(() => { const i = document.getElementById('shade');"
                             " return i ? [i.complete, i.naturalWidth, i.naturalHeight] : null; })()")
            check(img is not None and img[0] and img[1] > 0 and img[2] > 0, f"the shaded picture loaded ({img})")
            labels = b.evaluate("Array.from(document.querySelectorAll('svg.force-plot .axis-label')).map(t => t.textContent)")
            check(any("(mm)" in t for t in labels) and any("(N)" in t for t in labels),
                  f"the force plot's axes are labelled in mm and N ({labels})")
            ticks = b.evaluate("[document.querySelectorAll('svg.force-plot .ticks.x text').length,"
                               " document.querySelectorAll('svg.force-plot .ticks.y text').length]")
            check(ticks[0] >= 3 and ticks[1] >= 3, f"both axes have tick labels ({ticks})")
            points = b.evaluate("document.querySelector('svg.force-plot polyline.force-along')"
                                ".getAttribute('points').trim().split(/\\s+/).length")
            check(points > 20, f"the force curve has its samples, simplified within 0.2 px ({points})")
            sections = b.evaluate("['representative', 'perceptual', 'physical', 'provenance']"
                                  ".map(id => !!document.getElementById(id))")
            check(all(sections), "the page has the three layers and the provenance")
            check(b.evaluate("document.querySelectorAll('#provenance table.provenance tbody tr').length") > 0,
                  "the provenance table has rows")
            b.screenshot(str(args.out / "entry.png"))
            b.click("nav a")
            b.wait_event("Page.loadEventFired")
            check(b.evaluate("location.pathname").endswith("/index.html"), "the entry page links back to the index")

        # Compare: two gratings a period doubling apart and a photograph, where the library has them.
        picks = [n for n in ("corduroy", "pinwale-corduroy", "gravel") if n in names]
        if check(len(picks) >= 2, f"the library has entries to compare ({picks})"):
            b.navigate("about:blank")
            b.navigate(index_url)
            b.wait_for("document.body.dataset.ready === 'true'", "the index's script")
            compare(b, expected, picks, args.out)
            b.navigate("about:blank")
            b.navigate((catalog / "entries" / f"{picks[0]}.html").resolve().as_uri())
            similar(b, args.sandpaper, args.library, args.out, picks[0])
    finally:
        b.close()

    print(f"screenshots: {args.out / 'index-filtered.png'}, {args.out / 'entry.png'}, {args.out / 'compare.png'}")
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
