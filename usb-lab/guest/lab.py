#!/usr/bin/env python3
"""The USB lab: boots a QEMU guest with a real Linux USB stack (dummy_hcd, configfs gadgets,
FunctionFS, usbhid) and runs a scenario script in it.

  lab.py run --script S [--binary B]... [--file GUEST:HOST]... [--out DIR] [--in DIR] [--timeout S]
  lab.py selftest [--binary B]...
  lab.py build [--binary B]... [--file GUEST:HOST]...     (the initramfs only; prints its path)
  lab.py info

In the guest: host binaries (and their `ldd` closure) and --file files sit in the initramfs at their
paths; the scenario is /lab/scenario.sh, run by busybox sh as root with LAB_GADGET=/lab/gadget.sh to
source, LAB_OUT=/out (the host's --out folder, read-write over virtio-9p) and LAB_IN=/in (the
host's --in folder, read-only). The console streams to standard output; a line
"lab: scenario started ..." (standard error) says how long the boot took. The guest has 2 CPUs under
TCG (KVM hangs or aborts inside these VMs); its kernel is Debian's installed one, unpacked once to a
PVH vmlinux. The initramfs and that vmlinux are cached in --cache (default build-usb-lab/), the
initramfs keyed by its inputs' paths, sizes and mtimes.

Exit status: the scenario's own; 124 when the host-side timeout killed QEMU; 125 when the guest
ended without saying how the scenario ended (a kernel panic, say); 77 when the lab cannot run on
this machine (no QEMU, kernel image or busybox: tools/install-deps.sh installs them); 3 when the
lab could not do what it was asked (a missing file, say); 2: bad usage.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import selectors
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import initramfs  # noqa: E402  (beside this file)
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bus"))
import dummy_hcd_module  # noqa: E402  (usb-lab/bus/)
import kernel  # noqa: E402
from initramfs import LabError, Spec, Unavailable  # noqa: E402

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
DEFAULT_CACHE = REPO / "build-usb-lab"
UNAVAILABLE = 77
QEMU_NICE = -19  # the guest's priority over the machine's other work, where allowed (run() says why)
FAILED = 3
TIMED_OUT = 124
NO_STATUS = 125
START_MARK = "LAB-SCENARIO-START"
STATUS_MARK = re.compile(r"LAB-EXIT-STATUS (\d+)")


@dataclass
class Machine:
    qemu: str
    kernel: Path
    kernel_version: str


def find_machine() -> Machine:
    """QEMU and the newest kernel image whose modules are installed; LabError names what is missing."""
    qemu = shutil.which("qemu-system-x86_64")
    missing = []
    if not qemu:
        missing.append("qemu-system-x86_64 (Debian package qemu-system-x86)")
    kernels = kernel.installed()
    if not kernels:
        missing.append("a kernel image /boot/vmlinuz-* with its /lib/modules (linux-image-amd64)")
    if not initramfs.BUSYBOX.is_file():
        missing.append(f"{initramfs.BUSYBOX} (busybox-static)")
    if missing:
        raise Unavailable("the USB lab cannot run here; missing: " + "; ".join(missing)
                       + ". tools/install-deps.sh installs them.")
    version, image = kernels[-1]
    return Machine(qemu, image, version)


def image_spec(machine: Machine, script: bytes, binaries: list[Path] = (),
               files: dict[str, Path | bytes] | None = None, strip_debug: bool = True) -> Spec:
    """The guest's files: the lab's own (/init, /lab/gadget.sh, the scenario) win over the caller's."""
    all_files: dict[str, Path | bytes] = {
        "/init": (HERE / "init.sh").read_bytes(),
        "/lab/gadget.sh": (HERE / "gadget.sh").read_bytes(),
        "/lab/scenario.sh": script,
    }
    if binaries:
        listed = "".join(f"{Path(b).absolute()}\n" for b in binaries)
        all_files["/lab/binaries"] = listed.encode()
    for guest, host in (files or {}).items():
        all_files.setdefault(guest, host)
    return Spec(machine.kernel_version, [Path(b) for b in binaries], all_files,
                strip_debug=strip_debug)


@dataclass
class Result:
    status: int                      # the scenario's exit status, or TIMED_OUT / NO_STATUS
    wall: float                      # seconds from starting QEMU to its end
    boot: float | None = None        # seconds from starting QEMU to the scenario's first line
    guest_uptime: float | None = None  # the guest's own uptime at that moment
    console: list[str] = field(default_factory=list)
    bus: str = "stock"               # the bus the guest had: "1ms", "stock", or "stock: why not 1ms"


