"""A small Chrome DevTools Protocol client over --remote-debugging-pipe, standard library only.

Chromium reads NUL-terminated JSON commands on its fd 3 and writes responses and events on its fd 4
(https://chromedevtools.github.io/devtools-protocol/). One page target, attached with flatten=True, so
every page command carries its sessionId.
"""
import base64
import fcntl
import json
import os
import select
import shutil
import subprocess
import tempfile
import time


class CdpError(RuntimeError):
    pass


def find_chromium():
    """The Chromium executable: $CHROMIUM, else chromium or chromium-browser on PATH, else None."""
    env = os.environ.get("CHROMIUM")
    if env:
        return env if os.access(env, os.X_OK) else None
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def chromium_for_test(what):
    """(executable, None) when a browser test can run; (None, exit status) when it cannot: 77 (skipped)
    with SANDPAPER_SKIP_BROWSER_TESTS=1, else 1 (failed) when Chromium is missing, saying why."""
    if os.environ.get("SANDPAPER_SKIP_BROWSER_TESTS") == "1":
        print("skipped: SANDPAPER_SKIP_BROWSER_TESTS=1")
        return None, 77
    chromium = find_chromium()
    if not chromium:
        print(f"FAIL Chromium not found: {what} needs it. Install it with `sudo apt-get install chromium` "
              "(tools/install-deps.sh does), or set CHROMIUM=/path/to/chromium; "
              "SANDPAPER_SKIP_BROWSER_TESTS=1 skips this test.")
        return None, 1
    return chromium, None


class Browser:
    def __init__(self, executable, width=1280, height=900, timeout=60):
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="sandpaper-chromium-")
        to_child_r, self._to_child_w = os.pipe()
        self._from_child_r, from_child_w = os.pipe()
        # Above 10, so that placing them on 3 and 4 in the child cannot overwrite one with the other.
        a = fcntl.fcntl(to_child_r, fcntl.F_DUPFD, 10)
        b = fcntl.fcntl(from_child_w, fcntl.F_DUPFD, 10)

        def on_fds_3_and_4():
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [executable, "--headless=new", "--remote-debugging-pipe", "--user-data-dir=" + self.profile,
                "--no-first-run", "--no-default-browser-check", "--disable-gpu", "--hide-scrollbars",
                "--disable-extensions", "--mute-audio", f"--window-size={width},{height}", "about:blank"]
        if os.geteuid() == 0:
            args.insert(1, "--no-sandbox")  # Chromium refuses to run as root with its sandbox
        self.proc = subprocess.Popen(args, preexec_fn=on_fds_3_and_4, close_fds=False,
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        for fd in (to_child_r, from_child_w, a, b):
            os.close(fd)
        self._buffer = b""
        self._next_id = 0
        self._events = []
        self.session = None
        target = self.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 session=False)["sessionId"]
        self.send("Page.enable")
        self.send("Runtime.enable")
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)
        os.close(self._to_child_w)
        os.close(self._from_child_r)

    def _read_message(self, deadline):
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise CdpError("Chromium did not answer within %d s" % self.timeout)
            ready, _, _ = select.select([self._from_child_r], [], [], left)
            if not ready:
                continue
            chunk = os.read(self._from_child_r, 1 << 20)
            if not chunk:
                err = self.proc.stderr.read().decode(errors="replace") if self.proc.poll() is not None else ""
                raise CdpError("Chromium closed the DevTools pipe" + (": " + err[-2000:] if err else ""))
            self._buffer += chunk
        raw, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(raw)

    def send(self, method, params=None, session=True):
        self._next_id += 1
        msg = {"id": self._next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self._to_child_w, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self._next_id:
                if "error" in m:
                    raise CdpError(f"{method}: {m['error']}")
                return m.get("result", {})
            if "method" in m:
                self._events.append(m)

    def wait_event(self, method, deadline_s=None):
        deadline = time.monotonic() + (deadline_s or self.timeout)
        while True:
            for i, e in enumerate(self._events):
                if e["method"] == method and e.get("sessionId") == self.session:
                    return self._events.pop(i)
            self._events.append(self._read_message(deadline))

    def clear_events(self):
        self._events.clear()

    def navigate(self, url):
        self.clear_events()
        result = self.send("Page.navigate", {"url": url})
        if result.get("errorText"):
            raise CdpError(f"cannot open {url}: {result['errorText']}")
        self.wait_event("Page.loadEventFired")

    def evaluate(self, expression):
        r = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in r:
            raise CdpError(f"JavaScript failed: {r['exceptionDetails']}\n{expression}")
        return r["result"].get("value")

    def wait_for(self, expression, what, deadline_s=10):
        deadline = time.monotonic() + deadline_s
        while time.monotonic() < deadline:
            if self.evaluate(expression):
                return
            time.sleep(0.05)
        raise CdpError("timed out waiting for " + what)

    # Where a click lands: the element's centre once it has stayed put for two animation frames and
    # is the topmost thing there (a person clicks what they see). On a loaded machine a page still
    # laying out after an answer (a list above the button growing or shrinking) moves the button
    # between measuring it and the press, and the press lands beside it.
    _CLICK_POINT = """(async () => {
        const e = document.querySelector(%s); if (!e) return null;
        e.scrollIntoView({block: 'center'});
        const frame = () => new Promise((r) => requestAnimationFrame(() => r()));
        const centre = () => { const r = e.getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2]; };
        let last = centre(), why = '';
        for (let i = 0; i < 100; i++) {
          await frame(); await frame();
          const now = centre();
          const top = document.elementFromPoint(now[0], now[1]);
          if (now[0] === last[0] && now[1] === last[1] && top && (top === e || e.contains(top))) return now;
          why = top && top !== e && !e.contains(top) ? 'covered by ' + (top.id || top.tagName) : 'still moving';
          last = now;
        }
        return why;
      })()"""

    def click(self, selector):
        """A real mouse click at the centre of the element (scrolled into view, standing still, on top)."""
        box = self.evaluate(self._CLICK_POINT % json.dumps(selector))
        if box is None:
            raise CdpError("nothing matches " + selector)
        if isinstance(box, str):
            raise CdpError(f"cannot click {selector}: {box}")
        for kind in ("mouseMoved", "mousePressed", "mouseReleased"):
            self.send("Input.dispatchMouseEvent", {"type": kind, "x": box[0], "y": box[1], "button": "left",
                                                   "clickCount": 1})

    def type_into(self, selector, text):
        """Focuses the field, selects what it holds and types `text` as keyboard input would."""
        self.evaluate("(() => { const e = document.querySelector(%s); e.focus(); e.select && e.select(); })()"
                      % json.dumps(selector))
        self.send("Input.insertText", {"text": text})

    def screenshot(self, path, full_page=True, max_height=6000):
        params = {"format": "png"}
        if full_page:
            w, h = self.evaluate("[document.documentElement.scrollWidth, document.documentElement.scrollHeight]")
            params["captureBeyondViewport"] = True
            params["clip"] = {"x": 0, "y": 0, "width": w, "height": min(h, max_height), "scale": 1}
        data = self.send("Page.captureScreenshot", params)["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))
