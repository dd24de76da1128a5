"""The USB lab guest's kernel: Debian's installed image, booted as an uncompressed ELF when it can be.

Under TCG the kernel's own decompressor takes about 6 s of a 12 s boot (Debian's bzImage is
xz-compressed). QEMU boots an uncompressed vmlinux directly through its PVH entry point
(CONFIG_PVH), so the payload is unpacked once on the host and cached beside the initramfs images.
"""
from __future__ import annotations

import gzip
import io
import lzma
import os
import shutil
import struct
import subprocess
from pathlib import Path

# Where each compressor's stream starts inside a bzImage.
_MAGICS = [(b"\xfd7zXZ\x00", "xz"), (b"\x28\xb5\x2f\xfd", "zstd"), (b"\x1f\x8b\x08", "gzip")]
_XEN_ELFNOTE_PHYS32_ENTRY = 18


def installed() -> list[tuple[str, Path]]:
    """(version, image) of every /boot/vmlinuz-* whose /lib/modules/<version> exists, newest
    last."""
    found = []
    for image in Path("/boot").glob("vmlinuz-*"):
        version = image.name[len("vmlinuz-"):]
        if (Path("/lib/modules") / version / "modules.dep").exists() and os.access(image, os.R_OK):
            found.append((image.stat().st_mtime, version, image))
    return [(v, i) for _, v, i in sorted(found)]


def _has_pvh_note(elf: bytes) -> bool:
    if elf[:4] != b"\x7fELF" or elf[4] != 2:  # 64-bit ELF only
        return False
    phoff, = struct.unpack_from("<Q", elf, 0x20)
    phentsize, phnum = struct.unpack_from("<HH", elf, 0x36)
    for i in range(phnum):
        p_type, _, p_offset, _, _, p_filesz = struct.unpack_from("<IIQQQQ", elf, phoff + i * phentsize)
        if p_type != 4:  # PT_NOTE
            continue
        pos, end = p_offset, p_offset + p_filesz
        while pos + 12 <= end:
            namesz, descsz, ntype = struct.unpack_from("<III", elf, pos)
            name = elf[pos + 12:pos + 12 + namesz].rstrip(b"\0")
            if name == b"Xen" and ntype == _XEN_ELFNOTE_PHYS32_ENTRY:
                return True
            pos += 12 + (namesz + 3) // 4 * 4 + (descsz + 3) // 4 * 4
    return False


def _payload(image: bytes) -> bytes | None:
    for magic, kind in _MAGICS:
        at = image.find(magic)
        while at >= 0:
            try:
                if kind == "xz":
                    out = lzma.LZMADecompressor(format=lzma.FORMAT_XZ).decompress(image[at:])
                elif kind == "gzip":
                    out = gzip.GzipFile(fileobj=io.BytesIO(image[at:])).read()
                elif shutil.which("zstd"):
                    out = subprocess.run(["zstd", "-dc"], input=image[at:], capture_output=True).stdout
                else:
                    out = b""
            except (lzma.LZMAError, OSError, EOFError):
                out = b""
            if out[:4] == b"\x7fELF":
                return out
            at = image.find(magic, at + 1)
    return None


def bootable(image: Path, cache_dir: Path) -> Path:
    """The uncompressed PVH vmlinux for image, cached in cache_dir; the image itself when its
    payload cannot be unpacked here or has no PVH entry point."""
    st = image.stat()
    cached = cache_dir / f"{image.name.replace('vmlinuz', 'vmlinux')}-{st.st_size}-{st.st_mtime_ns}"
    marker = cache_dir / f"{cached.name}.nopvh"
    if cached.exists():
        return cached
    if marker.exists():
        return image
    cache_dir.mkdir(parents=True, exist_ok=True)
    elf = _payload(image.read_bytes())
    if elf is None or not _has_pvh_note(elf):
        marker.touch()
        return image
    tmp = cache_dir / f"{cached.name}.{os.getpid()}.tmp"  # two labs may unpack at once
    tmp.write_bytes(elf)
    os.replace(tmp, cached)
    return cached
