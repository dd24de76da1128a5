#!/usr/bin/env python3
"""A scene in the studio's 3-D view, in headless Chromium (docs/STUDIO.md, "Scenes in 3-D"): the
studio started on examples/3d, examples/3d/textured-sphere.hsc chosen from the page's file list, the
WebGL canvas read back (drawn, not blank), a left-drag across the ball in the canvas (the 3-D Dummy
mode), and then: the device the studio holds moved along the drag, pressed 2 mm into the ball, and
the page shows the contact force as a number and as an arrow.

Independent figures: the ball's stiffness from the scene file (800 N/m) times the press depth the page
was set to (2 mm, then 4 mm): the normal force k d; and `sandpaper probe` (its own renderer, proxy
brought straight in along the radius) at the same device points. Also the API's refusals, a scene
that does not compile (the last good scene stays), orbiting (the camera moves, the device does not),
and lifting the device (no force). Screenshot: <out>/studio-scene.png (docs/studio-scene.png).

Exit 0 pass, 1 fail (including: Chromium missing), 77 skipped (SANDPAPER_SKIP_BROWSER_TESTS=1).
Prints 'N passed, N failed'."""
import argparse
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "support"))
sys.path.insert(0, os.path.join(here, "..", "catalog"))
from cdp import Browser, chromium_for_test  # noqa: E402
from studio_process import Studio  # noqa: E402
from checklist import Checklist  # noqa: E402

checks = Checklist()
check = checks.check

# From examples/3d/textured-sphere.hsc: the ball.
BALL_CENTRE_M = (0.0, 0.040, 0.0)
BALL_RADIUS_M = 0.040
BALL_STIFFNESS_N_PER_M = 800.0


def wait(b, expression, what, seconds=30):
    try:
        b.wait_for(expression, what, seconds)
        return True
    except Exception as e:
        print(f"     ({e})", flush=True)
        return False


