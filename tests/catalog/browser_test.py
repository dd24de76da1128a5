#!/usr/bin/env python3
"""Browser test of `sandpaper library catalog` (docs/CATALOG.md): writes the catalog of the shipped
library, opens index.html from file:// in headless Chromium, reads every entry page by page, filters by
family and by a roughness range and checks exactly which entries remain, follows a link to an entry
page and checks what it shows. (index_scale_browser_test.py tries the index with 100,000 entries.)

The expected entries come from the library itself, not from the catalog: roughness from
`sandpaper library --json` (which compiles each entry on its own), families from the entries' files.
Screenshots: <out>/index-filtered.png, <out>/entry.png.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1).
"""
import argparse
import json
import os
import pathlib
import re
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
    # `family WORD` as written in each entry's own file (the statement is not inherited through `like`).
    for f in library.rglob("*.hmat"):
        if f.stem in entries and entries[f.stem]["family"] is None:
            m = re.search(r"^\s*family\s+([A-Za-z0-9_.-]+)", f.read_text(), re.M)
            entries[f.stem]["family"] = m.group(1) if m else ""
    return entries


def page_names(b):
    return b.evaluate("Array.from(document.querySelectorAll('#entries tbody tr'))"
                      ".filter(tr => !tr.hidden && tr.offsetParent !== null).map(tr => tr.dataset.name)")


def visible_names(b):
    """Every entry the filters keep. The index makes only the rows of the page shown (100 a page), so
    this turns the pages with the pager's 'next' button and reads each."""
    names = []
    while True:
        names += page_names(b)
        page, pages = b.evaluate("[Number(document.body.dataset.page), Number(document.body.dataset.pages)]")
        if page >= pages:
            break
        b.click("#pager-bottom .next")
        b.wait_for(f"document.body.dataset.page === '{page + 1}'", f"page {page + 1}")
    if len(names) != len(set(names)):
        check(False, f"no entry is on two pages ({len(names)} rows, {len(set(names))} names)")
    return set(names)


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
    args = ap.parse_args()

    chromium, status = chromium_for_test("the catalog's browser test")
    if status is not None:
        return status

    args.out.mkdir(parents=True, exist_ok=True)
    catalog = args.out / "catalog"
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
        want = {n for n, rough in textured.items() if lo <= rough <= hi}
        got = visible_names(b)
        check(got == want, f"roughness {lo}..{hi}: shows exactly {sorted(want)}, got {sorted(got)}")
        check(0 < len(want) < len(names), f"the range keeps some entries and drops others ({len(want)} of {len(names)})")
        check(b.evaluate("document.getElementById('count').textContent.trim()")
              == f"{len(want):,} of {len(names):,} entries match", "the count line follows the filter")
        h = urllib.parse.parse_qs(b.evaluate("location.hash").lstrip("#"))
        check(h.get("rmin") == [str(lo)] and h.get("rmax") == [str(hi)], f"the range is kept in the URL hash ({h})")
        b.screenshot(str(args.out / "index-filtered.png"))

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
    finally:
        b.close()

    print(f"screenshots: {args.out / 'index-filtered.png'}, {args.out / 'entry.png'}")
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