def boot(machine: Machine, initrd: Path, *, out_dir: Path | None = None, in_dir: Path | None = None,
         timeout: float = 300, memory_mb: int | None = None, smp: int = 2, accel: str = "tcg",
         kernel_log: bool = False, append: str = "", echo=None,
         kernel_path: Path | None = None) -> Result:
    """Boots the guest on initrd (and kernel_path, by default the machine's image), passes each
    console line to echo, and returns how it ended."""
    if memory_mb is None:
        # The initramfs lives twice for a moment (the loaded image and the unpacked rootfs).
        memory_mb = max(1024, 2 * initrd.stat().st_size // (1 << 20) + 768)
    # The crypto self-tests cost most of a second of TCG boot and test nothing the lab uses.
    cmdline = ["console=ttyS0", "panic=-1", "oops=panic", "mitigations=off", "cryptomgr.notests",
               "loglevel=7" if kernel_log else "quiet"]
    # qemu64, not max: max offers ERMS, and the kernel's and glibc's `rep movsb` copies then run
    # a byte per step under TCG (unpacking a 350 MB initramfs: 15 s to the scenario, not 8).
    args = [machine.qemu, "-nodefaults", "-no-user-config", "-display", "none",
            "-machine", "pc", "-cpu", "qemu64", "-m", str(memory_mb), "-smp", str(smp),
            "-serial", "stdio", "-no-reboot",
            "-kernel", str(kernel_path or machine.kernel), "-initrd", str(initrd)]
    if accel == "tcg":
        # MTTCG: one host thread per guest CPU (the device program and the host programs overlap).
        args += ["-accel", "tcg,thread=multi"]
    else:
        args += ["-accel", accel]
    for tag, path, readonly, flag in (("labout", out_dir, False, "lab.out=1"),
                                      ("labin", in_dir, True, "lab.in=1")):
        if path is None:
            continue
        Path(path).mkdir(parents=True, exist_ok=True)
        args += ["-virtfs", f"local,path={Path(path).absolute()},mount_tag={tag},"
                            f"security_model=none{',readonly=on' if readonly else ''}"]
        cmdline.append(flag)
    # The guest prints what each process is doing shortly before the host gives up on it (init.sh);
    # guest time runs at host time under TCG, and the margin covers the boot and the report.
    if timeout > 60:
        cmdline.append(f"lab.report_after={int(timeout - 40)}")
    if append:
        cmdline.append(append)
    args += ["-append", " ".join(cmdline)]
    echo = echo or (lambda line: print(line, flush=True))

    # The guest stands for a PC of its own: its clock should measure the software under test, not
    # whatever else this machine runs. Under TCG every guest thread is QEMU's, and `stress-ng --cpu 4`
    # beside it on two cores made the guest's studio latency three times its quiet figure. Where
    # this process may (root), QEMU runs at a higher priority (nice -19) than the machine's other work.
    def _higher_priority():
        try:
            os.nice(QEMU_NICE)
        except PermissionError:
            pass

    if os.geteuid() != 0:
        echo(f"lab: QEMU runs at normal priority (not root: nice {QEMU_NICE} refused); a loaded machine slows the guest")
    t0 = time.monotonic()
    proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, preexec_fn=_higher_priority)
    result = Result(status=NO_STATUS, wall=0.0)
    sel = selectors.DefaultSelector()
    sel.register(proc.stdout, selectors.EVENT_READ)
    pending = b""
    deadline = t0 + timeout

    def line_seen(raw: bytes) -> None:
        line = raw.decode("utf-8", "replace").rstrip("\r")
        result.console.append(line)
        if line.startswith(START_MARK) and result.boot is None:
            result.boot = time.monotonic() - t0
            m = re.search(r"uptime=([\d.]+)", line)
            result.guest_uptime = float(m.group(1)) if m else None
            print(f"lab: scenario started {result.boot:.1f} s after QEMU did "
                  f"(guest uptime {result.guest_uptime} s)", file=sys.stderr, flush=True)
            return
        m = STATUS_MARK.search(line)
        if m:
            result.status = int(m.group(1))
            return
        echo(line)

    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                print(f"lab: timed out after {timeout:.0f} s; killing QEMU", file=sys.stderr,
                      flush=True)
                proc.kill()
                result.status = TIMED_OUT
                break
            if not sel.select(min(left, 1.0)):
                continue
            chunk = os.read(proc.stdout.fileno(), 1 << 16)
            if not chunk:
                break
            pending += chunk
            *lines, pending = pending.split(b"\n")
            for raw in lines:
                line_seen(raw)
        if pending:
            line_seen(pending)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        sel.close()
    result.wall = time.monotonic() - t0
    if result.status == NO_STATUS and result.boot is None:
        print("lab: the guest ended before the scenario started (see the console above)",
              file=sys.stderr)
    elif result.status == NO_STATUS:
        print("lab: the guest ended without the scenario's exit status", file=sys.stderr)
    return result


