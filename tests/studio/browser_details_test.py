#!/usr/bin/env python3
"""Smaller things of the studio's page, in headless Chromium against a running `sandpaper studio`
(docs/STUDIO.md), each against a figure from outside the page:

- the header's status line is read whole at 1280 px (F12's long message fits its line);
- hovering a `like` name shows the library entry as prose, not Markdown's asterisks and backticks;
- the status line about a file's unsaved edits does not follow the user to another file;
- a workspace's compile line names it, its patches and size (from the .hws file itself);
- a 60 x 39.8 mm photograph previewed in part says so, with the patch's size;
- unit completion after a length (`size 40`, a length by schema/LANGUAGE.md) offers lengths, not N or N/m;
- /favicon.ico is an icon, not a 404.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1)."""
import argparse
import base64
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "support"))
sys.path.insert(0, os.path.join(here, "..", "catalog"))
from cdp import Browser, chromium_for_test  # noqa: E402
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402
from editor_keys import new_line  # noqa: E402

checks = Checklist()
check = checks.check

# schema/LANGUAGE.md, "Units": the length units, and two that are not lengths.
LENGTHS = {"mm", "m", "cm", "um", "in"}
NOT_LENGTHS = {"N", "N/m", "gf", "%"}


def key(b, name, code):
    for kind in ("rawKeyDown", "keyUp"):
        b.send("Input.dispatchKeyEvent", {"type": kind, "key": name, "code": name, "windowsVirtualKeyCode": code})


def mouse(b, kind, x, y, buttons=1):
    b.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left", "buttons": buttons,
                                        "clickCount": 1})


def text_xy(b, needle, offset):
    return b.evaluate("""(() => { const v = window.studio.editor; const i = v.state.doc.toString().indexOf(%s);
        if (i < 0) return null; const c = v.coordsAtPos(i + %d); return [c.left, (c.top + c.bottom) / 2]; })()"""
                      % (json.dumps(needle), offset))


def click_at_text(b, needle, after=True):
    xy = text_xy(b, needle, len(needle) if after else 0)
    mouse(b, "mousePressed", xy[0] + 0.5, xy[1])
    mouse(b, "mouseReleased", xy[0] + 0.5, xy[1], 0)


def wait(b, expression, what, seconds=20):
    try:
        b.wait_for(expression, what, seconds)
        return True
    except Exception:
        return False


