#!/usr/bin/env python3
"""`sandpaper run FILE --watch`: plays until Ctrl-C, recompiles on every save and swaps the new program
in; a save that does not compile leaves the last good program playing. Waits for the lines the run
prints (never a sleep), with bounded deadlines. Prints 'N passed, N failed'."""
import argparse
import os
import pathlib
import select
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check


class Lines:
    def __init__(self, stream):
        self.fd = stream.fileno()
        self.buffer = b""
        self.seen = []

    def wait_for(self, needle, seconds=30):
        deadline = time.monotonic() + seconds
        while True:
            while b"\n" in self.buffer:
                line, self.buffer = self.buffer.split(b"\n", 1)
                text = line.decode(errors="replace")
                self.seen.append(text)
                if needle in text:
                    return text
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            ready, _, _ = select.select([self.fd], [], [], left)
            if ready:
                chunk = os.read(self.fd, 4096)
                if not chunk:
                    return None
                self.buffer += chunk


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    args = ap.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-watch-"))
    material = tmp / "m.hmat"
    material.write_text("# watched\nroughness 0.5\ngrating period 3 mm\n")
    proc = subprocess.Popen([os.path.abspath(args.sandpaper), "run", str(material), "--watch", "--device", "sim"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    err = Lines(proc.stderr)
    try:
        check(err.wait_for("watch: playing") is not None, "the run says it is playing and watching")
        material.write_text("# watched\nroughness 0.8\ngrating period 3 mm\n")
        line = err.wait_for("watch: reloaded")
        check(line is not None and "roughness 0.8" in line, f"a save is recompiled and swapped in: {line}")
        material.write_text("# watched\nroughness 0.8\ngrating period 3 m m\n")
        line = err.wait_for("the last good program keeps playing")
        check(line is not None and "does not compile" in line, "a broken save is reported, and the last good program plays on")
        check(any("E02" in s for s in err.seen), "with the compiler's diagnostics")
        check(proc.poll() is None, "the run is still going")
        material.write_text("# watched\nroughness 0.3\ngrating period 3 mm\n")
        line = err.wait_for("watch: reloaded")
        check(line is not None and "roughness 0.3" in line, f"the next good save plays: {line}")
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            out, _ = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            out, _ = proc.communicate()
    out = out.decode(errors="replace")
    check(proc.returncode == 0 and "stopped by signal" in out, f"Ctrl-C ends it (exit {proc.returncode})")
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
