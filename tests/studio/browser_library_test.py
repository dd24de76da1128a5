#!/usr/bin/env python3
"""The studio's page in headless Chromium, on what comes from the library (docs/STUDIO.md, "The page"):

- A diagnostic from a library entry's file is shown with that file's name and place, marked on the
  open text's line that brought the entry in (the `like` of a three-line material; the `patch` of a
  workspace), and clicking it opens the entry's file at that line, without an exception in the page.
  Expected places are read off the files themselves: silk-satin's grating is on line 8, column 3 of
  library/textiles/silk-satin.hmat, the material's `like` on its line 2, the sampler's silk-satin patch
  on line 10 of examples/workspace/sampler.hws.
- "insert like NAME" puts the line inside the `material { }` block when the cursor is on the comment
  line above it, replaces a `like` that is there (one entry to start from), and in a workspace says
  why not and changes nothing.
- A studio stopped with those edits unsaved keeps them; started again on plain.hmat, the page holds
  the kept text, says where it came from, and Ctrl-Z goes back to the file's text.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1).
Prints 'N passed, N failed'."""
import argparse
import json
import os
import pathlib
import shutil
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "support"))
sys.path.insert(0, os.path.join(here, "..", "catalog"))
from cdp import Browser, chromium_for_test  # noqa: E402
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check


def wait(b, expression, what, seconds=15):
    try:
        b.wait_for(expression, what, seconds)
        return True
    except Exception:
        return False


def open_file(b, name):
    b.evaluate("(() => { const s = document.querySelector('#file'); s.value = %s; s.dispatchEvent(new Event('change')); })()"
               % json.dumps(name))
    return wait(b, "window.studio.state.file === %s && document.body.dataset.compiles !== undefined"
                   " && window.studio.text().length > 0" % json.dumps(name), "opening " + name)


def marks(b):
    """Each squiggle in the editor: [line number, its text]."""
    return b.evaluate("""[...document.querySelectorAll('.cm-lintRange')].map(e => {
        const v = window.studio.editor; const p = v.posAtDOM(e, 0);
        return [v.state.doc.lineAt(p).number, e.textContent]; })""")


def entry_diagnostic(b, entry_file):
    """The listed diagnostic from `entry_file`: [its place as shown, code], or None."""
    return b.evaluate("""(() => { const li = [...document.querySelectorAll('#diagnostics li')]
        .find(l => (l.dataset.file || '').endsWith(%s)); return li ? [li.querySelector('b').textContent, li.dataset.code] : null; })()"""
                      % json.dumps(entry_file))


def cursor_on_line(b, n):
    b.evaluate("(() => { const v = window.studio.editor; v.dispatch({ selection: { anchor: v.state.doc.line(%d).from } }); v.focus(); })()" % n)


