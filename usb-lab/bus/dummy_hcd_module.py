"""The lab's own dummy_hcd module: Debian's source of the guest kernel's release
(/usr/src/linux-source-X.Y.tar.xz, package linux-source-X.Y), changed by patch_dummy_hcd.py to run
real full-speed frames, built against the guest kernel's headers (/lib/modules/VERSION/build,
package linux-headers-amd64) at the time the lab builds its guest, and cached beside the initramfs.
Nothing of the kernel is kept in the repository. docs/USB_PID.md "The lab's bus"."""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
PATCH = HERE / "patch_dummy_hcd.py"
MEMBER = "drivers/usb/gadget/udc/dummy_hcd.c"


def _source_tarball(kernel_version: str) -> Path | None:
    m = re.match(r"(\d+\.\d+)", kernel_version)
    if not m:
        return None
    p = Path(f"/usr/src/linux-source-{m.group(1)}.tar.xz")
    return p if p.is_file() else None


def build(kernel_version: str, cache_dir: Path) -> tuple[Path | None, str]:
    """(the patched module, "") or (None, why it could not be made: the lab then loads the stock one)."""
    headers = Path("/lib/modules") / kernel_version / "build"
    tarball = _source_tarball(kernel_version)
    missing = []
    if tarball is None:
        release = ".".join(kernel_version.split("-")[0].split(".")[:2])
        missing.append(f"the kernel's source (/usr/src/linux-source-{release}.tar.xz, Debian package linux-source-{release})")
    if not (headers / "Makefile").is_file():
        missing.append(f"the headers of kernel {kernel_version} ({headers}, Debian package linux-headers-amd64)")
    if missing:
        return None, "missing " + " and ".join(missing) + "; tools/install-deps.sh installs them"
    st = tarball.stat()
    key = hashlib.sha256(f"{kernel_version} {tarball} {st.st_size} {st.st_mtime_ns}\n".encode()
                         + PATCH.read_bytes() + Path(__file__).read_bytes()).hexdigest()[:20]
    out = Path(cache_dir) / f"dummy_hcd-{key}.ko"
    if out.is_file():
        return out, ""
    Path(cache_dir).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="usb-lab-dummy-hcd-") as tmp:
        work = Path(tmp)
        prefix = tarball.name[: -len(".tar.xz")]
        r = subprocess.run(["tar", "-xJf", str(tarball), "-C", str(work), f"{prefix}/{MEMBER}"],
                           capture_output=True, text=True)
        source = work / prefix / MEMBER
        if r.returncode != 0 or not source.is_file():
            return None, f"{tarball} has no {MEMBER}: {r.stderr.strip()[-300:]}"
        mod = work / "mod"
        mod.mkdir()
        r = subprocess.run([sys.executable, str(PATCH), str(source), str(mod / "dummy_hcd.c")],
                           capture_output=True, text=True)
        if r.returncode != 0:
            return None, (r.stderr or r.stdout).strip()
        (mod / "Kbuild").write_text("obj-m := dummy_hcd.o\n")
        r = subprocess.run(["make", "-C", str(headers), f"M={mod}", "modules"], capture_output=True, text=True)
        built = mod / "dummy_hcd.ko"
        if r.returncode != 0 or not built.is_file():
            tail = "\n".join((r.stdout + r.stderr).strip().splitlines()[-8:])
            return None, f"building dummy_hcd against {headers} failed:\n{tail}"
        partial = out.with_suffix(".tmp")
        shutil.copyfile(built, partial)
        os.replace(partial, out)
    return out, ""
