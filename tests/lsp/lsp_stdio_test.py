#!/usr/bin/env python3
"""`sandpaper lsp` as a process, driven over stdio as an editor drives it.

Usage: lsp_stdio_test.py SANDPAPER_BINARY. Prints the exchange (what was sent, what came back) and
fails on any wrong answer. Waits for replies by reading the pipe, with a generous deadline that
only a hung server reaches; never sleeps.
"""
import json
import os
import select
import subprocess
import sys
import tempfile

DEADLINE_S = 120


def frame(message):
    body = json.dumps(message).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


class Server:
    def __init__(self, binary):
        self.proc = subprocess.Popen([binary, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE)
        self.buffer = b""
        self.next_id = 1

    def _read_some(self):
        ready, _, _ = select.select([self.proc.stdout], [], [], DEADLINE_S)
        if not ready:
            raise AssertionError("no reply within %d s" % DEADLINE_S)
        chunk = os.read(self.proc.stdout.fileno(), 65536)
        if not chunk:
            raise AssertionError("the server closed stdout; stderr: " + self.proc.stderr.read().decode())
        self.buffer += chunk

    def read(self):
        while b"\r\n\r\n" not in self.buffer:
            self._read_some()
        header, rest = self.buffer.split(b"\r\n\r\n", 1)
        length = int(header.split(b":")[1])
        while len(rest) < length:
            self._read_some()
            header, rest = self.buffer.split(b"\r\n\r\n", 1)
        self.buffer = rest[length:]
        message = json.loads(rest[:length])
        print("<-", json.dumps(message)[:400])
        return message

    def send(self, method, params=None, request=True):
        message = {"jsonrpc": "2.0", "method": method}
        if params is not None:
            message["params"] = params
        if request:
            message["id"] = self.next_id
            self.next_id += 1
        print("->", json.dumps(message)[:400])
        self.proc.stdin.write(frame(message))
        self.proc.stdin.flush()
        return message.get("id")

    def response(self, id_):
        while True:
            m = self.read()
            if m.get("id") == id_:
                return m


def main():
    binary = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "wale.hmat")
        uri = "file://" + path
        text = 'material "wale" {\n  like corduroy\n  grating period 3.2 mm hill 50%\n  roughness 0.55 zz\n}\n'
        s = Server(binary)
        init = s.response(s.send("initialize", {"processId": os.getpid(), "rootUri": "file://" + tmp,
                                                 "capabilities": {}}))
        assert init["result"]["capabilities"]["hoverProvider"] is True, init
        s.send("initialized", {}, request=False)
        s.send("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "sandpaper", "version": 1,
                                                         "text": text}}, request=False)
        diags = s.read()
        assert diags["method"] == "textDocument/publishDiagnostics", diags
        codes = [d["code"] for d in diags["params"]["diagnostics"]]
        assert codes == ["E0210"], codes  # `zz` after a complete roughness statement
        assert diags["params"]["diagnostics"][0]["range"]["start"] == {"line": 3, "character": 17}, diags

        fixed = text.replace(" zz", "")
        s.send("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                          "contentChanges": [{"text": fixed}]}, request=False)
        diags = s.read()
        assert diags["params"]["diagnostics"] == [], diags

        pos = lambda line, ch: {"textDocument": {"uri": uri}, "position": {"line": line, "character": ch}}
        hover = s.response(s.send("textDocument/hover", pos(2, 18)))
        value = hover["result"]["contents"]["value"]
        assert "texture.period" in value and "3.2 mm" in value and "physical" in value, value
        completion = s.response(s.send("textDocument/completion", pos(1, 7)))
        labels = [i["label"] for i in completion["result"]]
        assert "corduroy" in labels and "velvet" in labels, labels[:20]
        definition = s.response(s.send("textDocument/definition", pos(1, 9)))
        target = definition["result"]["uri"]
        assert target.startswith("file://") and target.endswith("/corduroy.hmat"), definition
        with open(target[len("file://"):]) as f:
            line = f.read().split("\n")[definition["result"]["range"]["start"]["line"]]
        assert line.startswith('material "corduroy"'), line

        shutdown = s.response(s.send("shutdown"))
        assert shutdown["result"] is None, shutdown
        s.send("exit", request=False)
        s.proc.stdin.close()
        status = s.proc.wait(timeout=DEADLINE_S)
        log = s.proc.stderr.read().decode()
        print("stderr:", log.strip())
        assert status == 0, status
        assert "ready" in log, log
    print("lsp stdio: ok")


if __name__ == "__main__":
    main()
