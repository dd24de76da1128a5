#!/usr/bin/env python3
"""The studio's force-field arrows in headless Chromium (docs/STUDIO.md, "Preview"): on
examples/corduroy.hmat the arrows must stand for the force where it is. Corduroy's force lives on
its walls (a grating of period 3.2 mm, hill 50 %, walls Gaussians of sigma = 3.2 mm x 6/256 =
0.075 mm; docs/TEXTURES.md), so a grid of cell centres steps over every wall and sees microNewtons.

Independent figures: the compiler's maximum lateral force (`sandpaper compile --json`, from its own
1024-points-a-period table), against the scale the page states in newtons; the walls' places worked
by hand (hill centred on x = 0, so walls at x = +-0.8 mm + k 3.2 mm) and confirmed by the servo
loop's own force at the hand (/api/hand, /api/state), against where the page draws its arrows
(read from the overlay canvas' pixels). Screenshot: <out>/studio-field-arrows.png.

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1)."""
import argparse
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "support"))
sys.path.insert(0, os.path.join(here, "..", "catalog"))
from cdp import Browser, chromium_for_test  # noqa: E402
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check

PERIOD_MM, HILL = 3.2, 0.5
SIGMA_MM = PERIOD_MM * 6 / 256


def wall_distance(x_mm):
    """Distance (mm) from x to the nearest wall: walls at +-HILL*PERIOD/2 + k*PERIOD."""
    half = HILL * PERIOD_MM / 2
    u = (x_mm + half) % PERIOD_MM  # walls at u = 0 and u = 2 half
    return min(u, abs(u - 2 * half), PERIOD_MM - u)


def on_hill(x_mm):
    """Whether x lies on a hill (|x - k P| < hill P / 2): arrows point away from hills, into valleys."""
    u = (x_mm + PERIOD_MM / 2) % PERIOD_MM - PERIOD_MM / 2
    return abs(u) < HILL * PERIOD_MM / 2


