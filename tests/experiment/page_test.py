#!/usr/bin/env python3
"""The subject's page (docs/EXPERIMENTS.md, "The subject's page") in headless Chromium, against
`sandpaper experiment run --observer page` on the simulated joystick: a magnitude-estimation session
answered at the keyboard (a bad answer refused at the page and at the server), a rest break, the
two-interval keys, and a sorting session whose patches are dragged and tapped into piles; what the
page sent is what results.jsonl holds. A session killed mid-way leaves the page saying "Paused". The Host guard refuses a foreign name. Screenshots in <out>.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1)."""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import urllib.error
import urllib.request

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "support"))
sys.path.insert(0, os.path.join(here, "..", "catalog"))
from cdp import Browser, chromium_for_test  # noqa: E402
from checklist import Checklist  # noqa: E402

c = Checklist()

HEAD = 'schema = "sandpaper-experiment/1"\ninstructions = """Feel each surface.\nAnswer on this page."""\n'
PRESENT = '[presentation]\nduration = "0.3 s"\nramp = "0.05 s"\nhand_speed_mm_s = 30\n'
ME = HEAD + ('title = "Roughness"\ntask = "magnitude-estimation"\nstimuli = ["a3p7", "a10p12", "a19p100"]\n'
             'seed = 3\npractice = 1\nbreak_every = 2\n') + PRESENT
TWO = HEAD + ('title = "Stronger"\ntask = "two-interval"\nstimuli = ["a10p25"]\nseed = 3\n'
              '[two_interval]\nincrements = [0.1, 0.3]\n') + PRESENT
SORT = HEAD + ('title = "Sorting"\ntask = "sorting"\nstimuli = ["a1p7", "a3p12", "a10p50", "a19p100", "a3p100"]\n'
               'seed = 3\n[sorting]\npiles = [2, 3]\n') + PRESENT


