#!/usr/bin/env python3
"""tools/usb-lab/run with input it cannot use: a material that does not compile is refused on the
host with the compiler's diagnostics and exit status 1, before any guest is booted; a missing file and
bad figures are usage errors (2). Needs only the build's `sandpaper`, not QEMU or the firmware.

  tool_test.py --build DIR
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
failures: list[str] = []


def check(ok: bool, what: str) -> None:
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def tool(build: Path, *args: str) -> tuple[subprocess.CompletedProcess, float]:
    t0 = time.monotonic()
    r = subprocess.run([sys.executable, str(REPO / "tools/usb-lab/run"), "--build", str(build), *args],
                       capture_output=True, text=True, timeout=120)
    return r, time.monotonic() - t0


def main() -> int:
    p = argparse.ArgumentParser()
    p.add_argument("--build", type=Path, required=True)
    real = p.parse_args().build.resolve() / "bin" / "sandpaper"
    with tempfile.TemporaryDirectory(prefix="usb-lab-tool-") as tmp:
        tmp = Path(tmp)
        # A build tree of our own holding only the compiler: the guest's files (its initramfs, in
        # BUILD/usb-lab) would appear here if a guest were prepared, and nothing else could boot one.
        build = tmp / "build"
        (build / "bin").mkdir(parents=True)
        (build / "bin" / "sandpaper").symlink_to(real)
        bad = tmp / "typo.hmat"
        bad.write_text('material "typo" {\n  grating period 2.5 mm\n  roughnes 0.6\n}\n')

        for extra in ([], ["--device", "hidraw"], ["--fault", "unplug"]):
            r, seconds = tool(build, "--material", str(bad), *extra)
            what = " ".join(["run", "--material typo.hmat", *extra])
            check(r.returncode == 1, f"{what}: exit status 1 (got {r.returncode}; {seconds:.2f} s)")
            check(f"{bad}:3:3" in r.stderr and "roughnes" in r.stderr,
                  f"the compiler's diagnostic at typo.hmat:3:3 is printed: {r.stderr.strip()[:400]!r}")
            check("does not compile" in r.stderr and "no guest was booted" in r.stderr,
                  f"and the tool says the material does not compile and no guest was booted")
            check("Traceback" not in r.stderr, "no Python traceback")
            check(r.stdout == "", f"nothing on stdout: {r.stdout[:200]!r}")
        check(not (build / "usb-lab").exists(), "no guest's files were prepared (BUILD/usb-lab absent)")

        r, _ = tool(build, "--material", str(tmp / "absent.hmat"))
        check(r.returncode == 2 and "no such material file" in r.stderr, f"a missing file is a usage error: {r.returncode} {r.stderr.strip()!r}")
        r, _ = tool(build, "--material", str(REPO / "examples/corduroy.hmat"), "--speed", "0")
        check(r.returncode == 2 and "must be positive" in r.stderr, f"a speed of 0 is a usage error: {r.returncode} {r.stderr.strip()!r}")
        r, _ = tool(build, "--material", str(bad), "--device", "bluetooth")
        check(r.returncode == 2 and "invalid choice" in r.stderr, f"an unknown path is a usage error: {r.returncode}")
        r, _ = tool(build, "--material", str(REPO / "examples/corduroy.hmat"), "--fault", "stale", "--device", "evdev")
        check(r.returncode == 2 and "cannot be seen" in r.stderr,
              f"a stale device through evdev is refused, saying why: {r.returncode} {r.stderr.strip()[-160:]!r}")

        os.unlink(build / "bin" / "sandpaper")
        r, _ = tool(build, "--material", str(bad))
        check(r.returncode == 1 and "not built" in r.stderr and "README" in r.stderr,
              f"without a built sandpaper it says to build it: {r.returncode} {r.stderr.strip()!r}")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