def choose_entry(b, name):
    b.type_into("#library-search", name)
    ok = wait(b, "document.querySelector('#library-results li[data-name=%s]') !== null" % json.dumps(name), "the search")
    if ok:
        b.click("#library-results li[data-name=%s]" % json.dumps(name))
        ok = wait(b, "document.querySelector('#library-entry').dataset.name === %s" % json.dumps(name), "the entry")
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    args = ap.parse_args()
    chromium, status = chromium_for_test("the studio's library browser test")
    if status is not None:
        return status
    examples = pathlib.Path(args.examples).resolve()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-library-"))
    folder = tmp / "swatches"
    folder.mkdir()
    (folder / "satin.hmat").write_text('material "satin-swatch" {\n  like silk-satin\n}\n')
    plain = '# a plain swatch\nmaterial "plain" {\n  roughness 0.4\n}\n'
    (folder / "plain.hmat").write_text(plain)
    shutil.copy(examples / "workspace" / "sampler.hws", folder / "sampler.hws")

    studio = Studio(os.path.abspath(args.sandpaper), folder / "satin.hmat")
    b = Browser(chromium, width=1400, height=1150)
    try:
        b.navigate(studio.url)
        check(wait(b, "document.body.dataset.ready === 'yes'", "the page to load", 30), "the page loads")
        b.evaluate("window.pageErrors = []; window.addEventListener('error', e => window.pageErrors.push(String(e.message)));"
                   " window.addEventListener('unhandledrejection', e => window.pageErrors.push(String(e.reason)));"
                   " const logged = console.error; console.error = (...a) => { window.pageErrors.push(a.map(String).join(' ')); logged(...a); }")

        # 1. The three-line material: silk-satin's W0350 is the entry's, found at its grating.
        listed = wait(b, "document.querySelector('#diagnostics li[data-code=\"W0350\"]') !== null", "W0350 listed") and \
            entry_diagnostic(b, "silk-satin.hmat")
        check(bool(listed) and listed[0].endswith("textiles/silk-satin.hmat:8:3") and listed[1] == "W0350",
              f"W0350 is listed with the entry's file and place: {listed}")
        wait(b, "document.querySelector('.cm-lintRange') !== null", "a squiggle")
        m = marks(b)
        check([2, "silk-satin"] in m, f"it is marked on the `like silk-satin` line (2): {m}")
        if b.evaluate("document.querySelector('#diagnostics li[data-code=\"W0350\"]') !== null"):
            b.click("#diagnostics li[data-code='W0350']")
        shown = wait(b, "!document.querySelector('#library-text').hidden && document.querySelector('#library-text mark') !== null",
                     "the entry's file")
        check(shown and b.evaluate("document.querySelector('#library-entry').dataset.name") == "silk-satin",
              "clicking it opens silk-satin's file in the library browser")
        check(shown and b.evaluate("document.querySelector('#library-text mark').textContent").strip()
              == "grating period 0.7 mm hill 50%", "at the grating's line")
        check(b.evaluate("window.studio.editor.state.doc.lineAt(window.studio.editor.state.selection.main.head).number") == 2,
              "and the editor's cursor goes to the `like` line")
        errors = b.evaluate("window.pageErrors")
        check(errors == [], f"with no exception in the page: {errors}")

        # 2. Insert like: a `like` there is replaced, not doubled.
        check(choose_entry(b, "corduroy"), "corduroy chosen in the library browser")
        cursor_on_line(b, 1)
        b.click("#library-insert")
        want = 'material "satin-swatch" {\n  like corduroy\n}\n'
        check(wait(b, "window.studio.text() === %s" % json.dumps(want), "the replaced like"),
              f"`insert like corduroy` replaces `like silk-satin`: {b.evaluate('window.studio.text()')!r}")
        check("silk-satin" in b.evaluate("document.querySelector('#status').textContent"), "and says which it replaced")

        # 3. Insert like into a material without one, the cursor on the comment line above the block.
        check(open_file(b, "plain.hmat"), "plain.hmat opens")
        cursor_on_line(b, 1)
        b.click("#library-insert")
        want = '# a plain swatch\nmaterial "plain" {\n  like corduroy\n  roughness 0.4\n}\n'
        inserted_ok = wait(b, "window.studio.text() === %s" % json.dumps(want), "the inserted like")
        status_now = b.evaluate("document.querySelector('#status').textContent")
        check(inserted_ok, f"`insert like corduroy` goes inside the block: {b.evaluate('window.studio.text()')!r}"
                           f" (status line: {status_now!r})")
        check(wait(b, "document.body.dataset.compiles === 'yes' && window.studio.state.file === 'plain.hmat'", "the compile"),
              "and the text compiles")

        # 4. The workspace: silk-satin's W0350 marked on its patch, not on line 8 (a comment).
        check(open_file(b, "sampler.hws"), "sampler.hws opens")
        listed = wait(b, "[...document.querySelectorAll('#diagnostics li')].some(l => (l.dataset.file || '').endsWith('silk-satin.hmat'))",
                      "silk-satin's diagnostic") and entry_diagnostic(b, "silk-satin.hmat")
        check(bool(listed) and listed[0].endswith("textiles/silk-satin.hmat:8:3"), f"the workspace lists it with its file: {listed}")
        wait(b, "document.querySelector('.cm-lintRange') !== null", "a squiggle")
        m = marks(b)
        check([10, '"silk-satin"'] in m, f"marked on the silk-satin patch (line 10): {m}")
        check(not any(line == 8 for line, _ in m), f"nothing marked on line 8, a comment: {m}")
        before = b.evaluate("window.studio.text()")
        b.click("#library-insert")
        check(wait(b, "document.querySelector('#status').classList.contains('bad')", "the refusal")
              and "workspace" in b.evaluate("document.querySelector('#status').textContent")
              and b.evaluate("window.studio.text()") == before,
              "in a workspace, insert like says why not and changes nothing")
        errors = b.evaluate("window.pageErrors")
        check(errors == [], f"no exception in the page: {errors}")
    finally:
        b.close()  # (a page with unsaved edits asks before it is left: a new browser for the next start)
        code, printed, err = studio.stop()
    check(code == 0, f"the studio stops on Ctrl-C (exit {code})")
    check(".plain.hmat.recovered" in err, f"keeping plain.hmat's unsaved edits: {err!r}")

    # 5. The next start offers the kept text; Ctrl-Z goes back to the file's.
    again = Studio(os.path.abspath(args.sandpaper), folder / "plain.hmat")
    b = Browser(chromium, width=1400, height=1150)
    try:
        b.navigate(again.url)
        check(wait(b, "document.body.dataset.ready === 'yes'", "the page to load", 30), "started again, the page loads")
        inserted = '# a plain swatch\nmaterial "plain" {\n  like corduroy\n  roughness 0.4\n}\n'
        check(b.evaluate("window.studio.text()") == inserted and b.evaluate("document.querySelector('#saved').textContent") == "unsaved",
              "with the kept text, unsaved")
        status_line = b.evaluate("document.querySelector('#status').textContent")
        check(".plain.hmat.recovered" in status_line, f"the status line says where it came from: {status_line!r}")
        cursor_on_line(b, 1)
        for kind in ("rawKeyDown", "keyUp"):
            b.send("Input.dispatchKeyEvent", {"type": kind, "key": "z", "code": "KeyZ", "modifiers": 2, "windowsVirtualKeyCode": 90})
        check(wait(b, "window.studio.text() === %s && document.querySelector('#saved').textContent === 'saved'" % json.dumps(plain),
                   "the undo"), "Ctrl-Z goes back to the file's text, which is saved")
    finally:
        b.close()
        again.stop()
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