class Session:
    """`experiment run --observer page` in the background; `url` once its readiness line is printed."""

    def __init__(self, sp, design, out):
        self.proc = subprocess.Popen([sp, "experiment", "run", str(design), "--subject", "P1", "-o", str(out),
                                      "--observer", "page", "--listen", "127.0.0.1:0", "--virtual-clock"],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.url = None
        self.err = []
        ready = threading.Event()

        def read():
            for line in self.proc.stderr:
                self.err.append(line)
                m = re.match(r"subject page: (http://\S+)", line)
                if m:
                    self.url = m.group(1)
                    ready.set()
            ready.set()

        threading.Thread(target=read, daemon=True).start()
        ready.wait(60)

    def finish(self):
        try:
            out, _ = self.proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, _ = self.proc.communicate()
        return self.proc.returncode, out


last_seq = [-1]


def screen(b, kind, seconds=20):
    """Waits for a new screen (a seq not seen before) of `kind`."""
    try:
        b.wait_for(f"document.body.dataset.screen === {json.dumps(kind)} && +document.body.dataset.seq > {last_seq[0]}",
                   kind, seconds)
        last_seq[0] = b.evaluate("+document.body.dataset.seq")
        return True
    except Exception:
        return False


def key(b, name, code, text=None):
    down = {"type": "keyDown" if text else "rawKeyDown", "key": name, "code": name, "windowsVirtualKeyCode": code}
    if text:
        down["text"] = text
    b.send("Input.dispatchKeyEvent", down)
    b.send("Input.dispatchKeyEvent", {"type": "keyUp", "key": name, "code": name, "windowsVirtualKeyCode": code})


def centre(b, selector):
    return b.evaluate("(() => { const r = document.querySelector(%s).getBoundingClientRect();"
                      " return [r.left + r.width / 2, r.top + r.height / 2]; })()" % json.dumps(selector))


def drag(b, source, target):
    (x0, y0), (x1, y1) = centre(b, source), centre(b, target)
    b.send("Input.dispatchMouseEvent", {"type": "mouseMoved", "x": x0, "y": y0})
    b.send("Input.dispatchMouseEvent", {"type": "mousePressed", "x": x0, "y": y0, "button": "left", "buttons": 1, "clickCount": 1})
    for i in range(1, 11):
        b.send("Input.dispatchMouseEvent", {"type": "mouseMoved", "x": x0 + (x1 - x0) * i / 10, "y": y0 + (y1 - y0) * i / 10,
                                            "button": "left", "buttons": 1})
    b.send("Input.dispatchMouseEvent", {"type": "mouseReleased", "x": x1, "y": y1, "button": "left", "buttons": 0, "clickCount": 1})


def begin(b, sp, tmp, name, text):
    """Starts a session of design `text` and opens its page at the first question."""
    (tmp / f"{name}.toml").write_text(text)
    s = Session(sp, tmp / f"{name}.toml", tmp / name)
    last_seq[0] = -1
    b.navigate(s.url)
    ok = screen(b, "instructions")
    b.click("#continue")
    return s, ok


def answers(folder):
    return [json.loads(l) for l in open(folder / "results.jsonl") if '"answer"' in l]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    chromium, status = chromium_for_test("the subject page's test")
    if status is not None:
        return status
    sp = os.path.abspath(args.sandpaper)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-page-"))
    b = Browser(chromium, width=1280, height=900)
    try:
        # Magnitude estimation at the keyboard.
        (tmp / "me.toml").write_text(ME)
        s = Session(sp, tmp / "me.toml", tmp / "me")
        c.check(s.url is not None, f"the session prints the page's address ({s.url})")
        req = urllib.request.Request(s.url + "api/screen", headers={"Host": "evil.example:80"})
        try:
            urllib.request.urlopen(req, timeout=10)
            refused = False
        except urllib.error.HTTPError as e:
            refused = e.code == 403
        c.check(refused, "a request naming another host is refused (403)")
        last_seq[0] = -1
        b.navigate(s.url)
        c.check(screen(b, "instructions") and "Feel each surface." in b.evaluate("document.body.innerText"),
                "the instructions are shown")
        heading = b.evaluate("document.querySelector('h1').innerText")
        c.check(heading == "How rough does each surface feel?", f"the subject sees a subject's title, not the design's ({heading!r})")
        paras = b.evaluate("JSON.stringify([...document.querySelectorAll('.instructions p')].map(p => p.innerText))")
        c.check(json.loads(paras) == ["Feel each surface. Answer on this page."],
                f"the design's hard line break flows within its paragraph ({paras})")
        b.screenshot(str(out / "subject-instructions.png"), full_page=False)
        key(b, "Enter", 13)
        values = ["4", "7.5", "12", "2"]
        ok = True
        for i, v in enumerate(values):
            ok = ok and screen(b, "estimate")
            if i == 0:
                b.type_into("#value", "-3")
                key(b, "Enter", 13)
                ok = ok and b.evaluate("document.querySelector('.error').textContent").startswith("Please give a positive")
                seq = b.evaluate("+document.body.dataset.seq")
                r = urllib.request.Request(s.url + "api/answer", data=json.dumps({"seq": seq, "value": -3}).encode(),
                                           headers={"Content-Type": "application/json"}, method="POST")
                try:
                    urllib.request.urlopen(r, timeout=10)
                    ok = False
                except urllib.error.HTTPError as e:
                    ok = ok and e.code == 400
            b.type_into("#value", v)
            if i == 1:
                b.screenshot(str(out / "subject-estimate.png"), full_page=False)
            key(b, "Enter", 13)
            if i == 2:  # after two recorded trials: the rest break
                ok = ok and screen(b, "rest")
                b.click("#continue")
        c.check(ok, "four estimates typed (a negative one refused by the page and by the server), with a rest after two")
        c.check(screen(b, "done"), "the page thanks the subject at the end")
        rc, stdout = s.finish()
        got = [a["response"] for a in answers(tmp / "me")]
        c.check(rc == 0 and got == [4, 7.5, 12, 2], f"results.jsonl holds what was typed: {got} (exit {rc})")

        # A session killed with SIGKILL cannot send its last screen: the page says "Paused" itself,
        # as docs/EXPERIMENTS.md promises, not "Waiting for the experiment".
        s, ok = begin(b, sp, tmp, "killed", ME)
        ok = ok and screen(b, "estimate")
        s.proc.kill()
        s.proc.wait()
        try:
            b.wait_for("document.body.dataset.screen === 'paused' && document.body.innerText.includes('Paused')",
                       "paused", 30)
            paused = True
        except Exception:
            paused = False
        shown = b.evaluate("document.body.innerText")
        c.check(ok and paused, f"after kill -9 mid-session the page says Paused ({shown.strip()!r})")

        # Two intervals: the number keys.
        s, ok = begin(b, sp, tmp, "two", TWO)
        for k in ("1", "2"):
            ok = ok and screen(b, "interval")
            key(b, k, 48 + int(k), k)
        ok = ok and screen(b, "done")
        rc, _ = s.finish()
        got = [a["chosen_interval"] for a in answers(tmp / "two")]
        c.check(ok and rc == 0 and got == [1, 2], f"two-interval answers by the 1 and 2 keys: {got}")

        # Sorting: drag for the first sort, tap patch then pile for the second.
        s, ok = begin(b, sp, tmp, "sort", SORT)
        ok = ok and screen(b, "sort")
        # The server checks what it is sent: 4294967297 was taken as pile 1 (read as a 32-bit int).
        seq = b.evaluate("+document.body.dataset.seq")
        r = urllib.request.Request(s.url + "api/answer", headers={"Content-Type": "application/json"}, method="POST",
                                   data=json.dumps({"seq": seq, "assignment": [4294967297, 2, 1, 2, 2]}).encode())
        try:
            urllib.request.urlopen(r, timeout=10)
            c.check(False, "an assignment to pile 4294967297 was accepted")
        except urllib.error.HTTPError as e:
            c.check(e.code == 400, f"an assignment to pile 4294967297 is refused (HTTP {e.code})")
        plan1 = {1: 1, 2: 2, 3: 1, 4: 2, 5: 2}
        for patch, pile in plan1.items():
            drag(b, f"#patch-{patch}", f"#pile-{pile}")
        placed = b.evaluate("[1,2,3,4,5].map(i => +document.getElementById('patch-' + i).parentElement.dataset.pile)")
        ok = ok and placed == [plan1[i] for i in range(1, 6)]
        b.screenshot(str(out / "subject-sorting.png"), full_page=False)
        b.click("#done")
        ok = ok and screen(b, "sort") and b.evaluate("document.getElementById('pile-3') !== null")
        plan2 = {1: 3, 2: 1, 3: 2, 4: 3, 5: 1}
        early = b.evaluate("document.getElementById('done').disabled")  # until every patch is in a pile
        for patch, pile in plan2.items():
            b.click(f"#patch-{patch}")
            b.click(f"#pile-{pile}")
        b.click("#done")
        ok = ok and screen(b, "done")
        rc, _ = s.finish()
        c.check(ok and early, f"patches dragged into 2 piles, then tapped into 3 ({placed}); Done waits for all")
        got = answers(tmp / "sort")
        want_ok = len(got) == 2
        for a, plan in zip(got, (plan1, plan2)):
            for patch, pile in plan.items():
                want_ok = want_ok and a["stimuli"][patch - 1] in a["piles"][pile - 1]
        c.check(rc == 0 and want_ok, "results.jsonl holds each patch (by its number on the page) in the pile it was put in")
    finally:
        b.close()
        shutil.rmtree(tmp, ignore_errors=True)
    return c.finish()


if __name__ == "__main__":
    sys.exit(main())
