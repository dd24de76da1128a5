"""The USB lab guest's root file system: one uncompressed newc cpio archive, cached by its inputs.

It holds busybox-static and its applet links, host binaries with every library `ldd` names for them
(at their host paths, host symlinks mirrored, so the dynamic loader and the host's ld.so.cache find
them as on the host), extra files, the kernel modules the lab needs with their dependencies, and the
lab's /init. Uncompressed because the guest runs under TCG, where decompressing hundreds of MB costs
more than the copy the kernel would save.
"""
from __future__ import annotations

import gzip
import hashlib
import lzma
import os
import re
import shutil
import stat
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

BUSYBOX = Path("/bin/busybox")

# What the lab loads, in this order (each after its own dependencies): the gadget side (configfs,
# FunctionFS and the kernel's HID function), the host side's HID drivers, virtio-9p for the shared
# folders, and last dummy_hcd, whose two instances (dummy_udc.0, dummy_udc.1) let two gadgets be
# plugged at once.
MODULES: list[tuple[str, str]] = [
    ("configfs", ""), ("libcomposite", ""), ("usb_f_fs", ""), ("usb_f_hid", ""),
    ("hid", ""), ("hid_generic", ""), ("usbhid", ""), ("evdev", ""),
    ("virtio_pci", ""), ("9pnet_virtio", ""), ("9p", ""),
    ("dummy_hcd", "num=2"),
]

# Bump when the archive's layout changes in a way the inputs' hash cannot see.
LAYOUT_VERSION = 1


class LabError(Exception):
    """The lab cannot do what it was asked (a missing input file, a failed ldd); says what."""


class Unavailable(LabError):
    """This machine lacks what the lab runs on (QEMU, a kernel image, busybox)."""


def _modname(path: str) -> str:
    name = os.path.basename(path)
    name = re.sub(r"\.ko(\.(xz|zst|gz))?$", "", name)
    return name.replace("-", "_")


def module_order(kernel_version: str, wanted: list[tuple[str, str]]) -> list[tuple[str, str]]:
    """(path relative to /lib/modules/<version>, parameters) in a load order that puts every
    module after its dependencies; modules built into the kernel are left out."""
    base = Path("/lib/modules") / kernel_version
    deps: dict[str, list[str]] = {}
    path_of: dict[str, str] = {}
    for line in (base / "modules.dep").read_text().splitlines():
        mod, _, rest = line.partition(":")
        deps[mod] = rest.split()
        path_of[_modname(mod)] = mod
    builtin = set()
    builtin_file = base / "modules.builtin"
    if builtin_file.exists():
        builtin = {_modname(l) for l in builtin_file.read_text().split()}

    order: list[str] = []
    params: dict[str, str] = {}

    def visit(mod: str) -> None:
        if mod in order:
            return
        for dep in deps.get(mod, []):
            visit(dep)
        order.append(mod)

    for name, par in wanted:
        key = name.replace("-", "_")
        if key in path_of:
            params[path_of[key]] = par
            visit(path_of[key])
        elif key not in builtin:
            raise LabError(f"kernel {kernel_version} has no module {name} (not in modules.dep, "
                           f"not built in)")
    return [(m, params.get(m, "")) for m in order]


def ldd_closure(binary: Path) -> list[str]:
    """The libraries and dynamic loader `ldd` names for a binary; [] for a static one."""
    proc = subprocess.run(["ldd", str(binary)], capture_output=True, text=True)
    if proc.returncode != 0:
        if "not a dynamic executable" in proc.stdout + proc.stderr:
            return []
        raise LabError(f"ldd {binary} failed: {proc.stderr.strip() or proc.stdout.strip()}")
    libs = []
    for line in proc.stdout.splitlines():
        line = line.strip()
        if "not found" in line:
            raise LabError(f"{binary}: a library is missing on this machine: {line}")
        m = re.match(r"\S+ => (/\S+) \(", line) or re.match(r"(/\S+) \(", line)
        if m:
            libs.append(m.group(1))
    return libs


