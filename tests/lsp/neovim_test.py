#!/usr/bin/env python3
"""`sandpaper lsp` through a real editor: headless Neovim (Debian 12's 0.7.2 or later) with the
shipped set-up, editors/neovim/sandpaper.lua, opening a material as a user would. Neovim's own LSP
client asks for hover, go to definition and completion and receives the diagnostics of a typo
(tests/lsp/neovim_session.lua); this checks what it got.

Usage: neovim_test.py SANDPAPER_BINARY SOURCE_DIR. Fails, not skips, without Neovim (install it with
tools/install-deps.sh). Waits for the editor to exit, with a deadline only a hang reaches.
"""
import json
import os
import pathlib
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


def main():
    sandpaper, source = os.path.abspath(sys.argv[1]), pathlib.Path(sys.argv[2]).resolve()
    nvim = shutil.which("nvim")
    if not nvim:
        print("FAIL Neovim not found: the language server's editor test needs it. Install it with "
              "`sudo apt-get install neovim` (tools/install-deps.sh does).")
        return 1
    checks = Checklist()
    check = checks.check
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-nvim-"))
    material = tmp / "wale.hmat"
    material.write_text(MATERIAL)
    out = tmp / "session.json"
    env = dict(os.environ, SANDPAPER_NVIM_OUT=str(out), HOME=str(tmp), XDG_STATE_HOME=str(tmp / "state"),
               XDG_DATA_HOME=str(tmp / "data"), XDG_CONFIG_HOME=str(tmp / "config"))
    cmd = [nvim, "--headless", "--clean", "-n", "-i", "NONE",
           "--cmd", "let g:sandpaper_command = %s" % json.dumps(sandpaper),
           "-u", str(source / "editors" / "neovim" / "sandpaper.lua"),
           "-c", "luafile " + str(source / "tests" / "lsp" / "neovim_session.lua"), str(material)]
    version = subprocess.run([nvim, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    print(version)
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=180, stdin=subprocess.DEVNULL)
    if not out.exists():
        print("FAIL Neovim wrote no session (exit %d)\nstdout: %s\nstderr: %s" % (run.returncode, run.stdout, run.stderr))
        return 1
    got = json.loads(out.read_text())
    print(json.dumps({k: v for k, v in got.items() if k != "completion"}, indent=2))
    check(got.get("filetype") == "sandpaper", f"a .hmat file is the sandpaper filetype, not conf: {got.get('filetype')!r}")
    check(got.get("attached") is True and got.get("server") == "sandpaper", "the language server started and attached")
    hover = got.get("hover")
    hover = hover if isinstance(hover, str) else json.dumps(hover)
    check("texture.period" in hover and "3.2 mm" in hover and "physical" in hover,
          f"hover on 3.2 gives explain's line for the period: {hover!r}")
    definition = got.get("definition") or ""
    check(definition.startswith("file://") and definition.endswith("/library/textiles/corduroy.hmat"),
          f"go to definition on `corduroy` opens the library entry: {definition}")
    completion = got.get("completion", [])
    check("corduroy" in completion and "pinwale-corduroy" in completion and "roughness" not in completion,
          f"completion after `like cor` offers the library's names (Neovim filters by prefix), no keywords: "
          f"{len(completion)} items")
    typo = [d for d in got.get("diagnostics", []) if d.get("code") == "E0204"]
    check(len(typo) == 1 and typo[0]["lnum"] == 3 and typo[0]["col"] == 21 and typo[0]["severity"] == 1
          and "mn" in typo[0]["message"],
          f"the unit typo `mn` is an error E0204 at line 4, column 22: {got.get('diagnostics')}")
    check(len(got.get("diagnostics", [])) == 1,
          f"and the completion's line, since deleted, left no diagnostic behind: {got.get('diagnostics')}")
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
