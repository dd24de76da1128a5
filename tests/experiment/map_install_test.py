#!/usr/bin/env python3
"""Installing a fitted device map (docs/EXPERIMENTS.md, step 7; docs/CALIBRATION.md, "[domain] stimuli"):
the shipped viscosity design run for 3 simulated subjects on the simulated joystick, then
`analyse --map-out` into a temporary copy of calibration/ (never the shipped one).

- The named levels keep compiling after the map is installed: its domain is the stimuli widened to
  the levels' values, and beyond the stimuli a compile warns W0322; `--map-domain stimuli` keeps the
  stimuli's range, and analyse lists `viscosity very-thick` as broken (E0303), as it is.
- analyse lists the levels (and library entries) the map changes.
- A map written where no compile reads it (the README's relative form, from another folder) is
  warned about, and analyse says where maps are read from; explain shows a map's path that opens
  from the current folder.
- A damper design has no felt-against-compiled force to compare: "not compared", not 0.
- A subject in two results folders is warned about.
- The written map has `apparatus` and `[jnd]`; the plot's trial points are blue.

Expected values come from the files and the ratio-scale definition (v = (b / b_ref)^slope, docs), not
from the program's output."""
import argparse
import colorsys
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checklist import Checklist  # noqa: E402

c = Checklist()
DESIGN = "examples/experiments/viscosity-magnitude.toml"


def run(sp, *args, **kw):
    return subprocess.run([sp, *args], capture_output=True, text=True, timeout=300, **kw)