# The lab's buses: "stock", the guest kernel's own dummy_hcd (Debian 6.1.192: 125 us frames at every
# speed, bInterval not honoured); "1ms", the lab's build of it with a real bus's frames
# (usb-lab/bus/: 1 ms at full speed, an interrupt endpoint held to its bInterval).
BUSES = ("stock", "1ms")


def bus_module(machine: Machine, bus: str, cache_dir: Path) -> tuple[dict[str, Path], str]:
    """The module files for `bus` and what the guest is told of it (/lab/bus): "1ms", or "stock",
    or "stock: WHY" when the 1 ms bus was asked for and could not be built."""
    if bus not in BUSES:
        raise LabError(f"unknown bus {bus!r} (one of {', '.join(BUSES)})")
    if bus == "stock":
        return {}, "stock"
    module, why = dummy_hcd_module.build(machine.kernel_version, Path(cache_dir))
    if module is None:
        print(f"lab: the 1 ms bus cannot be built, so the guest runs the stock dummy_hcd: {why}",
              file=sys.stderr, flush=True)
        return {}, "stock: " + why.replace("\n", " ").replace('"', "'")
    return {"dummy_hcd": module}, "1ms"


def run(script: bytes, *, binaries: list[Path] = (), files: dict[str, Path | bytes] | None = None,
        out_dir: Path | None = None, in_dir: Path | None = None, timeout: float = 300,
        cache_dir: Path = DEFAULT_CACHE, strip_debug: bool = True, bus: str = "1ms", **boot_args) -> Result:
    """Builds (or reuses) the initramfs and boots it with the scenario on `bus` (BUSES); raises
    LabError when the lab cannot run here. The guest finds which bus it has in /lab/bus."""
    machine = find_machine()
    module_files, bus_line = bus_module(machine, bus, Path(cache_dir))
    files = dict(files or {})
    files["/lab/bus"] = (bus_line + "\n").encode()
    spec = image_spec(machine, script, binaries, files, strip_debug)
    spec.module_files = module_files
    initrd, built, secs = initramfs.build(spec, Path(cache_dir))
    size = initrd.stat().st_size / (1 << 20)
    print(f"lab: initramfs {initrd.name}, {size:.0f} MB, "
          f"{'built in' if built else 'cached, checked in'} {secs:.1f} s", file=sys.stderr,
          flush=True)
    vmlinux = kernel.bootable(machine.kernel, Path(cache_dir))
    result = boot(machine, initrd, out_dir=out_dir, in_dir=in_dir, timeout=timeout,
                  kernel_path=vmlinux, **boot_args)
    result.bus = bus_line
    if out_dir is not None:
        (Path(out_dir) / "console.log").write_text("\n".join(result.console) + "\n")
    print(f"lab: scenario exit status {result.status}; QEMU ran {result.wall:.1f} s",
          file=sys.stderr, flush=True)
    return result


def _files(pairs: list[str]) -> dict[str, Path]:
    files = {}
    for pair in pairs:
        guest, sep, host = pair.partition(":")
        if not sep or not guest.startswith("/") or not host:
            raise SystemExit(f"lab: --file wants GUEST:HOST with an absolute guest path: {pair!r}")
        files[guest] = Path(host)
    return files