@dataclass
class Spec:
    """What goes into the archive. files: guest path -> host path (its content) or bytes."""
    kernel_version: str
    binaries: list[Path] = field(default_factory=list)
    files: dict[str, Path | bytes] = field(default_factory=dict)
    modules: list[tuple[str, str]] = field(default_factory=lambda: list(MODULES))
    # A module loaded from this file instead of the kernel's own (name -> .ko): the lab's dummy_hcd.
    module_files: dict[str, Path] = field(default_factory=dict)
    # The binaries' DWARF goes (objcopy --strip-debug; code and symbols stay): a -g build of
    # sandpaper is 214 MB, 7 MB without, and every MB costs boot time under TCG.
    strip_debug: bool = True


class _Cpio:
    """A newc ("070701") archive writer, the format the kernel's initramfs unpacker reads."""

    def __init__(self, out):
        self.out = out
        self.ino = 1
        self.dirs: set[str] = {""}

    def _header(self, name: str, mode: int, size: int, nlink: int = 1, rdev=(0, 0), mtime=0):
        raw = name.encode() + b"\0"
        fields = [self.ino, mode, 0, 0, nlink, mtime, size, 0, 0, rdev[0], rdev[1], len(raw), 0]
        self.ino += 1
        hdr = b"070701" + b"".join(b"%08X" % f for f in fields) + raw
        self.out.write(hdr + b"\0" * (-len(hdr) % 4))

    def _pad(self, size: int) -> None:
        self.out.write(b"\0" * (-size % 4))

    def parents(self, path: str) -> None:
        parent = os.path.dirname(path)
        if parent not in self.dirs:
            self.directory(parent)

    def directory(self, path: str, mode: int = 0o755) -> None:
        if path in self.dirs:
            return
        self.parents(path)
        self._header(path, stat.S_IFDIR | mode, 0, nlink=2)
        self.dirs.add(path)

    def symlink(self, path: str, target: str) -> None:
        self.parents(path)
        data = target.encode()
        self._header(path, stat.S_IFLNK | 0o777, len(data))
        self.out.write(data)
        self._pad(len(data))

    def chardev(self, path: str, major: int, minor: int, mode: int = 0o600) -> None:
        self.parents(path)
        self._header(path, stat.S_IFCHR | mode, 0, rdev=(major, minor))

    def data(self, path: str, data: bytes, mode: int = 0o644) -> None:
        self.parents(path)
        self._header(path, stat.S_IFREG | mode, len(data))
        self.out.write(data)
        self._pad(len(data))

    def host_file(self, path: str, host: Path, mode: int | None = None) -> None:
        st = os.stat(host)
        self.parents(path)
        self._header(path, stat.S_IFREG | (mode if mode is not None else st.st_mode & 0o7777),
                     st.st_size)
        with open(host, "rb") as f:
            shutil.copyfileobj(f, self.out, 1 << 20)
        self._pad(st.st_size)

    def trailer(self) -> None:
        self._header("TRAILER!!!", 0, 0, nlink=1)
        self.out.write(b"\0" * (-self.out.tell() % 512))


