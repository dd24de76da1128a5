#!/usr/bin/env python3
"""The udev rules Sandpaper installs (docs/DEVICES.md "No root"): each line is udev syntax (udev(7):
comma-separated KEY op "value", match keys with == or !=, assignments with =, += or :=), checked by
`udevadm verify` too where this system's udev has it (systemd 253 and later; Debian 12 has 252);
the file gives uaccess to the hidraw nodes of every USB device a calibration file names and to input
event devices whose force-feedback bitmap is not zero, matched here as udev matches (shell globs).

  udev_rules_test.py RULES_FILE CALIBRATION_DIR
"""
from __future__ import annotations

import fnmatch
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

MATCH_KEYS = {"ACTION", "DEVPATH", "KERNEL", "KERNELS", "SUBSYSTEM", "SUBSYSTEMS", "DRIVER", "DRIVERS",
              "TAGS", "RESULT", "PROGRAM", "TEST", "ATTR", "ATTRS", "ENV", "CONST", "SYSCTL", "TAG", "NAME"}
ASSIGN_KEYS = {"TAG", "MODE", "OWNER", "GROUP", "ENV", "SYMLINK", "RUN", "OPTIONS", "NAME", "ATTR", "IMPORT",
               "LABEL", "GOTO", "SECLABEL", "SYSCTL"}
WITH_ATTRIBUTE = {"ATTR", "ATTRS", "ENV", "CONST", "SYSCTL", "TEST", "IMPORT", "RUN", "SECLABEL"}
PAIR = re.compile(r'\s*([A-Z]+)(?:\{([^{}"]+)\})?\s*(==|!=|\+=|-=|:=|=)\s*"((?:[^"\\]|\\.)*)"\s*')

failures: list[str] = []


def check(ok: bool, what: str) -> None:
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def parse(line: str) -> list[tuple[str, str | None, str, str]] | str:
    """The rule's (key, attribute, op, value) list, or why it is not udev syntax."""
    pairs, at = [], 0
    while at < len(line):
        m = PAIR.match(line, at)
        if not m:
            return f"not KEY op \"value\" at column {at + 1}: {line[at:]!r}"
        key, attr, op, value = m.groups()
        matching = op in ("==", "!=")
        if key not in (MATCH_KEYS if matching else ASSIGN_KEYS):
            return f"{key} cannot be used with {op}"
        if (attr is None) == (key in WITH_ATTRIBUTE) and key not in ("RUN", "IMPORT", "TEST"):
            return f"{key} {'needs' if attr is None else 'takes no'} {{attribute}}"
        pairs.append((key, attr, op, value))
        at = m.end()
        if at < len(line):
            if line[at] != ",":
                return f"expected ',' at column {at + 1}"
            at += 1
    return pairs


def matches(rule, device: dict) -> bool:
    """Whether the match keys of `rule` hold for `device` ({"SUBSYSTEM", "KERNEL", "ATTRS": [{...} per
    device up the chain]}): udev's shell-glob comparison; all ATTRS of one rule on one device."""
    chain_attrs = [r for r in rule if r[0] == "ATTRS"]
    for key, attr, op, value in rule:
        if op not in ("==", "!=") or key == "ATTRS":
            continue
        ok = fnmatch.fnmatchcase(device.get(key, ""), value)
        if ok != (op == "=="):
            return False
    if chain_attrs:
        return any(all(attr in level and fnmatch.fnmatchcase(level[attr], value) for _, attr, _, value in chain_attrs)
                   for level in device["ATTRS"])
    return True


def main() -> int:
    rules_file, calibration = Path(sys.argv[1]), Path(sys.argv[2])
    text = rules_file.read_text()
    rules = []
    for n, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parsed = parse(line)
        check(not isinstance(parsed, str), f"line {n} is udev syntax{'' if not isinstance(parsed, str) else ': ' + parsed}")
        if not isinstance(parsed, str):
            check(("TAG", None, "+=", "uaccess") in parsed, f"line {n} gives the seat's user the node (TAG+=\"uaccess\")")
            rules.append(parsed)
    # The checker itself refuses what udev refuses.
    for bad in ('KERNEL=="hidraw*" TAG+="uaccess"', 'KERNEL=hidraw*', 'MODE=="0660"', 'ATTRS=="x"', 'KERNEL=="a", '):
        check(isinstance(parse(bad), str), f"the syntax check refuses {bad!r}")
    udevadm = shutil.which("udevadm")
    if udevadm and subprocess.run([udevadm, "verify", "--help"], capture_output=True).returncode == 0:
        r = subprocess.run([udevadm, "verify", str(rules_file)], capture_output=True, text=True)
        check(r.returncode == 0, f"udevadm verify: {r.stdout}{r.stderr}")
    else:
        print("note: this udev has no `udevadm verify` (systemd 253 and later); the syntax check above stands for it")

    def device_of(hidraw_ids=None, ff="0", subsystem="hidraw", kernel="hidraw0"):
        usb = {"idVendor": hidraw_ids[0], "idProduct": hidraw_ids[1]} if hidraw_ids else {}
        input_level = {"capabilities/ff": ff, "name": "a device"} if subsystem == "input" else {}
        return {"SUBSYSTEM": subsystem, "KERNEL": kernel, "ATTRS": [{}, input_level, {"bInterfaceClass": "03"}, usb]}

    def allowed(device) -> bool:
        return any(matches(r, device) for r in rules)

    named = []
    for f in sorted((calibration / "devices").glob("*.toml")):
        usb = tomllib.loads(f.read_text()).get("usb")
        if usb and "vendor_id" in usb:
            named.append((f.stem, f"{usb['vendor_id']:04x}", f"{usb['product_id']:04x}"))
    check(bool(named), f"the calibration files name USB devices: {named}")
    for name, vid, pid in named:
        check(allowed(device_of((vid, pid))), f"{name}'s hidraw node ({vid}:{pid}) is the seat user's")
        check(not allowed(device_of((vid, pid), subsystem="usb", kernel="1-1")),
              f"but not {name}'s USB device itself (libusb stays a root's or a rule's choice)")
    check(not allowed(device_of(("046d", "c52b"))), "another HID device's hidraw node is not given away")
    # A force-feedback bitmap as the kernel prints it: hex words, highest first (input.c, input_print_bitmap).
    check(allowed(device_of(ff="107030000 0", subsystem="input", kernel="event7")), "an event device with force feedback is")
    check(not allowed(device_of(ff="0", subsystem="input", kernel="event3")), "an event device without it is not")
    check(not allowed(device_of(ff="107030000 0", subsystem="input", kernel="js0")), "nor the old joystick interface")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
