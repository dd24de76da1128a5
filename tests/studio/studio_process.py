"""A `sandpaper studio` process for tests: started on a free loopback port, ready once it prints its
`studio: http://...` line (never after a sleep), spoken to over HTTP with the standard library, and
stopped with SIGINT as a user's Ctrl-C would."""
import http.client
import json
import os
import re
import select
import signal
import subprocess
import time


class StudioError(RuntimeError):
    pass


class Studio:
    def __init__(self, sandpaper, path, *extra, ready_timeout=60):
        self.proc = subprocess.Popen([sandpaper, "studio", str(path), "--listen", "127.0.0.1:0", *extra],
                                     stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.output = b""
        deadline = time.monotonic() + ready_timeout
        while True:
            line = self._read_line(deadline)
            m = re.match(rb"studio: http://([^:/]+):(\d+)/", line)
            if m:
                self.host, self.port = m.group(1).decode(), int(m.group(2))
                self.url = f"http://{self.host}:{self.port}/"
                return

    def _read_line(self, deadline):
        while b"\n" not in self.output:
            left = deadline - time.monotonic()
            if left <= 0 or self.proc.poll() is not None:
                err = self.proc.stderr.read().decode(errors="replace") if self.proc.poll() is not None else ""
                raise StudioError("the studio did not print its address: " + self.output.decode(errors="replace") + err)
            ready, _, _ = select.select([self.proc.stdout], [], [], min(left, 0.5))
            if ready:
                chunk = os.read(self.proc.stdout.fileno(), 4096)
                if not chunk:
                    continue
                self.output += chunk
        line, self.output = self.output.split(b"\n", 1)
        return line

    def request(self, method, path, body=None, content_type="application/json", headers=None):
        """(status, parsed JSON or bytes). `headers` may replace Host or add Origin."""
        conn = http.client.HTTPConnection(self.host, self.port, timeout=30)
        try:
            conn.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
            hdrs = {"Host": f"{self.host}:{self.port}"}
            hdrs.update(headers or {})
            data = b""
            if body is not None:
                data = body.encode() if isinstance(body, str) else json.dumps(body).encode()
                hdrs["Content-Type"] = content_type if isinstance(body, str) else "application/json"
            hdrs["Content-Length"] = str(len(data))
            for k, v in hdrs.items():
                conn.putheader(k, v)
            conn.endheaders(data)
            res = conn.getresponse()
            raw = res.read()
            ctype = res.getheader("Content-Type", "")
            return res.status, (json.loads(raw) if ctype.startswith("application/json") else raw)
        finally:
            conn.close()

    def get(self, path, **kw):
        return self.request("GET", path, **kw)

    def post(self, path, body, **kw):
        return self.request("POST", path, body, **kw)

    def state(self):
        status, s = self.get("/api/state")
        if status != 200:
            raise StudioError(f"/api/state: HTTP {status}")
        return s

    def stop(self, timeout=30):
        """Ctrl-C; returns (exit code, everything it printed on stdout after the address)."""
        self.proc.send_signal(signal.SIGINT)
        try:
            out, err = self.proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, err = self.proc.communicate()
            raise StudioError("the studio did not stop on SIGINT")
        return self.proc.returncode, (self.output + out).decode(errors="replace"), err.decode(errors="replace")
