#!/usr/bin/env python3
"""The catalog's index page at 100,000 entries (docs/CATALOG.md, "The index"), in headless Chromium.

catalog_index_page_scale (tests/catalog/index_page_scale.cpp) writes index.html, catalog-data.js, its
parts in catalog-data/ and assets/ for N synthetic entries as `sandpaper library catalog` writes them, without drawing N pictures.
This opens the page from file:// and checks, by reading the DOM, that it shows one page of 100 rows,
counts every entry, turns pages (by mouse, by keyboard, and back through the history), filters by words
and by family and roughness range with exactly the entries expected, and restores all of that from the
URL hash on a fresh load; without JavaScript it says so.

Every expected name and count is computed here from the generator's rules (the comment at the top of
index_page_scale.cpp), not read from what it wrote. The time from navigation to the first rows and the
files' sizes are printed, not checked: they depend on the machine. Screenshot of the first page's top:
<out>/index-100000.png.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1).
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser, chromium_for_test  # noqa: E402

PAGE = 100
# Generous, so that a slow machine fails no check: these are waits for the page, never measurements.
WAIT_S = 120
NOUNS = ["weave", "grit", "grain", "plate", "sheet"]
FAMILIES = [("textiles", "Textiles"), ("stone", "Stone"), ("wood", "Wood"), ("metals", "Metals"),
            ("papers", "Papers"), ("plastics", "Plastics")]
ADJECTIVES = ["soft", "coarse", "ribbed", "woven", "smooth", "gritty", "polished", "brushed", "knitted", "grainy",
              "waxy", "dimpled", "fibrous"]
TEXTURES = ["cotton", "linen", "granite", "slate", "oak", "pine", "steel", "brass", "kraft", "vellum", "nylon", "felt",
            "canvas", "tweed", "leather", "basalt", "maple"]

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def name_of(i):
    return f"{NOUNS[i % 5]}-{i:06d}"


def entry(i):
    """Entry i as index_page_scale.cpp makes it."""
    family = FAMILIES[i % 7] if i % 7 != 6 else ("", "")
    describes = f"{ADJECTIVES[i % 13]} {TEXTURES[(i // 13) % 17]} surface" + (", like a corduroy" if i % 9973 == 17 else "")
    aliases = []
    if i % 50 == 3:
        aliases.append("alt-" + name_of(i))
    if i % 500 == 3:
        aliases.append("second-" + name_of(i))
    if i % 30011 == 29:
        aliases.append(f"corduroy-cloth-{i}")
    return {
        "name": name_of(i),
        "family": family[0],
        "family_title": family[1],
        "roughness": None if i % 11 == 0 else ((i * 7919) % 1200 + 1) / 1000,
        "thumbnail": not (i % 11 == 0 and i % 2 == 1),
        "describes": describes,
        "aliases": aliases,
        "deprecated_by": name_of(i - 1) if i % 97 == 5 else "",
    }


def tokens(text):
    """A text's words as docs/LIBRARY.md ("search") defines them: runs of ASCII letters and digits (and
    of other characters), ASCII lower-cased."""
    return [w for w in re.split(r"[^a-z0-9\u0080-\uffff]+", re.sub(r"[A-Z]", lambda m: m.group(0).lower(), text)) if w]


def matching(entries, family=None, rmin=None, rmax=None, words=""):
    """The names the index should keep, in the order it shows them, by the rules docs/CATALOG.md and
    docs/LIBRARY.md give: every word begins a word of the name (8 points), an alias (4), describes (2)
    or the family's id or title (1); with words, higher scores first, equal ones in the data's order.
    (No query here is an entry's exact name or alias.)"""
    words = tokens(words)
    scored = []
    for e in entries:
        if family is not None and e["family"] != family:
            continue
        if rmin is not None or rmax is not None:
            r = e["roughness"]
            if r is None or not any((rmin is None or v >= rmin) and (rmax is None or v <= rmax)
                                    for v in (r, float("%.3g" % r))):
                continue
        fields = [(8, tokens(e["name"])), (4, tokens(" ".join(e["aliases"]))), (2, tokens(e["describes"])),
                  (1, tokens(e["family"] + " " + e["family_title"]))]
        score = 0
        for w in words:
            best = next((points for points, field in fields if any(t.startswith(w) for t in field)), 0)
            if best == 0:
                break
            score += best
        else:
            scored.append((-score, len(scored), e["name"]))
    return [name for _, _, name in sorted(scored)]


def rows(b):
    return b.evaluate("Array.from(document.querySelectorAll('#entries tbody tr')).map(tr => tr.dataset.name)")


def text(b, selector):
    return b.evaluate("document.querySelector(%s).textContent.trim()" % json.dumps(selector))


def page_of(page, pages, shown):
    first, last = (page - 1) * PAGE + 1, min(page * PAGE, shown)
    return f"page {page:,} of {pages:,} ({first:,}\u2013{last:,})"


def press_enter(b):
    for kind in ("keyDown", "keyUp"):
        b.send("Input.dispatchKeyEvent", {"type": kind, "key": "Enter", "code": "Enter", "windowsVirtualKeyCode": 13,
                                          **({"text": "\r"} if kind == "keyDown" else {})})


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--generator", required=True, help="catalog_index_page_scale")
    ap.add_argument("--entries", type=int, default=100000)
    ap.add_argument("--out", required=True, type=pathlib.Path)
    args = ap.parse_args()
    n = args.entries

    chromium, status = chromium_for_test("the catalog index's scale test")
    if status is not None:
        return status

    args.out.mkdir(parents=True, exist_ok=True)
    site = args.out / "site"
    r = subprocess.run([args.generator, str(n), str(site)], capture_output=True, text=True)
    if not check(r.returncode == 0, f"catalog_index_page_scale {n} exits 0 (got {r.returncode}: {r.stderr.strip()})"):
        return 1
    entries = [entry(i) for i in range(n)]
    names = [e["name"] for e in entries]
    pages = math.ceil(n / PAGE)

    b = Browser(chromium, timeout=WAIT_S)
    try:
        index_url = (site / "index.html").resolve().as_uri()
        started = time.monotonic()
        b.navigate(index_url)
        b.wait_for("document.body.dataset.ready === 'true'", "the index's script", deadline_s=WAIT_S)
        wall = time.monotonic() - started
        timing = b.evaluate("(() => { const m = performance.getEntriesByName('catalog-first-rows')[0];"
                            " const p = performance.getEntriesByName('first-contentful-paint')[0];"
                            " const nav = performance.getEntriesByType('navigation')[0];"
                            " return {rows: m ? m.startTime : null, paint: p ? p.startTime : null,"
                            " load: nav ? nav.loadEventEnd : null}; })()")

        shown = rows(b)
        check(len(shown) == min(PAGE, n), f"the first page has {min(PAGE, n)} rows ({len(shown)})")
        check(shown == names[:PAGE], "they are the first entries, in order")
        check(text(b, "#count") == f"{n:,} entries", f"the count line says {n:,} entries ({text(b, '#count')!r})")
        check(text(b, "#pager-top .page-of") == page_of(1, pages, n),
              f"the pager says {page_of(1, pages, n)!r} ({text(b, '#pager-top .page-of')!r})")
        check(b.evaluate("document.querySelector('#pager-top .prev').disabled"), "'previous' is disabled on page 1")

        # What a row shows, for entries on the first page whose fields are known.
        by_name = {e["name"]: e for e in entries[:PAGE]}
        cells = b.evaluate("Array.from(document.querySelectorAll('#entries tbody tr')).map(tr => ({"
                           "name: tr.dataset.name, deprecated: tr.classList.contains('deprecated'),"
                           "thumb: !!tr.querySelector('td.thumb img'), noThumb: !!tr.querySelector('td.thumb .no-thumb'),"
                           "aliases: (tr.querySelector('.aliases') || {}).textContent || '',"
                           "tag: (tr.querySelector('.deprecated-tag') || {}).textContent || '',"
                           "family: tr.querySelector('td.family').textContent, rough: tr.querySelector('td.num').textContent,"
                           "describes: tr.lastElementChild.textContent, href: tr.querySelector('td.name a').getAttribute('href')}))")
        wrong = []
        for c in cells:
            e = by_name.get(c["name"])
            want = e and {"deprecated": bool(e["deprecated_by"]), "thumb": e["thumbnail"], "noThumb": not e["thumbnail"],
                          "aliases": ", ".join(e["aliases"]),
                          "tag": f"deprecated: use {e['deprecated_by']}" if e["deprecated_by"] else "",
                          "family": e["family_title"] or "\u2014",
                          "rough": "\u2014" if e["roughness"] is None else f"{e['roughness']:.3g}",
                          "describes": e["describes"], "href": f"entries/{e['name']}.html"}
            got = {k: v for k, v in c.items() if k != "name"}
            if got != want:
                wrong.append((c["name"], got, want))
        check(not wrong, "each row shows its entry's thumbnail, aliases, deprecation, family, roughness and words"
              + (f": {wrong[:3]}" if wrong else ""))
        b.wait_for("(() => { const i = document.querySelector('#entries tbody tr td.thumb img');"
                   " return i && i.complete && i.naturalWidth > 0; })()", "the first row's thumbnail",
                   deadline_s=WAIT_S)
        # The window's worth: only the first 200 entries have thumbnail files, and lazy images below it
        # would be drawn as not yet loaded.
        b.screenshot(str(args.out / "index-100000.png"), full_page=False)

        # Page 2 by mouse, back to 1 through the history, page 2 again by keyboard.
        b.click("#pager-top .next")
        b.wait_for("document.body.dataset.page === '2'", "page 2", deadline_s=WAIT_S)
        check(rows(b) == names[PAGE:2 * PAGE], "page 2 shows entries 101-200")
        check(text(b, "#pager-top .page-of") == page_of(2, pages, n), f"the pager says {page_of(2, pages, n)!r}")
        check(urllib.parse.parse_qs(b.evaluate("location.hash").lstrip("#")).get("page") == ["2"],
              "the page is kept in the URL hash")
        b.evaluate("history.back()")
        b.wait_for("document.body.dataset.page === '1'", "page 1 after Back", deadline_s=WAIT_S)
        check(rows(b) == names[:PAGE], "Back returns to page 1")
        b.evaluate("document.querySelector('#pager-bottom .next').focus()")
        press_enter(b)
        b.wait_for("document.body.dataset.page === '2'", "page 2 by keyboard", deadline_s=WAIT_S)
        check(rows(b) == names[PAGE:2 * PAGE], "Enter on the focused 'next' button turns the page")

        # Words: every word begins a word of the name, an alias, describes or the family; ranked.
        for words in ("corduroy", "Ribbed OAK"):
            want = matching(entries, words=words)
            b.type_into("#q", words)
            b.wait_for(f"document.body.dataset.shown === '{len(want)}'", f"the filter {words!r}", deadline_s=WAIT_S)
            check(b.evaluate("document.body.dataset.page") == "1", f"{words!r}: a new filter starts at page 1")
            check(rows(b) == want[:PAGE], f"{words!r}: the first page shows exactly the {min(len(want), PAGE)} first of "
                  f"{len(want)} expected" + ("" if rows(b) == want[:PAGE] else f" (got {rows(b)[:5]}...)"))
            check(text(b, "#count") == f"{len(want):,} of {n:,} entries match", f"{words!r}: {text(b, '#count')!r}")
        check(0 < len(matching(entries, words="corduroy")) < PAGE, "the word filter finds a few entries among many")
        b.click("#clear")
        b.wait_for(f"document.body.dataset.shown === '{n}'", "'Show all'", deadline_s=WAIT_S)
        check(b.evaluate("location.hash") == "", "'Show all' empties the hash")

        # Family and roughness range.
        family, lo, hi = "stone", "0.3", "0.6"
        want = matching(entries, family=family, rmin=float(lo), rmax=float(hi))
        b.evaluate("(() => { const s = document.getElementById('family'); s.value = %s;"
                   " s.dispatchEvent(new Event('change', {bubbles: true})); })()" % json.dumps(family))
        b.type_into("#rmin", lo)
        b.type_into("#rmax", hi)
        b.wait_for(f"document.body.dataset.shown === '{len(want)}'", "the family and range filter", deadline_s=WAIT_S)
        check(text(b, "#count") == f"{len(want):,} of {n:,} entries match",
              f"family {family}, roughness {lo}..{hi}: {len(want):,} entries ({text(b, '#count')!r})")
        check(rows(b) == want[:PAGE], "and the first page shows the first 100 of them")
        want_pages = math.ceil(len(want) / PAGE)
        check(want_pages >= 3, f"over several pages ({want_pages})")
        b.click("#pager-top .next")
        b.click("#pager-top .next")
        b.wait_for("document.body.dataset.page === '3'", "page 3 of the filtered entries", deadline_s=WAIT_S)
        check(rows(b) == want[2 * PAGE:3 * PAGE], "page 3 of the filtered entries shows the 201st to 300th")
        h = urllib.parse.parse_qs(b.evaluate("location.hash").lstrip("#"))
        check(h == {"family": [family], "rmin": [lo], "rmax": [hi], "page": ["3"]}, f"the URL hash holds all of it ({h})")

        # A fresh load restores the filters and the page from the hash.
        hash_ = urllib.parse.urlencode({"family": family, "rmin": lo, "rmax": hi, "page": 3})
        b.navigate("about:blank")
        b.navigate(index_url + "#" + hash_)
        b.wait_for("document.body.dataset.ready === 'true'", "the index's script after reload", deadline_s=WAIT_S)
        fields = b.evaluate("['family', 'rmin', 'rmax', 'q'].map(id => document.getElementById(id).value)")
        check(fields == [family, lo, hi, ""], f"the fields are restored from the hash ({fields})")
        check(b.evaluate("document.body.dataset.page") == "3" and rows(b) == want[2 * PAGE:3 * PAGE],
              "and so is the page, with the same rows")
        check(text(b, "#pager-top .page-of") == page_of(3, want_pages, len(want)),
              f"the pager says {page_of(3, want_pages, len(want))!r}")

        # Measured, not checked: the first word search also builds the text it searches.
        filter_ms = b.evaluate("(() => { ['family', 'rmin', 'rmax'].forEach(id => document.getElementById(id).value = '');"
                               " const q = document.getElementById('q'); const t = performance.now();"
                               " q.value = 'corduroy'; q.dispatchEvent(new Event('input')); return performance.now() - t; })()")

        # Without JavaScript the page says what it needs and where the entries' pages are, and shows no
        # empty table or filters that do nothing.
        b.send("Emulation.setScriptExecutionDisabled", {"value": True})
        b.navigate("about:blank")
        b.navigate(index_url)
        seen = b.evaluate("['p.noscript', '#filters', '#entries'].map(s => document.querySelector(s).offsetParent !== null)")
        check(seen == [True, False, False], f"without JavaScript: the note, no filters, no table ({seen})")
        check("entries/<name>.html" in text(b, "p.noscript"), "the note says where the entry pages are")
    finally:
        b.close()

    size = {f: (site / f).stat().st_size for f in ("index.html", "catalog-data.js")}
    parts = sorted((site / "catalog-data").glob("part-*.js"))
    print(f"{n:,} entries: index.html {size['index.html']:,} bytes, catalog-data.js {size['catalog-data.js']:,} bytes, "
          f"{len(parts)} parts in catalog-data/ of {sum(p.stat().st_size for p in parts):,} bytes in all "
          f"(the largest {max((p.stat().st_size for p in parts), default=0):,})")
    print(f"navigation to the first rows: {timing['rows']:.0f} ms (first contentful paint {timing['paint'] or 0:.0f} ms, "
          f"load event {timing['load'] or 0:.0f} ms; {wall * 1000:.0f} ms from Page.navigate to ready, as the test saw it)")
    print(f"a word filter over every entry, the first: {filter_ms:.0f} ms")
    print(f"screenshot: {args.out / 'index-100000.png'}")
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
