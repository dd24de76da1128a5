#!/usr/bin/env python3
"""The studio's HTTP contract (docs/STUDIO.md), against a running `sandpaper studio` on the simulated
joystick: health, compile (the same object as `sandpaper compile --json`), state, parameter (the new
compiled force within 200 ms, ticks rising), hand (Dummy mode), the Host/Origin refusal, the folder
confinement, a broken material leaving the last good program playing, saving, and Ctrl-C.

Exit 0 pass, 1 fail. Prints 'N passed, N failed'."""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check


def poll(studio, predicate, seconds):
    """The first state within `seconds` that satisfies `predicate`, with the time it took; else (last, None)."""
    t0 = time.monotonic()
    s = studio.state()
    while not predicate(s):
        if time.monotonic() - t0 > seconds:
            return s, None
        time.sleep(0.005)
        s = studio.state()
    return s, time.monotonic() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    args = ap.parse_args()
    sandpaper = os.path.abspath(args.sandpaper)
    examples = pathlib.Path(args.examples).resolve()

    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-api-"))
    folder = tmp / "examples"
    shutil.copytree(examples, folder)
    (tmp / "library").symlink_to(examples.parent / "library")  # the examples' images: ../library/images
    outside = tmp / "outside.hmat"
    outside.write_text("roughness 0.5\n")
    (folder / "escape.hmat").symlink_to(outside)
    # A file named in Latin-1: JSON cannot name it, so it is listed apart, with what to do.
    (folder / os.fsdecode(b"caf\xe9.hmat")).write_text("roughness 0.5\n")
    original = (folder / "corduroy.hmat").read_text()

    studio = Studio(sandpaper, folder / "corduroy.hmat")
    try:
        status, health = studio.get("/api/health")
        check(status == 200 and health.get("ok") is True and isinstance(health.get("version"), str),
              f"GET /api/health: {health}")

        status, listing = studio.get("/api/files")
        files, unlisted = listing.get("files", []), listing.get("not_listed", [])
        check(status == 200 and "corduroy.hmat" in files and all(isinstance(f, str) and "\ufffd" not in f for f in files)
              and [u.get("file") for u in unlisted] == ["caf\ufffd.hmat"] and "rename" in unlisted[0].get("why", ""),
              f"GET /api/files lists the materials, and a name not in UTF-8 apart with what to do: {unlisted}")

        # POST /api/compile: the same object as the CLI's, run from the same folder on the same file name.
        text = (folder / "corduroy.hmat").read_text()
        status, compiled = studio.post("/api/compile", text, content_type="text/plain")
        cli = subprocess.run([sandpaper, "compile", "corduroy.hmat", "--json", "-o", str(tmp / "c.patch")],
                             cwd=folder, capture_output=True, text=True)
        expected = json.loads(cli.stdout)
        expected["output"] = None
        # A calibration file is shown by a path that opens from the process's own folder (relative
        # there, else absolute); the studio runs from this test's folder, the CLI from the material's.
        def opened_from(j, base):
            if isinstance(j, dict):
                return {k: opened_from(v, base) for k, v in j.items()}
            if isinstance(j, list):
                return [opened_from(v, base) for v in j]
            if isinstance(j, str):
                return re.sub(r"(?<![\w/.])calibration/[\w./-]+\.toml", lambda m: os.path.join(base, m.group(0)), j)
            return j
        compiled = opened_from(compiled, os.getcwd())
        expected = opened_from(expected, str(folder))
        check(status == 200 and compiled == expected,
              "POST /api/compile equals `sandpaper compile --json` (but for the patch written)")
        status, bad = studio.post("/api/compile", text.replace("period 3.2 mm", "period 3.2 mn"), content_type="text/plain")
        d = bad.get("diagnostics", [{}])[0]
        check(status == 200 and bad.get("ok") is False and d.get("line") == 6 and d.get("code") == "E0204"
              and "mn" in d.get("message", "") and isinstance(d.get("column"), int),
              f"a typo compiles to a diagnostic at its line: {d.get('line')}:{d.get('column')} {d.get('code')} {d.get('message')}")

        s1 = studio.state()
        keys = {"ticks", "rate_hz", "overruns", "compiled_max_lateral_force_N", "material", "hand", "force_N"}
        check(keys <= set(s1), f"GET /api/state has {sorted(keys)}")
        s2, took = poll(studio, lambda s: s["ticks"] > s1["ticks"] + 50, 10)
        check(took is not None and s2["running"], f"ticks rise: {s1['ticks']} -> {s2['ticks']}")
        check(s2["material"] == "corduroy/wide-wale", f"the opened file plays: {s2['material']}")

        # POST /api/parameter: recompiled, swapped, and shown by /api/state within 200 ms.
        before = studio.state()
        status, r = studio.post("/api/parameter", {"name": "roughness", "value": 0.8})
        t_answer = time.monotonic()
        check(status == 200 and r.get("ok") is True, "POST /api/parameter roughness 0.8 compiles")
        new_force = r.get("compiled_max_lateral_force_N", 0)
        seen = []

        def shows_new(s):
            seen.append(s["ticks"])
            return abs(s["compiled_max_lateral_force_N"] - new_force) < 1e-9 and s["material_version"] == r["version"]

        after, _ = poll(studio, shows_new, 5)
        took = time.monotonic() - t_answer
        check(new_force > before["compiled_max_lateral_force_N"] * 1.2,
              f"roughness 0.8 compiles to a larger force: {before['compiled_max_lateral_force_N']:.4f} -> {new_force:.4f} N")
        check(shows_new(after) and took <= 0.2, f"/api/state shows the new compiled force {took * 1000:.0f} ms after the answer")
        later, _ = poll(studio, lambda s: seen.append(s["ticks"]) or s["ticks"] > before["ticks"] + 50, 10)
        check(all(b >= a for a, b in zip(seen, seen[1:])) and seen[-1] > before["ticks"] + 50,
              f"ticks never went backwards and kept rising ({before['ticks']} -> {seen[-1]})")
        check("roughness 0.8 " in r.get("text", "") and r["text"].count("\n") == original.count("\n"),
              "the edit changed the number in the text and nothing else")
        status, e = studio.post("/api/parameter", {"name": "grating.period", "value": 2, "unit": "N"})
        check(status == 400 and "length" in e.get("error", ""), f"a force unit for a period is refused: {e}")
        status, e = studio.post("/api/parameter", {"name": "nope", "value": 2})
        check(status == 400 and "grating.period" in e.get("error", ""), "an unknown parameter is refused, naming the known ones")

        # Every page learns of a change made anywhere: the state carries the document's text version.
        status, st = studio.get("/api/state")
        before_version = st["document"]["text_version"]
        status, r2 = studio.post("/api/parameter", {"name": "roughness", "value": 0.8})
        status, st = studio.get("/api/state")
        check(st["document"]["text_version"] > before_version and st["document"]["text_version"] == r2["text_version"]
              and st["document"]["file"] == "corduroy.hmat" and st["document"]["version"] == r2["version"],
              f"/api/state's document follows the API's change: {st['document']} after text_version {before_version}")

        # Zoom and pan: any window of the patch, drawn on request. Corduroy's 3.2 mm grating over the
        # whole 95 mm patch is 0.186 mm a pixel, coarser than its walls (3.2 / 64 = 0.05 mm); a 5 mm
        # window, 0.0098 mm a pixel, is not.
        status, whole = studio.get("/api/view?x_mm=0&y_mm=0&w_mm=95&h_mm=95")
        check(status == 200 and whole["window_mm"] == [95, 95] and abs(whole["pixel_mm"] - 95 / 512) < 1e-9
              and whole["finer_than_pixel"] is True, f"the whole patch, its walls finer than a pixel: {whole}")
        status, png = studio.get(whole.get("png", "/api/view/none.png"))
        check(status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n", "the view's picture is served")
        status, near = studio.get("/api/view?kind=field&x_mm=10&y_mm=-5&w_mm=5&h_mm=2.5")
        check(status == 200 and near["centre_mm"] == [10, -5] and near["window_mm"] == [5, 2.5]
              and near["finer_than_pixel"] is False and 0 < near["field_max_N"] <= 10,
              f"a 5 x 2.5 mm force field off the centre: {near}")
        for query, why in (("x_mm=0&y_mm=0&w_mm=500&h_mm=95", "twice the patch"), ("x_mm=48&y_mm=0&w_mm=5&h_mm=5", "on the patch"),
                           ("x_mm=0&y_mm=0&w_mm=0&h_mm=5", "0.01 mm"), ("x_mm=nan&y_mm=0&w_mm=5&h_mm=5", "number"),
                           ("x_mm=0&y_mm=0&w_mm=5", "h_mm"), ("kind=depth&x_mm=0&y_mm=0&w_mm=5&h_mm=5", "kind")):
            status, err = studio.get("/api/view?" + query)
            check(status == 400 and why in err.get("error", ""), f"/api/view?{query} is refused: {err.get('error')}")
        status, _ = studio.get("/api/view/../../etc/passwd")
        check(status == 404, "a view name outside the pattern is not a file")

        # The library browser: search through the index, an entry's numbers and text, its picture.
        status, found = studio.get("/api/library/search?q=wale%20corduroy")
        names = [e["name"] for e in found.get("entries", [])]
        check(status == 200 and names[:1] in (["corduroy"], ["pinwale-corduroy"]) and "pinwale-corduroy" in names
              and found.get("index") in ("fresh", "built"), f"searching `wale corduroy` finds the corduroys: {names}")
        corduroy = next((e for e in found["entries"] if e["name"] == "corduroy"), {})
        check(corduroy.get("period_mm") == 3.2 and corduroy.get("compiled_max_lateral_force_N", 0) > 0,
              f"with their compiled numbers: {corduroy}")
        status, entry = studio.get("/api/library/entry?name=wide-wale-corduroy")
        check(status == 200 and entry.get("name") == "corduroy" and 'material "corduroy"' in entry.get("text", "")
              and entry.get("picture") is True, "an entry by its alias: its numbers and its file's text")
        status, png = studio.get("/api/library/picture?name=corduroy")
        check(status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n", "and its picture")
        for bad in ["../../etc/passwd", "nope", ""]:
            status, e = studio.get("/api/library/entry?name=" + bad)
            check(status == 404, f"no entry {bad!r}: 404")

        # The language server's features on the studio's text (POST /api/language), as `sandpaper lsp` gives them.
        status, cur = studio.get("/api/current")
        lines = cur["text"].split("\n")
        like_line = next(i for i, l in enumerate(lines) if l.strip().startswith("like corduroy"))
        period_line = next(i for i, l in enumerate(lines) if "period 3.2 mm" in l)
        status, hover = studio.post("/api/language", {"feature": "hover", "line": period_line,
                                                      "character": lines[period_line].index("3.2")})
        value = (hover or {}).get("contents", {}).get("value", "")
        check(status == 200 and "texture.period" in value and "3.2 mm" in value and "corduroy.hmat" in value,
              f"hover on 3.2 gives explain's line for the period: {value!r}")
        status, definition = studio.post("/api/language", {"feature": "definition", "line": like_line,
                                                           "character": lines[like_line].index("corduroy") + 2})
        check(status == 200 and definition.get("uri", "").endswith("/library/textiles/corduroy.hmat"),
              f"definition on `corduroy` is the library entry: {definition}")
        status, items = studio.post("/api/language", {"feature": "completion", "line": like_line,
                                                      "character": lines[like_line].index("corduroy") + 3})
        labels = [i["label"] for i in items] if isinstance(items, list) else []
        check(status == 200 and "corduroy" in labels and "pinwale-corduroy" in labels
              and any(i.get("detail") for i in items), f"completion after `like` offers library names with what they describe")
        status, e = studio.post("/api/language", {"feature": "rename", "line": 0, "character": 0})
        check(status == 400 and "completion" in e.get("error", ""), f"an unknown feature is refused, naming the known: {e}")
        status, e = studio.post("/api/language", {"feature": "hover", "line": len(lines) + 5, "character": 0})
        check(status == 400, f"a position outside the text is refused: {e}")

        # A broken material never stops the loop: the last good program keeps playing.
        playing = studio.state()
        status, broken = studio.post("/api/material", r["text"].replace("grating period", "grating perod"),
                                     content_type="text/plain")
        check(status == 200 and broken["ok"] is False and broken["diagnostics"], "POST /api/material with a typo: diagnostics")
        later, took = poll(studio, lambda s: s["ticks"] > playing["ticks"] + 100, 10)
        check(took is not None and later["material_version"] == playing["material_version"]
              and later["compiled_max_lateral_force_N"] == playing["compiled_max_lateral_force_N"] and later["running"],
              "after the broken material the last good program still plays, ticking")
        status, fixed = studio.post("/api/material", r["text"], content_type="text/plain")
        check(fixed["ok"] is True and fixed["version"] > playing["material_version"], "the fixed text plays again")

        # Dummy mode: the simulated hand goes where the mouse puts it.
        status, h = studio.post("/api/hand", {"x_mm": 4.0, "y_mm": -3.0})
        moved, took = poll(studio, lambda s: abs(s["hand"][0] - 4) < 1e-6 and abs(s["hand"][1] + 3) < 1e-6, 5)
        check(status == 200 and took is not None, f"POST /api/hand moves the hand: {moved['hand']}")
        check(h.get("clipped") is False and h.get("target_mm") == [4.0, -3.0] and "why" not in h,
              f"a hand inside the workspace goes where it was sent, unclipped: {h}")
        status, e = studio.post("/api/hand", {"x_mm": "left"})
        check(status == 400, "a hand without numbers is refused")
        status, e = studio.post("/api/hand", "{\"x_mm\": 1", content_type="application/json")
        check(status == 400 and "not JSON" in e.get("error", ""), f"a body that is not JSON is refused, saying so: {e}")
        # The sim's workspace radius is 114 mm: the edge toward (1, -1) is at (80.6, -80.6) mm.
        status, h = studio.post("/api/hand", {"x_mm": 1e300, "y_mm": -1e300})
        s, took = poll(studio, lambda s: s["hand"][0] > 80 and s["hand"][1] < -80, 10)
        check(status == 200 and took is not None and max(abs(v) for v in s["hand"]) < 81,
              f"a hand sent past the edge goes to the edge in that direction: {s['hand']}")
        # 500 mm is past the sim's 114.3 mm radius: the answer says where the hand went and why.
        status, h = studio.post("/api/hand", {"x_mm": 500.0, "y_mm": 0.0})
        check(status == 200 and h.get("clipped") is True and h.get("requested_mm") == [500.0, 0.0]
              and abs(h["target_mm"][0] - 114.3) < 1e-9 and h["target_mm"][1] == 0
              and "114.3 mm" in h.get("why", "") and "workspace" in h.get("why", ""),
              f"a hand sent to 500 mm is answered with where it went (the 114.3 mm edge) and why: {h}")
        studio.post("/api/hand", {"x_mm": 4.0, "y_mm": -3.0})
        back, took = poll(studio, lambda s: abs(s["hand"][0] - 4) < 1e-6 and abs(s["hand"][1] + 3) < 1e-6, 10)
        check(took is not None, f"and comes back: {back['hand']}")

        # The guard: another Host (DNS rebinding) or another Origin (a page elsewhere) is refused.
        status, e = studio.get("/api/health", headers={"Host": "evil.example:80"})
        check(status == 403, f"a foreign Host is refused: {status} {e}")
        status, e = studio.post("/api/hand", {"x_mm": -20.0, "y_mm": 0.0}, headers={"Origin": "http://evil.example"})
        check(status == 403, f"a foreign Origin is refused: {status} {e}")
        time.sleep(0.05)  # (would let a wrongly accepted target be reached; the check is on the position)
        check(abs(studio.state()["hand"][0] - 4) < 1e-6, "the refused request did not move the hand")
        status, _ = studio.get("/", headers={"Host": "localhost:%d" % studio.port})
        check(status == 200, "localhost:PORT is this studio too")
        status, e = studio.post("/api/save", "", headers={"Origin": "http://127.0.0.1:1"})
        check(status == 403, "another port's origin is refused")

        # The folder: paths that climb out, absolute paths and links that lead out are refused.
        for name in ["../outside.hmat", str(outside), "escape.hmat", "workspace/../../outside.hmat"]:
            status, e = studio.post("/api/open", {"file": name})
            check(status == 403 and "outside" in e.get("error", ""), f"open {name!r} is refused: {status}")
        status, e = studio.post("/api/open", {"file": "missing.hmat"})
        check(status == 404, "a missing file is 404")
        check(outside.read_text() == "roughness 0.5\n", "the file outside is untouched")

        # Saving writes the edited text atomically; the comments stay.
        status, r = studio.post("/api/parameter", {"name": "grating.period", "value": 2.8, "unit": "mm"})
        status, saved = studio.post("/api/save", "")
        now = (folder / "corduroy.hmat").read_text()
        check(status == 200 and now == original.replace("roughness 0.55", "roughness 0.8").replace("period 3.2 mm", "period 2.8 mm"),
              "save rewrote exactly the two numbers, comments and layout intact")
        check(sorted(p.name for p in folder.iterdir() if p.name.startswith(".")) == [], "no temporary file left beside it")

        # New file and Save as, inside the folder only.
        status, made = studio.post("/api/new", {"file": "silk.hmat"})
        check(status == 200 and made.get("created") and made["ok"] and made["file"] == "silk.hmat"
              and (folder / "silk.hmat").read_text().startswith('material "silk" {'),
              f"POST /api/new creates silk.hmat with a text that compiles, and opens it: {made.get('diagnostics')}")
        for name, code in [("silk.hmat", 409), ("../outside2.hmat", 403), ("notes.txt", 400), ("missing/x.hmat", 404)]:
            status, e = studio.post("/api/new", {"file": name})
            check(status == code, f"new {name!r}: {code} ({e.get('error')})")
        check(not (tmp / "outside2.hmat").exists(), "nothing was written outside the folder")
        status, tuned = studio.post("/api/parameter", {"name": "roughness", "value": 0.3})
        check(status == 200 and "roughness 0.3" in tuned.get("text", ""), f"(tuned: {tuned.get('text') or tuned})")
        status, saved_as = studio.post("/api/save-as", {"file": "silk-fine.hmat"})
        status, cur = studio.get("/api/current")
        check(saved_as.get("saved") and cur["file"] == "silk-fine.hmat" and cur["saved"]
              and "roughness 0.3" in (folder / "silk-fine.hmat").read_text()
              and "roughness 0.5" in (folder / "silk.hmat").read_text(),
              "save-as writes the text under the new name and goes on with it; the old file is as it was")
        status, e = studio.post("/api/save-as", {"file": "corduroy.hmat"})
        check(status == 409, "save-as will not overwrite another file")
        status, e = studio.post("/api/save-as", {"file": "silk.hws"})
        check(status == 400, "nor save a material as a workspace")

        # Workspaces: the canvas' view and moving a patch.
        status, opened = studio.post("/api/open", {"file": "workspace/sampler.hws"})
        check(status == 200 and opened["ok"], "a workspace opens and plays")
        status, ws = studio.get("/api/workspace")
        check(status == 200 and len(ws["patches"]) == 7, f"GET /api/workspace lists its 7 patches")
        status, moved = studio.post("/api/workspace/patch", {"index": 6, "x_mm": 5, "y_mm": 10, "width_mm": 24, "height_mm": 18})
        check(status == 200 and moved["ok"] and 'at 5 mm, 10 mm size 24 mm x 18 mm' in moved["text"],
              "moving and resizing a patch rewrites its numbers")
        status, ws = studio.get("/api/workspace")
        near = lambda a, b: all(abs(x - y) < 1e-9 for x, y in zip(a, b))
        check(near(ws["patches"][6]["centre_mm"], [5, 10]) and near(ws["patches"][6]["size_mm"], [24, 18]),
              "the recompiled workspace has the patch where it was put")
        status, png = studio.get(f"/api/preview/patch-0.png?v={moved['version']}")
        check(status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n", "each patch has its picture")
        status, e = studio.get("/api/preview/..%2Fsecret")
        check(status == 404, "preview names outside the fixed set are 404")
    finally:
        code, out, err = studio.stop()
    check(code == 0 and "force at zero" in out, f"Ctrl-C stops the studio with the force at zero (exit {code})")
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
