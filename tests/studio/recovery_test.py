#!/usr/bin/env python3
"""A studio stopped with unsaved edits keeps them (docs/STUDIO.md, "Files"): a real `sandpaper studio`
gets a slider's edit (POST /api/parameter) in the open file and a typed text in a second file left open
in the studio, then Ctrl-C (SIGINT). Each file is untouched on disk, its edited text is in
.NAME.recovered beside it, and stderr names both. Started again, the studio offers the kept text as
unsaved edits of the file (with the file's text to go back to); saving it writes the file and removes
the copy.

Exit 0 pass, 1 fail. Prints 'N passed, N failed'."""
import argparse
import os
import pathlib
import shutil
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "support"))
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    args = ap.parse_args()
    sandpaper = os.path.abspath(args.sandpaper)
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-recovery-"))
    try:
        folder = tmp / "materials"
        folder.mkdir()
        corduroy = folder / "corduroy.hmat"
        shutil.copy(pathlib.Path(args.examples) / "corduroy.hmat", corduroy)
        original = corduroy.read_bytes()
        (folder / "cloth").mkdir()
        plain = folder / "cloth" / "plain.hmat"
        plain_text = 'material "plain" {\n  roughness 0.4\n}\n'
        plain.write_text(plain_text)
        typed = 'material "plain" {\n  roughness 0.7   # typed, not saved\n}\n'

        studio = Studio(sandpaper, corduroy)
        try:
            status, r = studio.post("/api/open", {"file": "cloth/plain.hmat"})
            check(status == 200, f"cloth/plain.hmat opens ({status})")
            status, r = studio.post("/api/material", typed, content_type="text/plain")
            check(status == 200 and r["saved"] is False, "a typed text makes it unsaved")
            status, r = studio.post("/api/open", {"file": "corduroy.hmat"})
            check(status == 200, "back to corduroy.hmat, plain.hmat left with its edits")
            status, r = studio.post("/api/parameter", {"name": "grating.period", "value": 4.5, "unit": "mm"})
            check(status == 200 and r["saved"] is False, f"the slider's edit: grating.period 4.5 mm ({status})")
            edited = r.get("text", "")
            # Worked from the file: only the period's characters change.
            check(edited == original.decode().replace("3.2 mm", "4.5 mm", 1), "the edit rewrote the period alone")
            status, files = studio.get("/api/files")
            check(sorted(files["unsaved"]) == ["cloth/plain.hmat", "corduroy.hmat"], f"both listed as unsaved: {files['unsaved']}")
        finally:
            code, out, err = studio.stop()
        check(code == 0, f"Ctrl-C stops it (exit {code})")
        check(corduroy.read_bytes() == original and plain.read_text() == plain_text, "neither file is written")
        kept = folder / ".corduroy.hmat.recovered"
        kept_plain = folder / "cloth" / ".plain.hmat.recovered"
        check(kept.is_file() and kept.read_text() == edited, f"the slider's edit is kept in {kept.name}")
        check(kept_plain.is_file() and kept_plain.read_text() == typed, f"the typed text in cloth/{kept_plain.name}")
        lines = err.splitlines()
        check(any("corduroy.hmat" in l and ".corduroy.hmat.recovered" in l for l in lines)
              and any("cloth/plain.hmat" in l and "cloth/.plain.hmat.recovered" in l for l in lines),
              f"stderr names each file and where its edits are: {err!r}")
        left = [p.name for p in folder.iterdir() if p.name.startswith(".") and not p.name.endswith(".recovered")]
        check(not left, f"no temporary file left beside them: {left}")

        again = Studio(sandpaper, corduroy)
        try:
            status, cur = again.get("/api/current")
            check(cur["text"] == edited and cur["saved"] is False, "started again, the studio holds the kept text, unsaved")
            rec = cur.get("recovered") or {}
            check(rec.get("copy") == ".corduroy.hmat.recovered" and rec.get("saved_text") == original.decode(),
                  f"and says where it came from, with the file's text to go back to: {rec.get('copy')!r}")
            status, files = again.get("/api/files")
            check(files["files"] == ["cloth/plain.hmat", "corduroy.hmat"], f"the copies are not listed as files: {files['files']}")
            status, r = again.post("/api/save", {})
            check(status == 200 and corduroy.read_text() == edited, "Save writes the kept text to the file")
            check(not kept.exists(), "and the copy goes")
            status, r = again.post("/api/open", {"file": "cloth/plain.hmat"})
            check(status == 200 and r.get("recovered") == "cloth/.plain.hmat.recovered" and r["saved"] is False,
                  f"the other file, opened, offers its kept text too: {r.get('recovered')!r}")
            status, cur = again.get("/api/current")
            check(cur["text"] == typed, "its text is the one typed")
        finally:
            code, out, err = again.stop()
        check(code == 0 and kept_plain.is_file() and kept_plain.read_text() == typed and not kept.exists(),
              f"stopped again, the unsaved one is kept, the saved one has no copy (exit {code})")
        check("corduroy.hmat" not in err and "cloth/plain.hmat" in err, f"stderr names only the unsaved one: {err!r}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