def damping(sp, text, cal, **kw):
    """(exit status, damping N*s/m or None, diagnostic codes) of `compile -e text --device sim`."""
    r = run(sp, "compile", "-e", text, "--device", "sim", "--calibration", cal, "--json", **kw)
    try:
        j = json.loads(r.stdout)
    except json.JSONDecodeError:
        return r.returncode, None, re.findall(r"\[([EW]\d{4})\]", r.stderr)
    codes = [d["code"] for d in j.get("diagnostics", [])]
    b = j.get("provenance", {}).get("damper.damping", {}).get("value")
    return r.returncode, b, codes


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    args = ap.parse_args()
    sp = os.path.abspath(args.sandpaper)
    repo = os.getcwd()
    tmp = tempfile.mkdtemp(prefix="sandpaper-map-install-")
    try:
        cal = os.path.join(tmp, "cal")
        shutil.copytree(os.path.join(repo, "calibration"), cal)
        levels = {l["name"]: l["value"] for l in tomllib.load(open(os.path.join(cal, "levels", "viscosity-levels.toml"), "rb"))["level"]}
        design = tomllib.load(open(DESIGN, "rb"))
        stim = [float(s.split()[1]) for s in design["stimuli"]]  # "damper 0.4 N*s/m"
        res = os.path.join(tmp, "results")
        ok = True
        for i in (1, 2, 3):
            r = run(sp, "experiment", "run", DESIGN, "--subject", f"S{i}", "-o", os.path.join(res, f"S{i}"),
                    "--observer", f"simulated:noise=0.1,seed={i}", "--virtual-clock", "--calibration", cal)
            ok = ok and r.returncode == 0
        c.check(ok, "the shipped viscosity design runs for 3 simulated subjects with --virtual-clock")
        rc, b, _ = damping(sp, "viscosity very-thick", cal)
        c.check(rc == 0 and b is not None and abs(b - 10) < 1e-9,
                f"before: `viscosity very-thick` compiles on sim to 10 N*s/m, the shipped map's reference ({b})")

        # Issue 72 item 18, as written: analyse --map-out into the calibration compile reads.
        out = os.path.join(cal, "maps", "sim-viscosity.toml")
        r = run(sp, "experiment", "analyse", res, "--map-out", out, "--calibration", cal, "--json")
        c.check(r.returncode == 0, f"analyse --map-out writes the map (exit {r.returncode}) {r.stderr[-300:]}")
        rep = json.loads(r.stdout) if r.returncode == 0 else {}
        m = tomllib.load(open(out, "rb")) if os.path.exists(out) else {}
        slope = m["predictor"][0]["coefficient"] if m else 0.42
        dom = m.get("domain", {})
        c.check(dom.get("stimuli") == ["0.4 N*s/m", "6.4 N*s/m"],
                f"the map records the stimuli's range, {min(stim)} to {max(stim)} N*s/m ({dom.get('stimuli')})")
        want_thin = 10 * levels["very-thin"] ** (1 / slope)
        lo, hi = (float(v.split()[0]) for v in dom.get("damping", ["0 x", "0 x"]))
        c.check(lo <= want_thin and hi >= 10, f"its domain is widened to the levels' dampings, {want_thin:.4g} to 10 N*s/m ({lo} to {hi})")
        rc, b, codes = damping(sp, "viscosity very-thick", cal)
        c.check(rc == 0 and b is not None and abs(b - 10) < 1e-6 and "W0322" in codes and "E0303" not in codes,
                f"after: `viscosity very-thick` still compiles, to 10 N*s/m, warning W0322 (exit {rc}, {b}, {codes})")
        rc, b, codes = damping(sp, "viscosity very-thin", cal)
        c.check(rc == 0 and b is not None and abs(b / want_thin - 1) < 1e-5 and codes == ["W0322"],
                f"after: `viscosity very-thin` compiles to 10 x 0.108036^(1/{slope:.4f}) = {want_thin:.5g} N*s/m with W0322 only ({b}, {codes})")
        rc, b, codes = damping(sp, "viscosity medium", cal)
        want = 10 * levels["medium"] ** (1 / slope)
        c.check(rc == 0 and codes == [] and b is not None and abs(b / want - 1) < 1e-5,
                f"a level inside the stimuli ({want:.4g} N*s/m) compiles with no warning ({b}, {codes})")
        changes = rep.get("map", {}).get("changes", [])
        by = {ch["name"]: ch for ch in changes if ch["kind"] == "level"}
        c.check(set(by) == set(levels) and not any(ch["breaks"] for ch in changes)
                and by["very-thick"]["after"]["codes"] == ["W0322"] and by["very-thin"]["changed"],
                f"analyse lists every viscosity level with what it compiles to before and after; none breaks ({sorted(by)})")
        c.check(m.get("domain", {}).get("apparatus") == "joystick", f"the map says apparatus = joystick ({dom.get('apparatus')})")
        shipped = tomllib.load(open(os.path.join(repo, "calibration", "maps", "stevens-guirao1964.toml"), "rb"))
        c.check(m.get("jnd", {}).get("weber_fraction") == shipped["jnd"]["weber_fraction"] and "stevens-guirao1964" in m["jnd"]["source"],
                f"the map has a [jnd], carried from the shipped map and saying so ({m.get('jnd')})")
        me = rep.get("magnitude_estimation", {})
        c.check(me.get("felt_vs_compiled_max_rel_diff", 0) is None and me.get("felt_vs_compiled", "").startswith("not compared"),
                f"dampers compile no force to compare: not compared ({me.get('felt_vs_compiled_max_rel_diff')!r}, {me.get('felt_vs_compiled')!r})")
        r2 = run(sp, "experiment", "analyse", res, "--calibration", cal)
        c.check("not compared" in r2.stdout, "the text report says not compared")
        c.check(rep.get("map", {}).get("read_by_compile") is True and "warning" not in r.stderr
                and rep["map"]["maps_read_from"] == os.path.realpath(os.path.join(cal, "maps")),
                f"a map written into the calibration compile reads is not warned about ({r.stderr[-200:]!r})")

        # The plot's trial points are blue: a saturated colour with a blue hue, as drawn over white.
        svg = open(os.path.join(res, "analysis", "magnitude-estimation.svg")).read()
        fills = re.findall(r'<circle class="trial"[^>]*fill="#([0-9a-fA-F]{3,6})" fill-opacity="([0-9.]+)"', svg)
        hex_, alpha = fills[0] if fills else ("fff", "1")
        if len(hex_) == 3:
            hex_ = "".join(ch * 2 for ch in hex_)
        rgb = [int(hex_[i:i + 2], 16) / 255 for i in (0, 2, 4)]
        seen = [float(alpha) * v + (1 - float(alpha)) for v in rgb]
        h, s, v = colorsys.rgb_to_hsv(*seen)
        c.check(fills and 190 <= h * 360 <= 250 and s >= 0.4,
                f"the trial points are blue over white (hue {h * 360:.0f} deg, saturation {s:.2f}; #{hex_} at {alpha})")

        # --map-domain stimuli: the experimenter's choice; analyse lists what breaks.
        cal2 = os.path.join(tmp, "cal2")
        shutil.copytree(os.path.join(repo, "calibration"), cal2)
        r = run(sp, "experiment", "analyse", res, "--map-out", os.path.join(cal2, "maps", "sim-viscosity.toml"),
                "--map-domain", "stimuli", "--calibration", cal2, "--json")
        rep2 = json.loads(r.stdout) if r.returncode == 0 else {}
        by = {ch["name"]: ch for ch in rep2.get("map", {}).get("changes", []) if ch["kind"] == "level"}
        thick = by.get("very-thick", {})
        c.check(thick.get("breaks") is True and "E0303" in thick.get("after", {}).get("codes", []) and "breaks" in r.stderr,
                f"with --map-domain stimuli, analyse lists very-thick as broken by E0303 and warns ({thick})")
        rc, _, codes = damping(sp, "viscosity very-thick", cal2)
        c.check(rc == 1 and "E0303" in codes, f"... and it is: very-thick does not compile there ({rc}, {codes})")

        # Issue 72 item 19: the README's relative --map-out from a folder whose calibration/ is not read.
        lab = os.path.join(tmp, "lab")
        os.makedirs(os.path.join(lab, "calibration", "maps"))
        cal3 = os.path.join(tmp, "cal3")
        shutil.copytree(os.path.join(repo, "calibration"), cal3)
        env = dict(os.environ, SANDPAPER_CALIBRATION=cal3)
        r = run(sp, "experiment", "analyse", res, "--map-out", "calibration/maps/sim-viscosity.toml", "--json", cwd=lab, env=env)
        rep3 = json.loads(r.stdout) if r.returncode == 0 else {}
        where = os.path.realpath(os.path.join(cal3, "maps"))
        c.check(r.returncode == 0 and os.path.exists(os.path.join(lab, "calibration", "maps", "sim-viscosity.toml")),
                "a relative --map-out is written relative to the current folder")
        c.check("warning" in r.stderr and where in r.stderr and "will not use" in r.stderr,
                f"... with a warning that compile reads maps from {where} ({r.stderr[-300:]!r})")
        c.check(rep3.get("map", {}).get("read_by_compile") is False and rep3["map"]["maps_read_from"] == where,
                f"... and the JSON says where maps are read from ({rep3.get('map', {}).get('maps_read_from')})")
        r = run(sp, "experiment", "analyse", res, "--map-out", "calibration/maps/sim-viscosity.toml", cwd=lab, env=env)
        c.check("compile reads maps from " + where in r.stdout, "the text report says where maps are read from")

        # explain names each map by a path that opens from the current folder.
        away = os.path.join(tmp, "away")
        os.makedirs(away)
        env = dict(os.environ, SANDPAPER_CALIBRATION=cal)
        ok = True
        shown = []
        for text, map_id in (("viscosity 0.5", "sim-viscosity"), ("softness 0.5", "harper-stevens1964")):
            r = run(sp, "explain", "-e", text, "--device", "sim", cwd=away, env=env)
            paths = re.findall(map_id + r" \(([^)]+\.toml)\)", r.stdout)
            shown += paths
            ok = ok and r.returncode == 0 and bool(paths) and all(os.path.isfile(os.path.join(away, p)) for p in paths)
        c.check(ok, f"explain run from another folder shows map paths that open from there ({shown})")

        # A subject found in two results folders is warned about, not silently pooled twice.
        dup = os.path.join(tmp, "dup")
        shutil.copytree(os.path.join(res, "S1"), os.path.join(dup, "S1"))
        shutil.copytree(os.path.join(res, "S1"), os.path.join(dup, "S1-copy"))
        shutil.copytree(os.path.join(res, "S2"), os.path.join(dup, "S2"))
        r = run(sp, "experiment", "analyse", dup, "--calibration", cal, "--json")
        rep4 = json.loads(r.stdout) if r.returncode == 0 else {}
        d = rep4.get("duplicate_subjects", [])
        c.check(r.returncode == 0 and len(d) == 1 and d[0]["subject"] == "S1" and len(d[0]["folders"]) == 2
                and "warning: subject S1" in r.stderr,
                f"a subject in two results folders is warned about ({d}, {r.stderr[-200:]!r})")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return c.finish()


if __name__ == "__main__":
    sys.exit(main())