def wait(b, expression, what, seconds=20):
    try:
        b.wait_for(expression, what, seconds)
        return True
    except Exception:
        return False


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    chromium, status = chromium_for_test("the studio's force-field test")
    if status is not None:
        return status
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    examples = pathlib.Path(args.examples).resolve()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-field-"))
    folder = tmp / "examples"
    shutil.copytree(examples, folder)
    (tmp / "library").symlink_to(examples.parent / "library")

    compiled = json.loads(subprocess.run([args.sandpaper, "compile", str(folder / "corduroy.hmat"), "--json"],
                                         check=True, capture_output=True, text=True).stdout)
    f_max = compiled["compiled_max_lateral_force_N"]
    check(1.0 < f_max < 3.0, f"the compiler's maximum lateral force of corduroy: {f_max:.4f} N")

    studio = Studio(os.path.abspath(args.sandpaper), folder / "corduroy.hmat")
    b = Browser(chromium, width=1400, height=1150)
    try:
        # The walls by hand, confirmed by the servo loop: the hand at rest on the wall at x = +0.8 mm
        # feels the compiled maximum along +x (downhill, into the valley); on the hill's middle, nothing.
        for x, want in ((0.8, f_max), (0.0, 0.0)):
            studio.post("/api/hand", {"x_mm": x, "y_mm": 0.0})
            deadline, s = time.monotonic() + 20, None
            while time.monotonic() < deadline:  # until the hand has arrived (no velocity term: the force is its place's)
                s = studio.state()
                if abs(s["hand"][0] - x) < 1e-4 and abs(s["hand"][1]) < 1e-4:
                    break
            check(abs(s["force_N"][0] - want) < 0.05 * f_max + 1e-3,
                  f"the servo loop's force with the hand at rest at x = {x} mm: {s['force_N'][0]:.4f} N (by hand: {want:.4f} N)")

        b.navigate(studio.url)
        check(wait(b, "document.body.dataset.ready === 'yes'", "the page", 30), "the page loads")
        check(wait(b, "document.querySelector('#picture').naturalWidth > 0 && window.studio.state.field?.n > 0",
                   "the preview and its field"), "the preview is drawn")
        b.click("#arrows")
        caption = "document.querySelector('#picture-caption').textContent"
        check(wait(b, caption + ".includes('arrows')", "the arrows' caption"), "ticking `arrows`, the caption says what they stand for")
        text = b.evaluate(caption)
        m = re.search(r"arrows:.*?longest is ([0-9.]+) N", text)
        stated = float(m.group(1)) if m else None
        check(stated is not None and abs(stated - f_max) <= 0.03 * f_max,
              f"the page states the arrows' scale in newtons, {stated} N, within 3 % of the compiler's {f_max:.4f} N: {text!r}")
        legend = b.evaluate("document.querySelector('#stage').dataset.arrowScaleN")
        check(legend is not None and abs(float(legend) - f_max) <= 0.03 * f_max,
              f"and the legend drawn on the picture stands for the same force: {legend} N")

        # Where the arrows are drawn: the overlay's blue pixels (the picture under it is grey, the hand
        # yellow and red), columns to millimetres.
        window_mm = b.evaluate("window.studio.state.preview.window_mm")
        b.evaluate("document.querySelector('#stage').scrollIntoView({block: 'center'})")
        # The hand (drawn in yellow and red over the arrows) sits on the hill's middle, where no arrow belongs.
        pixels = b.evaluate("""(() => { const c = document.querySelector('#overlay'); const g = c.getContext('2d');
            const d = g.getImageData(0, 0, c.width, c.height).data; const cols = [];
            for (let y = 34; y < c.height; y++) for (let x = 0; x < c.width; x++) { const i = 4 * (y * c.width + x);
              if (d[i + 3] > 40 && d[i + 2] - Math.max(d[i], d[i + 1]) > 25) cols.push([x, y]); }
            return [c.width, c.height, cols]; })()""")
        width, height, blue = pixels
        xs = [((px + 0.5) / width - 0.5) * window_mm[0] for px, _ in blue]
        on_hills = [x for x in xs if on_hill(x) and wall_distance(x) > 0.15]
        check(len(blue) > 500, f"{len(blue)} pixels of arrows are drawn")
        check(blue and len(on_hills) <= 0.01 * len(blue),
              f"none on the hills' flat tops, away from the walls: {len(on_hills)} of {len(blue)} arrow pixels")
        # Every wall in the window has arrows starting on it, down most of the picture's height.
        walls = [w for k in range(-10, 11) for w in (k * PERIOD_MM - 0.8, k * PERIOD_MM + 0.8)
                 if abs(w) < window_mm[0] / 2 - 0.2]
        rows_at = []
        for w in walls:
            rows = {py * 24 // height for (px, py), x in zip(blue, xs) if abs(x - w) < 2 * SIGMA_MM}
            rows_at.append(len(rows))
        check(walls and min(rows_at) >= 20,
              f"each of the {len(walls)} walls in the {window_mm[0]:.1f} mm window has arrows in at least 20 of 24 rows: {rows_at}")
        # Their lengths: an arrow at a wall is the wall's force, so the longest reach about 0.9 cell.
        b.screenshot(str(out / "studio-field-arrows.png"), full_page=False)

        # The field picture's colour scale: its brightest is the wall's peak, not a pixel beside it.
        b.click("input[name=view][value=field]")
        check(wait(b, caption + ".includes('force field at rest')", "the field picture"), "(the force field view)")
        text = b.evaluate(caption)
        m = re.search(r"\|F\| up to ([0-9.]+) N", text)
        up_to = float(m.group(1)) if m else None
        check(up_to is not None and abs(up_to - f_max) <= 0.02 * f_max,
              f"the field's brightness scale, {up_to} N, is the compiler's maximum {f_max:.4f} N within 2 %")
        b.screenshot(str(out / "studio-field-colour-arrows.png"), full_page=False)
    finally:
        b.close()
        code, _, _ = studio.stop()
    check(code == 0, f"the studio stops on Ctrl-C (exit {code})")
    shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