def mouse(b, kind, x, y, button="left", buttons=1, modifiers=0):
    b.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": button, "buttons": buttons,
                                        "clickCount": 1, "modifiers": modifiers})


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def probe(sandpaper, scene, from_m, device_m):
    """`sandpaper probe` from `from_m` (outside the surface) straight to `device_m` in one step: the
    step at the device point, as probe --json prints it."""
    mm = lambda p: ",".join(repr(x * 1e3) for x in p)  # noqa: E731
    out = subprocess.run([sandpaper, "probe", str(scene), "--from", mm(from_m), "--to", mm(device_m), "--steps", "1", "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["steps"][-1]


def settle(b):
    """Until the page's 3-D Dummy mode has no request on the wire and none waiting."""
    return wait(b, "(() => { const d = window.studio.scene3d.dummy; return !d.sending && !d.pending; })()",
                "the device's answers", 20)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    ap.add_argument("--examples", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    chromium, status = chromium_for_test("the studio's 3-D scene test")
    if status is not None:
        return status
    sandpaper = os.path.abspath(args.sandpaper)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    examples = pathlib.Path(args.examples).resolve()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="sandpaper-studio-scene-"))
    folder = tmp / "3d"
    shutil.copytree(examples / "3d", folder)
    (folder / "ribs.hmat").write_text('material "ribs" {\n  like corduroy\n}\n')
    scene_file = folder / "textured-sphere.hsc"
    scene_text = scene_file.read_text()

    studio = Studio(sandpaper, folder)
    b = Browser(chromium, width=1400, height=1100)
    try:
        # The API before the page: the folder's scenes are listed; nothing to draw while none is open.
        status, files = studio.get("/api/files")
        check(status == 200 and "textured-sphere.hsc" in files["files"] and "material-box.hsc" in files["files"],
              f"the folder's scene files are listed: {files.get('files')}")
        status, answer = studio.get("/api/scene")
        check(status == 409, f"no scene open: GET /api/scene is 409 ({status}: {answer.get('error')})")

        b.navigate(studio.url)
        check(wait(b, "document.body.dataset.ready === 'yes'", "the page to load"), "the page loads")
        check(b.evaluate("!!window.sandpaperScene3d") is False, "the 3-D view's script is not loaded before a scene opens")
        # The user chooses the scene from the file list.
        b.evaluate("(() => { const s = document.querySelector('#file'); s.value = 'textured-sphere.hsc';"
                   " s.dispatchEvent(new Event('change')); })()")
        check(wait(b, "document.body.dataset.kind === 'scene' && +(document.querySelector('#scene-stage').dataset.version || 0) > 0"
                      " && !!window.studio.scene3d", "the 3-D view", 60), "choosing the scene opens the 3-D view")
        check(b.evaluate("window.studio.text()") == scene_text, "the editor holds the scene's text")
        compile_line = b.evaluate("document.querySelector('#compile-state').textContent")
        check("textured sphere" in compile_line and "65026 triangles" in compile_line, f"the compile line: {compile_line!r}")
        # Laid out or not: a hidden pane's elements have no boxes.
        boxes = b.evaluate("['#stage', '#strip', '#scene-stage'].map((s) => document.querySelector(s).getClientRects().length)")
        check(boxes[0] == 0 and boxes[1] == 0 and boxes[2] > 0, f"the 2-D stage gives way to the 3-D one (boxes: {boxes})")

        status, g = studio.get("/api/scene")
        check(status == 200 and len(g["triangles"]) == 3 * 65026 and len(g["triangle_surfaces"]) == 65026
              and len(g["positions_m"]) % 3 == 0 and max(g["triangles"]) < len(g["positions_m"]) // 3,
              f"GET /api/scene: {len(g['triangle_surfaces'])} triangles over {len(g['positions_m']) // 3} vertices, in metres")
        ball = next((s for s in g["surfaces"] if s["object"] == "ball"), None)
        check(ball is not None and ball["stiffness_N_per_m"] == BALL_STIFFNESS_N_PER_M and ball["material"] == "corduroy"
              and ball["colour"].startswith("#"), f"the ball's surface: {ball}")
        lo, hi = g["bounds_m"]["min"], g["bounds_m"]["max"]
        check(abs(hi[1] - 0.08) < 1e-6 and abs(lo[0] + 0.12) < 1e-6, f"the scene's bounds in metres: {lo} .. {hi}")

        px = b.evaluate("window.studio.scene3d.pixels()")
        total = px["width"] * px["height"]
        check(px["painted"] > total * 0.05, f"WebGL drew the scene: {px['painted']} of {total} pixels are not the background")

        # The API's answer at a known point against `sandpaper probe` and against k d.
        top = [0.0, 0.078, 0.0]  # 2 mm into the top of the ball
        above = [0.0, 0.12, 0.0]
        status, t = studio.post("/api/scene/device", {"device_m": top, "from_m": above})
        p = probe(sandpaper, scene_file, above, top)
        check(status == 200 and t["in_contact"] and t["object"] == "ball" and
              all(abs(a - c) < 1e-6 for a, c in zip(t["force_N"], p["force_N"])),
              f"POST /api/scene/device at the ball's top: {t.get('force_N')} N, `sandpaper probe` {p['force_N']} N")
        want = BALL_STIFFNESS_N_PER_M * 0.002
        check(abs(t["force_magnitude_N"] - want) < 0.01 * want, f"|F| = k d = {want:.3f} N within 1 %: {t['force_magnitude_N']:.4f} N")
        for body, why in (({"device_m": [0, 1]}, "two numbers"), ({"device_m": [0, 50, 0]}, "50 m away"),
                          ({"x_mm": 1}, "no device_m"), ({"device_m": [0, 0.1, 0], "from_m": "up"}, "from_m not a point")):
            status, answer = studio.post("/api/scene/device", body)
            check(status == 400, f"refused with 400, {why}: {answer.get('error')}")

        # The wheel zooms (toward the scene's middle, the ball).
        b.evaluate("document.querySelector('#scene-stage').scrollIntoView({block: 'center'})")
        at = b.evaluate("window.studio.scene3d.screenOf(%s)" % json.dumps(BALL_CENTRE_M))
        far = b.evaluate("window.studio.scene3d.camera.position.distanceTo(window.studio.scene3d.controls.target)")
        for _ in range(6):
            b.send("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": at[0], "y": at[1], "deltaX": 0, "deltaY": -100})
        near = b.evaluate("window.studio.scene3d.camera.position.distanceTo(window.studio.scene3d.controls.target)")
        check(near < 0.9 * far, f"the wheel zooms in: the camera {far * 1e3:.0f} mm -> {near * 1e3:.0f} mm from the scene's middle")

        # The drag: left button across the ball's upper part as the camera sees it, where the surface
        # faces up and sideways, so the arrow along its normal is seen at length, not end-on.
        centre_px, right = b.evaluate("""(() => { const v = window.studio.scene3d; const e = v.camera.matrixWorld.elements;
            return [v.screenOf(%s), [e[0], e[1], e[2]]]; })()""" % json.dumps(BALL_CENTRE_M))
        edge_px = b.evaluate("window.studio.scene3d.screenOf(%s)"
                             % json.dumps([c + BALL_RADIUS_M * r for c, r in zip(BALL_CENTRE_M, right)]))
        radius_px = edge_px[0] - centre_px[0]
        check(radius_px > 40, f"the ball is {2 * radius_px:.0f} px across on the canvas")
        steps = 16
        x0, x1, y = centre_px[0] - 0.45 * radius_px, centre_px[0] + 0.45 * radius_px, centre_px[1] - 0.6 * radius_px
        mouse(b, "mouseMoved", x0, y, buttons=0)
        mouse(b, "mousePressed", x0, y)
        settle(b)
        devices = []
        for i in range(1, steps + 1):
            mouse(b, "mouseMoved", x0 + (x1 - x0) * i / steps, y)
            settle(b)
            status, d = studio.get("/api/scene/device")
            devices.append(d)
        mouse(b, "mouseReleased", x1, y, buttons=0)
        along = [dot(sub(d["device_m"], BALL_CENTRE_M), right) for d in devices]
        check(all(b2 > a for a, b2 in zip(along, along[1:])),
              "the device the studio holds moves along the drag, step by step: " + ", ".join(f"{a * 1e3:.1f}" for a in along) + " mm")
        check(along[-1] - along[0] > 0.5 * BALL_RADIUS_M,
              f"over {(along[-1] - along[0]) * 1e3:.1f} mm of the ball (the drag spans {0.9 * BALL_RADIUS_M * 1e3:.0f} mm of screen across it)")
        depths = [BALL_RADIUS_M - norm(sub(d["device_m"], BALL_CENTRE_M)) for d in devices]
        check(all(abs(x - 0.002) < 1e-4 for x in depths),
              f"each pressed 2 mm into the ball (its depth {min(depths) * 1e3:.3f} to {max(depths) * 1e3:.3f} mm)")
        check(all(d["in_contact"] and d["object"] == "ball" for d in devices), "in contact with the ball all the way")

        last = devices[-1]
        check(abs(last["normal_force_N"] - want) < 0.03 * want,
              f"the normal force is k d = 800 N/m x 2 mm = {want:.2f} N within 3 %: {last['normal_force_N']:.4f} N")
        outward = [x / norm(sub(last["device_m"], BALL_CENTRE_M)) for x in sub(last["device_m"], BALL_CENTRE_M)]
        p = probe(sandpaper, scene_file, [d + 0.005 * o for d, o in zip(last["device_m"], outward)], last["device_m"])
        check(abs(last["normal_force_N"] - p["normal_force_N"]) < 0.02 * p["normal_force_N"],
              f"and `sandpaper probe` at that device point says {p['normal_force_N']:.4f} N")
        check(last["force_magnitude_N"] >= last["normal_force_N"] * 0.999,
              f"|F| {last['force_magnitude_N']:.4f} N: the normal force and the drag of friction and the ribs")
        shown = b.evaluate("[document.querySelector('#scene-force').textContent, document.querySelector('#scene-surface').textContent,"
                           " document.querySelector('#scene-material').textContent, document.querySelector('#scene-scale').textContent]")
        check(float(shown[0]) > 0 and shown[0] == f"{last['force_magnitude_N']:.3f}",
              f"the page shows |F| = {shown[0]} N, the studio's {last['force_magnitude_N']:.4f} N")
        check("ball" in shown[1] and "corduroy" in shown[2], f"and where: {shown[1]!r}, {shown[2]!r}")
        arrow = b.evaluate("window.studio.scene3d.arrow()")
        check(arrow["visible"] and abs(arrow["length_m"] - last["force_magnitude_N"] * arrow["mm_per_N"] * 1e-3) < 1e-9
              and f"{arrow['mm_per_N']} mm of the scene = 1 N" in shown[3],
              f"the force arrow is {arrow['length_m'] * 1e3:.1f} mm long at the stated {shown[3]!r}")
        px = b.evaluate("window.studio.scene3d.pixels()")
        check(px["arrow"] > 30, f"and drawn: {px['arrow']} pixels change with it")
        b.screenshot(str(out / "studio-scene.png"), full_page=False)

        # A deeper press: the press depth typed beside the view.
        b.type_into("#press-depth", "4")
        mouse(b, "mousePressed", centre_px[0], y)
        settle(b)
        mouse(b, "mouseReleased", centre_px[0], y, buttons=0)
        status, d = studio.get("/api/scene/device")
        check(abs(d["normal_force_N"] - 2 * want) < 0.03 * 2 * want,
              f"pressed 4 mm: the normal force {d['normal_force_N']:.4f} N, k d = {2 * want:.2f} N within 3 %")
        b.type_into("#press-depth", "2")

        # Orbiting with the right button moves the camera, not the device.
        cam0 = b.evaluate("window.studio.scene3d.camera.position.toArray()")
        mouse(b, "mouseMoved", x0, y - 40, buttons=0)
        mouse(b, "mousePressed", x0, y - 40, button="right", buttons=2)
        for i in range(1, 6):
            mouse(b, "mouseMoved", x0 - 20 * i, y - 40, button="right", buttons=2)
        mouse(b, "mouseReleased", x0 - 100, y - 40, button="right", buttons=0)
        cam1 = b.evaluate("window.studio.scene3d.camera.position.toArray()")
        status, after = studio.get("/api/scene/device")
        check(norm(sub(cam0, cam1)) > 0.01 and after["moves"] == d["moves"],
              f"a right-drag orbits: the camera moved {norm(sub(cam0, cam1)) * 1e3:.0f} mm, the device stayed")

        # Lifting: no contact, no force, no arrow.
        b.click("#scene-lift")
        check(wait(b, "document.body.dataset.sceneForce === '0.000'", "the lift's answer"), "lift: the page shows 0 N")
        status, d = studio.get("/api/scene/device")
        check(not d["in_contact"] and d["force_magnitude_N"] == 0 and not b.evaluate("window.studio.scene3d.arrow().visible"),
              "the device is off the ball, with no force and no arrow")

        # A typo in the scene: its diagnostic listed, the last good scene stays drawn and touchable.
        version = b.evaluate("+document.querySelector('#scene-stage').dataset.version")
        status, r = studio.post("/api/material", scene_text.replace("stiffness 800 N/m", "stiffness 800 N/mm2"),
                                content_type="text/plain")
        check(status == 200 and not r["ok"] and r["diagnostics"], f"a typo does not compile: {r['diagnostics'][0]['code'] if r.get('diagnostics') else r}")
        check(wait(b, "document.body.dataset.compiles === 'no' && document.querySelectorAll('#diagnostics li.error').length > 0",
                   "the diagnostics"), "the page lists its diagnostics")
        status, t = studio.post("/api/scene/device", {"device_m": top, "from_m": above})
        check(status == 200 and abs(t["force_magnitude_N"] - want) < 0.01 * want
              and b.evaluate("+document.querySelector('#scene-stage').dataset.version") == version,
              "the last good scene is still felt and drawn")
        studio.post("/api/material", scene_text, content_type="text/plain")

        # Another file's kind: a material has no scene.
        status, _ = studio.post("/api/open", {"file": "ribs.hmat"})
        status, answer = studio.get("/api/scene")
        check(status == 409, f"a material open: GET /api/scene is 409 ({answer.get('error')})")
        check(wait(b, "document.body.dataset.kind === 'material' && getComputedStyle(document.querySelector('#scene3d')).display === 'none'",
                   "the page to follow"), "the page follows to the material and hides the 3-D view")
    finally:
        b.close()
        code, _, err = studio.stop()
        check(code == 0, f"the studio stops cleanly on Ctrl-C (exit {code}){': ' + err[-300:] if code else ''}")
        shutil.rmtree(tmp, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
