"""Runs one of the lab's scenarios (usb-lab/scenarios/NAME.sh) in the guest, with the build's
programs (sandpaper, sandpaper-play, sandpaper-lab-device, sandpaper-lab-post, sandpaper-lab-writes) and the source tree's data (the build
tree's programs read calibration/ and library/ from the source tree, so they sit at the same paths
in the guest). Used by tools/usb-lab/run and tests/usb-lab/lab_test.py."""
from __future__ import annotations

import os
import shlex
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE / "guest"))
import lab  # noqa: E402
from initramfs import LabError, Unavailable  # noqa: E402,F401  (re-exported for callers)

PROGRAMS = ("sandpaper", "sandpaper-play", "sandpaper-lab-device", "sandpaper-lab-post", "sandpaper-lab-writes")
DATA_DIRS = ("calibration", "library", "examples")


def programs(build: Path) -> dict[str, Path]:
    found = {name: (build / "bin" / name).resolve() for name in PROGRAMS}
    missing = [str(p) for p in found.values() if not p.is_file()]
    if missing:
        raise LabError("not built: " + ", ".join(missing)
                       + " (build with the README's commands, or pass --build DIR)")
    return found


def data_files() -> dict[str, Path]:
    files = {}
    for d in DATA_DIRS:
        for p in sorted((REPO / d).rglob("*")):
            if p.is_file():
                files[str(p)] = p
    return files


def run(name: str, build: Path, out_dir: Path, params: dict[str, str] | None = None,
        files: dict[str, Path | bytes] | None = None, timeout: float = 240, echo=None,
        bus: str | None = None) -> lab.Result:
    """Boots the guest on scenario `name` with `params` exported to it; its /out is `out_dir`; the
    USB bus is `bus` (lab.BUSES; default $SANDPAPER_LAB_BUS, else the lab's 1 ms bus; the guest's
    /lab/bus says which it got)."""
    bus = bus or os.environ.get("SANDPAPER_LAB_BUS") or "1ms"
    progs = programs(build)
    env = {"SANDPAPER": str(progs["sandpaper"]), "SANDPAPER_PLAY": str(progs["sandpaper-play"]),
           "LAB_DEVICE": str(progs["sandpaper-lab-device"]), "LAB_POST": str(progs["sandpaper-lab-post"]),
           "LAB_WRITES": str(progs["sandpaper-lab-writes"]),
           "REPO": str(REPO)}
    env.update(params or {})
    all_files: dict[str, Path | bytes] = data_files()
    all_files["/lab/ffboard.sh"] = HERE / "scenarios" / "ffboard.sh"
    all_files["/lab/params.sh"] = "".join(
        f"export {k}={shlex.quote(str(v))}\n" for k, v in env.items()).encode()
    all_files.update(files or {})
    script = (HERE / "scenarios" / f"{name}.sh").read_bytes()
    out_dir.mkdir(parents=True, exist_ok=True)
    return lab.run(script, binaries=list(progs.values()), files=all_files, out_dir=out_dir,
                   timeout=timeout, cache_dir=build / "usb-lab", echo=echo, bus=bus)
