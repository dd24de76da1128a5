#!/usr/bin/env python3
"""The documented Neovim set-up (editors/neovim/sandpaper.lua, docs/EDITORS.md) gives a user the
usual keys: headless Neovim (Debian 12's 0.7.2 or later) opens a material and tests/lsp/neovim_keys.lua
presses C-x C-o after `like cor`, K on a number and gd on a library name, as typed. This checks what
each key did: the completion menu's items, the hover window's text, the file and line gd jumped to.
The expected values come from the files: the library's entry names and the `material` line of
library/textiles/corduroy.hmat.

Usage: neovim_keys_test.py SANDPAPER_BINARY SOURCE_DIR. Fails, not skips, without Neovim. Waits for
the editor to exit, with a deadline only a hang reaches.
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))
from checklist import Checklist  # noqa: E402

MATERIAL = """# a designer's corduroy, opened in Neovim
material "wale" {
  like corduroy
  grating period 3.2 mm hill 50%
  roughness 0.5
}
"""


def library_names(library):
    names = set()
    for f in library.rglob("*.hmat"):
        names.update(re.findall(r'^material\s+"([^"]+)"', f.read_text(), re.M))
    return names


def main():
    sandpaper, source = os.path.abspath(sys.argv[1]), pathlib.Path(sys.argv[2]).resolve()
    nvim = shutil.which("nvim")
    if not nvim:
        print("FAIL Neovim not found: the language server's editor test needs it. Install it with "
              "`sudo apt-get install neovim` (tools/install-deps.sh does).")
        return 1
    checks = Checklist()
    check = checks.check
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-nvim-keys-"))
    material = tmp / "wale.hmat"
    material.write_text(MATERIAL)
    out = tmp / "keys.json"
    env = dict(os.environ, SANDPAPER_NVIM_OUT=str(out), HOME=str(tmp), XDG_STATE_HOME=str(tmp / "state"),
               XDG_DATA_HOME=str(tmp / "data"), XDG_CONFIG_HOME=str(tmp / "config"))
    cmd = [nvim, "--headless", "--clean", "-n", "-i", "NONE",
           "--cmd", "let g:sandpaper_command = %s" % json.dumps(sandpaper),
           "-u", str(source / "editors" / "neovim" / "sandpaper.lua"),
           "-c", "luafile " + str(source / "tests" / "lsp" / "neovim_keys.lua"), str(material)]
    print(subprocess.run([nvim, "--version"], capture_output=True, text=True).stdout.splitlines()[0])
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=180, stdin=subprocess.DEVNULL)
    if not out.exists():
        print("FAIL Neovim wrote no session (exit %d)\nstdout: %s\nstderr: %s" % (run.returncode, run.stdout, run.stderr))
        return 1
    got = json.loads(out.read_text())
    print(json.dumps(got, indent=2))
    check(got.get("attached") is True, "the language server started and attached")

    expected = {n for n in library_names(source / "library") if n.startswith("cor")}
    items = got.get("completion") or []
    check("corduroy" in expected and expected <= set(items),
          f"C-x C-o after `like cor` lists the library's entries starting with `cor` {sorted(expected)}: {items}")
    check(items and all(w.startswith("cor") for w in items),
          f"and only words that go on `cor` (no statement keywords): {items}")

    hover = got.get("hover") or ""
    check(isinstance(hover, str) and "texture.period" in hover and "3.2 mm" in hover and "physical" in hover,
          f"K on 3.2 opens a window with explain's line for the period: {hover!r}")

    entry = source / "library" / "textiles" / "corduroy.hmat"
    material_row = next(i for i, line in enumerate(entry.read_text().splitlines(), 1) if line.startswith("material"))
    check((got.get("definition_file") or "").endswith("/library/textiles/corduroy.hmat"),
          f"gd on `corduroy` opens the library entry library/textiles/corduroy.hmat: {got.get('definition_file')}")
    check((got.get("definition_cursor") or [None])[0] == material_row,
          f"at its `material` line {material_row}: cursor {got.get('definition_cursor')}")
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