def switch_to(b, name):
    b.evaluate("(() => { const s = document.querySelector('#file'); s.value = %s;"
               " s.dispatchEvent(new Event('change')); })()" % json.dumps(name))
    return wait(b, "window.studio.state.file === %s && document.body.dataset.compiles === 'yes'" % json.dumps(name),
                "opening " + name)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    chromium, status = chromium_for_test("the studio's details test")
    if status is not None:
        return status
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    examples = pathlib.Path(args.examples).resolve()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-details-"))
    folder = tmp / "examples"
    shutil.copytree(examples, folder)
    (tmp / "library").symlink_to(examples.parent / "library")
    # A photograph that is not square: the library's gravel cut to 512 x 340 px, at `size 60 mm`.
    subprocess.run(["oiiotool", str(examples.parent / "library" / "images" / "gravel.png"), "--cut", "512x340+0+80",
                    "-o", str(folder / "board.png")], check=True)
    (folder / "board.hmat").write_text('material "board" {\n  heightmap "board.png" size 60 mm smoothing 0.2 mm\n'
                                       '  roughness 0.5\n}\n')
    ws_text = (folder / "workspace" / "sampler.hws").read_text()
    ws_name = re.search(r'^workspace "([^"]+)"', ws_text, re.M).group(1)
    ws_patches = len(re.findall(r"^\s*patch\s", ws_text, re.M))

    studio = Studio(os.path.abspath(args.sandpaper), folder / "corduroy.hmat")
    b = Browser(chromium, width=1280, height=900)
    try:
        # /favicon.ico: what every browser asks for on its own.
        status, body = studio.get("/favicon.ico")
        check(status == 200 and isinstance(body, bytes) and b"<svg" in body, f"GET /favicon.ico answers an icon (HTTP {status})")

        b.navigate(studio.url)
        check(wait(b, "document.body.dataset.ready === 'yes'", "the page", 30), "the page loads")
        icon = b.evaluate("""(async () => { const r = await fetch('/favicon.ico'); const img = new Image();
            img.src = document.querySelector('link[rel=icon]')?.href || '/favicon.ico';
            try { await img.decode(); } catch (e) {} return [r.status, r.headers.get('content-type'), img.naturalWidth]; })()""")
        check(icon[0] == 200 and icon[1].startswith("image/") and icon[2] > 0,
              f"in Chromium the icon loads and decodes as a picture: {icon}")

        # The header at 1280 px: F12 on a `like` name says where the entry is defined, a long line.
        check(wait(b, "document.body.dataset.compiles === 'yes'", "the compile"), "(corduroy compiles)")
        header_h = b.evaluate("document.querySelector('header').getBoundingClientRect().height")
        click_at_text(b, "like cor")
        key(b, "F12", 123)
        check(wait(b, "(document.body.dataset.definition || '').endsWith('corduroy.hmat')", "F12"), "(F12 answered)")
        shown = b.evaluate("""(() => { const s = document.querySelector('#status'); const r = s.getBoundingClientRect();
            return [s.textContent, s.scrollWidth, s.clientWidth, r.right, window.innerWidth]; })()""")
        check(shown[0].startswith("defined in ") and shown[1] <= shown[2] and shown[3] <= shown[4],
              f"at 1280 px the status line is shown whole ({shown[1]} px of text in {shown[2]} px): {shown[0]!r}")
        cut = b.evaluate("""[...document.querySelectorAll('header > *')].filter(e => e.scrollWidth > e.clientWidth + 1
            || e.getBoundingClientRect().right > window.innerWidth).map(e => e.id || e.tagName)""")
        check(cut == [], f"nothing else in the header is cut or off the window: {cut}")
        check(abs(b.evaluate("document.querySelector('header').getBoundingClientRect().height") - header_h) < 1,
              "and the header kept its height (the page does not move under the hand)")

        # Hover on a `like` name: the entry as prose.
        key(b, "Escape", 27)
        xy = text_xy(b, "like corduroy", len("like cor"))
        mouse(b, "mouseMoved", xy[0] - 2, xy[1], 0)
        mouse(b, "mouseMoved", xy[0], xy[1], 0)
        hovered = wait(b, "(document.querySelector('.cm-tooltip-hover')?.textContent || '').includes('library entry')", "the hover")
        tip = b.evaluate("""(() => { const t = document.querySelector('.cm-tooltip-hover'); if (!t) return null;
            return [t.textContent, [...t.querySelectorAll('strong')].map(e => e.textContent),
                    [...t.querySelectorAll('code')].map(e => e.textContent)]; })()""")
        check(hovered and tip is not None and "**" not in tip[0] and "`" not in tip[0] and "corduroy" in tip[1]
              and any(c.endswith("corduroy.hmat") for c in tip[2]),
              f"hovering `corduroy` shows its entry as prose, the name bold and the file as code: {tip}")
        mouse(b, "mouseMoved", 5, 880, 0)

        # The unsaved-edits line stays with its file.
        click_at_text(b, "#")
        b.send("Input.insertText", {"text": "unsaved "})
        check(wait(b, "document.querySelector('#saved').textContent === 'unsaved'", "the edit"), "an edit, not saved")
        check(switch_to(b, "gravel.hmat"), "another file opens")
        check(switch_to(b, "corduroy.hmat") and "unsaved edits" in b.evaluate("document.querySelector('#status').textContent"),
              "back at the edited file, the status says its unsaved edits were kept")
        check(switch_to(b, "gravel.hmat"), "and to the other file again")
        line = b.evaluate("document.querySelector('#status').textContent")
        check("unsaved" not in line and "corduroy" not in line,
              f"the other file's status line says nothing of the first file's edits: {line!r}")
        check(b.evaluate("document.querySelector('#saved').textContent") == "saved", "and it is itself saved")

        # A workspace's compile line.
        check(switch_to(b, "workspace/sampler.hws"), "a workspace opens")
        compiled = b.evaluate("document.querySelector('#compile-state').textContent")
        check(ws_name in compiled and f"{ws_patches} patches" in compiled and "228.6" in compiled,
              f"its compile line names the workspace {ws_name!r}, its {ws_patches} patches and size: {compiled!r}")

        # The photograph's preview window is part of the patch, and says so.
        # A preview asked for before the studio has drawn it is answered 503 (on a loaded machine a
        # photograph takes longer than the studio waits); the page must ask again, not keep the last
        # file's picture. Chromium's own request interception answers the first ask 503.
        b.send("Fetch.enable", {"patterns": [{"urlPattern": "*/api/preview/preview.json*"}]})
        b.evaluate("(() => { const s = document.querySelector('#file'); s.value = 'board.hmat';"
                   " s.dispatchEvent(new Event('change')); })()")
        # The page refreshes one preview at a time (preview.js): it asks for the photograph's only
        # once the workspace's pictures, asked for just before, are drawn. Beside stress-ng that took
        # longer than 60 s, so the wait is long: it waits for the event, not for a pace.
        first = b.wait_event("Fetch.requestPaused", 240)["params"]
        b.send("Fetch.fulfillRequest", {"requestId": first["requestId"], "responseCode": 503,
                                        "responseHeaders": [{"name": "Content-Type", "value": "application/json"}],
                                        "body": base64.b64encode(b'{"error": "still being drawn"}').decode()})
        try:
            again = b.wait_event("Fetch.requestPaused", 120)["params"]
            b.send("Fetch.continueRequest", {"requestId": again["requestId"]})
        except Exception:
            again = {"request": {"url": "(nothing within 120 s)"}}
        b.send("Fetch.disable")
        check(again["request"]["url"] == first["request"]["url"],
              f"answered 503, the page asks again for the same load's preview: {first['request']['url']} then "
              f"{again['request']['url']}")
        check(switch_to(b, "board.hmat"), "a photograph opens")
        caption = "document.querySelector('#picture-caption').textContent"
        height = 60 * 340 / 512  # mm: the picture's shape kept (schema/LANGUAGE.md, `heightmap ... size W`)
        # The caption is drawn once the picture decodes, after the preview's state is set: wait for the
        # photo's own caption. (Beside stress-ng an older preview, decoded last, once left its
        # '60.0 × 60.0 mm' caption here; preview.js now lets only the latest write it.)
        check(wait(b, caption + ".includes('scale bar') && Math.abs(window.studio.state.preview?.window_mm[1] - %f) < 0.05"
                   " && %s.includes(%s)" % (height, caption, json.dumps(f"of the 60.0 × {height:.1f} mm patch")),
                   "its caption"), "(its picture)")
        window_mm = b.evaluate("window.studio.state.preview.window_mm")
        text = b.evaluate(caption)
        check(window_mm[0] < 59 and f"of the 60.0 × {height:.1f} mm patch" in text and "whole patch" in text,
              f"the {window_mm[0]:.1f} × {window_mm[1]:.1f} mm preview says it is part of the 60 × {height:.1f} mm patch: {text!r}")
        b.screenshot(str(out / "studio-details-photo.png"), full_page=False)

        # Units after a length.
        check(switch_to(b, "corduroy.hmat"), "(corduroy again)")
        click_at_text(b, "hill 50%")
        key(b, "End", 35)
        typed, moved = new_line(b, "size 40 ")
        check(typed is not None and typed[2] == "  size 40 ", f"Enter and `size 40 ` open an indented line: {typed}"
              + (" (the caret stayed before the typed words; End put it after them)" if moved else ""))
        # The list is read in the same evaluation that finds it open: a compile's answer can close a list
        # that typing opened, between one look and the next. Closed with no question to the language
        # server in flight, it is asked for again with Ctrl-Space, as a user would; never while one is
        # on its way, which asking again would cancel (on a loaded machine the studio compiles the typed
        # text first, and an answer takes seconds). Up to 120 s in all.
        labels = """(() => { const li = [...document.querySelectorAll('.cm-tooltip-autocomplete li .cm-completionLabel')];
            return li.length ? li.map(e => e.textContent) : null; })()"""
        settled = ("document.querySelectorAll('.cm-tooltip-autocomplete li .cm-completionLabel').length > 0"
                   " || window.studio.state.languageAsked === 0")
        offered, asked = None, 0
        deadline = time.monotonic() + 120
        while offered is None and time.monotonic() < deadline:
            try:
                b.wait_for(settled, "the completion list, or no question in flight", max(1, deadline - time.monotonic()))
            except Exception:
                break
            offered = b.evaluate(labels)
            if offered is None and b.evaluate("window.studio.state.languageAsked") == 0:
                asked += 1
                for kind in ("rawKeyDown", "keyUp"):
                    b.send("Input.dispatchKeyEvent", {"type": kind, "key": " ", "code": "Space", "modifiers": 2,
                                                      "windowsVirtualKeyCode": 32})
                try:  # the question Ctrl-Space sent, on its way or already answered
                    b.wait_for("window.studio.state.languageAsked > 0 || document.querySelectorAll("
                               "'.cm-tooltip-autocomplete li .cm-completionLabel').length > 0", "the question", 5)
                except Exception:
                    pass
        shown = offered is not None
        offered = offered or []
        check(shown and LENGTHS <= set(offered) and not (NOT_LENGTHS & set(offered)),
              f"after `size 40` the units offered are lengths only: {offered} (asked again {asked} times)")
        key(b, "Escape", 27)
    finally:
        b.close()
        code, _, _ = studio.stop()
    check(code == 0, f"the studio stops on Ctrl-C (exit {code})")
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