class _Tree:
    """The archive's entries keyed by guest path (without the leading /), laid out as on the host:
    a path under a host directory symlink (/lib -> usr/lib) is stored at its real place and the
    symlink stored too; a host file that is a symlink is stored as that symlink plus its target."""

    def __init__(self):
        self.entries: dict[str, tuple] = {}

    def _real_parent(self, path: str) -> str:
        """The path with its directories resolved as on the host, storing each symlink met."""
        parts = path.strip("/").split("/")
        real = ""
        for part in parts[:-1]:
            cand = f"{real}/{part}"
            if os.path.islink(cand):
                target = os.readlink(cand)
                self.entries.setdefault(cand.lstrip("/"), ("symlink", target))
                cand = os.path.realpath(cand)
            real = cand
        return f"{real}/{parts[-1]}".lstrip("/")

    def add_mirrored(self, host_path: str) -> None:
        """A host file at its own path, following (and storing) file symlinks to the real file."""
        seen = set()
        path = host_path
        while True:
            guest = self._real_parent(path)
            if guest in seen:
                raise LabError(f"symlink loop at {host_path}")
            seen.add(guest)
            host = "/" + guest
            if os.path.islink(host):
                target = os.readlink(host)
                self.entries.setdefault(guest, ("symlink", target))
                path = os.path.join(os.path.dirname(host), target)
                continue
            if not os.path.isfile(host):
                raise LabError(f"{host_path}: not a file")
            self.entries.setdefault(guest, ("file", Path(host), None))
            return

    def add(self, guest_path: str, kind: tuple, replace: bool = False) -> None:
        guest = self._real_parent(guest_path) if guest_path.startswith("/") else guest_path
        if replace or guest not in self.entries:
            self.entries[guest] = kind


def _module_bytes(path: Path) -> bytes:
    name = path.name
    if name.endswith(".ko.xz"):
        return lzma.decompress(path.read_bytes())
    if name.endswith(".ko.gz"):
        return gzip.decompress(path.read_bytes())
    if name.endswith(".ko.zst"):
        if not shutil.which("zstd"):
            raise LabError(f"{path} is zstd-compressed and zstd is not installed")
        return subprocess.run(["zstd", "-dc", str(path)], check=True, capture_output=True).stdout
    return path.read_bytes()


def _plan(spec: Spec) -> tuple[_Tree, list[str]]:
    """Every entry of the archive, and the lines of /lab/modules (guest path and parameters)."""
    if not BUSYBOX.is_file():
        raise Unavailable(f"{BUSYBOX} is missing: install busybox-static")
    tree = _Tree()
    # Highest priority first: entries added earlier win over later ones at the same path.
    for guest, src in spec.files.items():
        if not guest.startswith("/"):
            raise LabError(f"guest path {guest!r} is not absolute")
        if isinstance(src, bytes):
            tree.add(guest, ("bytes", src, 0o755 if src.startswith(b"#!") else 0o644))
        else:
            if not Path(src).is_file():
                raise LabError(f"{src}: no such file")
            tree.add(guest, ("file", Path(src), None))
    for binary in spec.binaries:
        binary = Path(binary).absolute()
        if not binary.is_file():
            raise LabError(f"{binary}: no such binary")
        tree.add_mirrored(str(binary))
        real = os.path.realpath(binary)
        if spec.strip_debug and shutil.which("objcopy"):
            tree.entries[real.lstrip("/")] = ("stripped", Path(real), None)
        for lib in ldd_closure(binary):
            tree.add_mirrored(lib)
    if spec.binaries and os.path.exists("/etc/ld.so.cache"):
        # Libraries found through /etc/ld.so.conf.d (outside the loader's default directories)
        # resolve in the guest only with the host's cache; its paths are the ones ldd printed.
        tree.add("/etc/ld.so.cache", ("file", Path("/etc/ld.so.cache"), None))
    tree.add_mirrored(str(BUSYBOX))
    applets = subprocess.run([str(BUSYBOX), "--list-full"], capture_output=True, text=True,
                             check=True).stdout.split()
    for applet in applets:
        if applet.strip("/") in ("linuxrc", "bin/busybox"):
            continue
        tree.add("/" + applet, ("symlink", "/bin/busybox"))

    modules = []
    mod_base = Path("/lib/modules") / spec.kernel_version
    for rel, params in module_order(spec.kernel_version, spec.modules):
        guest = re.sub(r"\.(xz|zst|gz)$", "", f"/lib/modules/{spec.kernel_version}/{rel}")
        tree.add(guest, ("module", spec.module_files.get(_modname(rel), mod_base / rel)))
        modules.append(f"{guest} {params}".rstrip())
    return tree, modules


