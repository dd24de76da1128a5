#!/usr/bin/env python3
"""The USB lab's tests (ctest label usb-lab; docs/USB_PID.md "In the lab"): each boots the QEMU
guest, runs one scenario of usb-lab/scenarios/ with the build's programs, and checks what the guest
wrote to its /out folder. A guest that cannot boot is a failure, not a skip.

  lab_test.py NAME --build DIR [--out DIR]
"""
from __future__ import annotations

import argparse
import json
import re
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "usb-lab"))
import scenario  # noqa: E402

failures: list[str] = []


def check(ok: bool, what: str) -> None:
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def hex_bytes(path: Path) -> str:
    """The bytes of one of tests/runtime/usb/data/*.hex (# comments, hex pairs) as plain hex."""
    text = "".join(line.split("#", 1)[0] for line in path.read_text().splitlines())
    return "".join(re.findall(r"[0-9a-fA-F]{2}", text))


def test_enumerate(build: Path, out: Path) -> None:
    stranger = hex_bytes(REPO / "tests/runtime/usb/data/openffboard_2axis.hex")
    r = scenario.run("enumerate", build, out, params={
        "STRANGER_VID": "0x1d6b", "STRANGER_PID": "0x0104", "STRANGER_HEX": stranger})
    check(r.status == 0, f"the scenario ran to its end (status {r.status})")
    if r.status != 0:
        return
    facts = json.loads((out / "enumerate.json").read_text())
    devices = (out / "devices.txt").read_text()
    check(facts["devices_status"] == 0, f"`sandpaper devices` exited 0 (got {facts['devices_status']})")
    check(facts["ffboard_speed"] == "12", f"the OpenFFBoard enumerated at full speed (12 Mb/s; got {facts['ffboard_speed']})")
    ffb = [l for l in devices.splitlines() if l.startswith("1209:ffb0")]
    check(len(ffb) == 1, "devices lists the OpenFFBoard once (1209:ffb0)")
    if ffb:
        check("HID PID force feedback" in ffb[0], "its descriptor is read as HID PID force feedback: " + ffb[0])
        check(re.search(r"calibration openffboard-2axis \((\S*/)?calibration/devices/openffboard-2axis\.toml\)$", ffb[0])
              is not None, "it names its calibration file")
    stranger_lines = [l for l in devices.splitlines() if l.startswith("1d6b:0104")]
    check(len(stranger_lines) == 1, "devices lists the unknown force-feedback gadget (1d6b:0104)")
    if stranger_lines:
        check("no device calibration: cannot be played yet" in stranger_lines[0],
              "the unknown one is listed as unknown: " + stranger_lines[0])
    check(facts["stranger_hidraw_before"] != "" and facts["stranger_hidraw_after"] == facts["stranger_hidraw_before"],
          "the unknown device was not opened: its kernel driver stayed bound "
          f"({facts['stranger_hidraw_before']} -> {facts['stranger_hidraw_after']})")
    check(facts["ffboard_driver_before"] == "usbhid" and facts["ffboard_driver_after"] == "usbhid",
          "listing devices leaves usbhid bound to the OpenFFBoard")


TESTS = {"enumerate": test_enumerate}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("name", choices=sorted(TESTS))
    p.add_argument("--build", required=True, type=Path)
    p.add_argument("--out", type=Path, help="keep the guest's output here (default: a temporary folder)")
    a = p.parse_args()
    try:
        if a.out:
            TESTS[a.name](a.build.resolve(), a.out.resolve())
        else:
            with tempfile.TemporaryDirectory(prefix=f"usb-lab-{a.name}-") as d:
                TESTS[a.name](a.build.resolve(), Path(d))
    except scenario.LabError as e:
        print(f"FAIL: the lab could not run: {e}", flush=True)
        return 1
    if failures:
        print(f"{a.name}: {len(failures)} check(s) failed", flush=True)
        return 1
    print(f"{a.name}: all checks passed", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