def _selftest(args) -> int:
    t0 = time.monotonic()
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="usb-lab-selftest-"))
    # /usr/bin/cmp: a dynamically linked host binary that is always there (diffutils), so the
    # selftest shows the ldd closure and loader work even without the caller's binaries.
    binaries = [Path("/usr/bin/cmp")] + [Path(b) for b in args.binary]
    result = run((HERE / "selftest.sh").read_bytes(), binaries=binaries, out_dir=out,
                 timeout=args.timeout, cache_dir=Path(args.cache), smp=args.smp,
                 accel=args.accel, kernel_log=args.kernel_log, strip_debug=not args.keep_debug)
    report = out / "selftest.json"
    wall = time.monotonic() - t0
    ok = result.status == 0 and report.exists()
    if report.exists():
        data = json.loads(report.read_text())
        ok = ok and data.get("speed") == "12" and data.get("hidraw", "").startswith("hidraw")
    boot = f"{result.boot:.1f} s" if result.boot is not None else "never"
    keep = args.out or not ok
    print(f"selftest: {'PASS' if ok else 'FAIL'} (boot to scenario {boot}, wall {wall:.1f} s"
          f"{f'; report and console in {out}' if keep else ''})", flush=True)
    if not keep:
        shutil.rmtree(out, ignore_errors=True)
    return 0 if ok else (result.status or 1)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="lab.py", description=__doc__.split("\n\n")[0],
        epilog=__doc__.split("\n\n", 1)[1], formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)

    def common(p, with_boot=True):
        p.add_argument("--binary", action="append", default=[], metavar="PATH",
                       help="a host binary to put in the guest at its path, with its ldd closure")
        p.add_argument("--cache", default=str(DEFAULT_CACHE), metavar="DIR",
                       help="where initramfs images are kept (default: %(default)s)")
        p.add_argument("--keep-debug", action="store_true",
                       help="keep the binaries' debug sections (default: objcopy --strip-debug)")
        if with_boot:
            p.add_argument("--timeout", type=float, default=300, metavar="S",
                           help="host-side limit for the whole boot (default: %(default)s)")
            p.add_argument("--smp", type=int, default=2, help="guest CPUs (default: 2)")
            p.add_argument("--accel", default="tcg",
                           help="QEMU accelerator (default: tcg; KVM aborts in these VMs)")
            p.add_argument("--kernel-log", action="store_true",
                           help="the kernel's messages on the console too (default: quiet)")

    p_run = sub.add_parser("run", help="boot the guest and run a scenario script")
    common(p_run)
    p_run.add_argument("--script", required=True, help="the scenario (busybox sh)")
    p_run.add_argument("--file", action="append", default=[], metavar="GUEST:HOST",
                       help="a host file put in the initramfs at the guest path")
    p_run.add_argument("--out", metavar="DIR", help="host folder shared read-write at /out")
    p_run.add_argument("--in", dest="in_dir", metavar="DIR",
                       help="host folder shared read-only at /in")
    p_run.add_argument("--append", default="", help="more kernel command line")

    p_self = sub.add_parser("selftest", help="plug a usb_f_hid joystick into dummy_udc.1 and check "
                                             "the host side enumerated it (exit 0: pass)")
    common(p_self)
    p_self.add_argument("--out", metavar="DIR", help="keep selftest.json and console.log here")
    p_self.set_defaults(timeout=180)

    p_build = sub.add_parser("build", help="build the initramfs only and print its path")
    common(p_build, with_boot=False)
    p_build.add_argument("--file", action="append", default=[], metavar="GUEST:HOST")
    p_build.add_argument("--script", help="the scenario (default: none)")

    sub.add_parser("info", help="which QEMU and kernel the lab would use")
    args = parser.parse_args(argv)

    try:
        if args.command == "info":
            m = find_machine()
            print(f"qemu: {m.qemu}\nkernel: {m.kernel} ({m.kernel_version})\n"
                  f"busybox: {initramfs.BUSYBOX}")
            return 0
        if args.command == "selftest":
            return _selftest(args)
        if args.command == "build":
            m = find_machine()
            script = Path(args.script).read_bytes() if args.script else b"true\n"
            spec = image_spec(m, script, [Path(b) for b in args.binary], _files(args.file),
                              not args.keep_debug)
            path, built, secs = initramfs.build(spec, Path(args.cache))
            print(f"{path} {path.stat().st_size} bytes, {'built' if built else 'cached'} "
                  f"in {secs:.2f} s")
            return 0
        result = run(Path(args.script).read_bytes(), binaries=[Path(b) for b in args.binary],
                     files=_files(args.file), out_dir=Path(args.out) if args.out else None,
                     in_dir=Path(args.in_dir) if args.in_dir else None, timeout=args.timeout,
                     cache_dir=Path(args.cache), smp=args.smp, accel=args.accel,
                     kernel_log=args.kernel_log, append=args.append,
                     strip_debug=not args.keep_debug)
        return result.status
    except Unavailable as e:
        print(f"lab: {e}", file=sys.stderr)
        return UNAVAILABLE
    except LabError as e:
        print(f"lab: {e}", file=sys.stderr)
        return FAILED


if __name__ == "__main__":
    sys.exit(main())