def _key(spec: Spec, tree: _Tree, modules: list[str]) -> str:
    h = hashlib.sha256()
    h.update(f"layout {LAYOUT_VERSION} {spec.kernel_version}\n".encode())
    h.update(Path(__file__).read_bytes())
    for line in modules:
        h.update(f"module {line}\n".encode())
    for guest in sorted(tree.entries):
        entry = tree.entries[guest]
        h.update(f"{guest} {entry[0]}\n".encode())
        if entry[0] in ("file", "module", "stripped"):
            st = os.stat(entry[1])
            h.update(f"{entry[1]} {st.st_size} {st.st_mtime_ns} {st.st_mode}\n".encode())
        elif entry[0] == "bytes":
            h.update(hashlib.sha256(entry[1]).digest())
        else:
            h.update(entry[1].encode())
    return h.hexdigest()[:20]


def _strip_debug(host: Path, into: Path) -> Path:
    out = into / f"stripped-{os.getpid()}-{host.name}"
    proc = subprocess.run(["objcopy", "--strip-debug", str(host), str(out)], capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise LabError(f"objcopy --strip-debug {host}: {proc.stderr.strip()}")
    return out


def _write(path: Path, tree: _Tree, modules: list[str]) -> None:
    tmp = path.with_suffix(f".{os.getpid()}.tmp")  # two labs may build at once
    with open(tmp, "wb", buffering=1 << 20) as out:
        cpio = _Cpio(out)
        for d in ("dev", "proc", "sys", "tmp", "run", "root", "out", "in", "lab", "mnt"):
            cpio.directory(d)
        # The kernel gives /init this console before any devtmpfs exists.
        cpio.chardev("dev/console", 5, 1)
        cpio.data("etc/passwd", b"root:x:0:0:root:/root:/bin/sh\n")
        cpio.data("etc/group", b"root:x:0:\n")
        cpio.data("lab/modules", ("\n".join(modules) + "\n").encode())
        # Directories before what is in them, and a symlinked directory (bin -> usr/bin) before
        # anything could try to create the same name as a real directory.
        for guest in sorted(tree.entries, key=lambda g: (tree.entries[g][0] != "symlink", g)):
            entry = tree.entries[guest]
            if entry[0] == "symlink":
                cpio.symlink(guest, entry[1])
            elif entry[0] == "file":
                cpio.host_file(guest, entry[1], entry[2])
            elif entry[0] == "bytes":
                cpio.data(guest, entry[1], entry[2])
            elif entry[0] == "stripped":
                lean = _strip_debug(entry[1], path.parent)
                try:
                    cpio.host_file(guest, lean, os.stat(entry[1]).st_mode & 0o7777)
                finally:
                    lean.unlink()
            elif entry[0] == "module":
                cpio.data(guest, _module_bytes(entry[1]))
        cpio.trailer()
    os.replace(tmp, path)


def build(spec: Spec, cache_dir: Path, keep: int = 4) -> tuple[Path, bool, float]:
    """The archive for spec, from cache_dir when its inputs (paths, sizes, mtimes) are unchanged.
    Returns (path, whether it was built now, seconds spent). Keeps the `keep` newest archives."""
    t0 = time.monotonic()
    tree, modules = _plan(spec)
    cache_dir.mkdir(parents=True, exist_ok=True)
    path = cache_dir / f"initramfs-{_key(spec, tree, modules)}.cpio"
    built = not path.exists()
    if built:
        _write(path, tree, modules)
    else:
        os.utime(path)  # the age the eviction below goes by
    # Each archive is the size of the binaries' library closure (hundreds of MB with
    # OpenImageIO): old ones go.
    old = sorted(cache_dir.glob("initramfs-*.cpio"), key=lambda p: p.stat().st_mtime, reverse=True)
    for stale in old[keep:]:
        stale.unlink(missing_ok=True)
    return path, built, time.monotonic() - t0
