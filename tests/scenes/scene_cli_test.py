#!/usr/bin/env python3
"""The scene commands as a user runs them on the shipped 3-D examples: explain, probe, compile,
run (sandpaper and sandpaper-play), preview, and the refusals. Forces are checked against k d
with k and d from the scene file (examples/3d/textured-sphere.hsc: a 40 mm ball at y = 40 mm,
800 N/m)."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("--sandpaper", required=True)
parser.add_argument("--player", required=True)
args = parser.parse_args()
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(*argv, expect=0):
    p = subprocess.run(list(argv), capture_output=True, text=True)
    if p.returncode != expect:
        print(p.stdout[-2000:], p.stderr[-2000:], sep="\n")
    check(p.returncode == expect, f"{' '.join(os.path.basename(a) if i == 0 else a for i, a in enumerate(argv))} exits {expect}")
    return p


sphere, box = "examples/3d/textured-sphere.hsc", "examples/3d/material-box.hsc"
relief = "examples/3d/relief-plane.hsc"

# explain: each face's material and where each contact value came from.
p = run(args.sandpaper, "explain", box, "--json")
e = json.loads(p.stdout)
faces = {(s["object"], s["side"]): s for s in e["surfaces"]}
check(faces[("crate", "top")]["material"] == "sandpaper-p80" and faces[("crate", "top")]["textured"], "explain: the crate's top is P80 sandpaper, textured")
check(faces[("crate", "front")]["material"] == "corduroy", "explain: the crate's front is corduroy")
check(faces[("crate", "top")]["stiffness_N_per_m"] == 1000 and faces[("crate", "top")]["stiffness_from"] == "scene", "explain: the scene's stiffness, said to be the scene's")
check(faces[("crate", "right")]["damping_from"] == "material", "explain: silk's damper comes from the material")
check(any("perceptual" in m["layers"] for m in e["materials"]), "explain: each material's layers are shown")

# A glTF scene from another tool: the library entry bound by name, MPEG_haptic_material's contact.
p = run(args.sandpaper, "explain", "examples/3d/gltf-scene/scene.gltf", "--json")
e = json.loads(p.stdout)
bound = [s for s in e["surfaces"] if s["material"] == "corduroy"]
check(bound and bound[0]["textured"], "explain a glTF scene: the library entry named in extras is bound and textured")
check(any(abs(s["stiffness_N_per_m"] - 1200) < 1e-3 and s["stiffness_from"] == "scene" for s in e["surfaces"]),
      "explain a glTF scene: MPEG_haptic_material's stiffness texture gives 0.6 x 2000 N/m")

# explain: a relief's depth and whether the lateral texture is kept, in JSON and in text.
p = run(args.sandpaper, "explain", relief, "--json")
e = json.loads(p.stdout)
faces = {(s["object"], s["side"]): s for s in e["surfaces"]}
floor = faces[("floor", "")]
block = [s for s in e["surfaces"] if s["object"] == "block"]
check(floor["relief_depth_m"] == 0.0005 and floor["lateral_texture"], "explain: the floor's relief is 0.5 mm, its lateral texture kept")
check(block and all(s["relief_depth_m"] == 0.0005 and not s["lateral_texture"] for s in block),
      "explain: the block is felt through its relief alone (`only`)")
p = run(args.sandpaper, "explain", relief)
check("relief 0.5 mm deep" in p.stdout and "lateral texture kept" in p.stdout and "lateral texture dropped" in p.stdout,
      "explain (text): the relief in mm and whether the lateral texture is kept")

# probe down onto the floor: pressed 2 mm, the normal force is k (d - c) with the carve c in [0, 0.5 mm].
p = run(args.sandpaper, "probe", relief, "--from", "1,10,3", "--to", "1,-2,3", "--steps", "12", "--json")
last = json.loads(p.stdout)["steps"][-1]
c = last.get("relief_carve_mm", -1) * 1e-3
check(0 <= c <= 0.0005 and abs(last["force_N"][1] - 1000 * (0.002 + 1e-6 - c)) <= 0.01 * 1000 * (0.002 - c),
      f"probe a relief: 2 mm in, the force is k (d - c) within 1 % (c = {c * 1e3:.4f} mm, got {last['force_N'][1]:.4f} N)")

# probe: straight down onto the top of the ball (y = 80 mm), 5 mm in at the last step.
p = run(args.sandpaper, "probe", sphere, "--from", "0,100,0", "--to", "0,75,0", "--steps", "25", "--json")
steps = json.loads(p.stdout)["steps"]
free = [s for s in steps if s["device_mm"][1] > 80.001]
check(all(s["force_magnitude_N"] == 0 and not s["in_contact"] for s in free), "probe: no force above the ball")
last = steps[-1]
k, d = 800.0, 0.005
check(abs(last["force_N"][1] - k * d) <= 0.01 * k * d, f"probe: 5 mm in, the force is k d = {k * d} N within 1 % (got {last['force_N'][1]:.4f})")
check(last.get("object") == "ball" and last.get("material") == "corduroy", "probe: the contact names the ball and its material")
mid = [s for s in steps if 77.0 < s["device_mm"][1] < 79.999]
check(all(abs(s["force_N"][1] - k * (0.080 - s["device_mm"][1] * 1e-3)) <= 0.01 * k * (0.080 - s["device_mm"][1] * 1e-3) + 1e-3 for s in mid) and mid,
      "probe: the force grows as k times the depth")

with tempfile.TemporaryDirectory() as tmp:
    # compile for sim3d, then the runtime-only player plays it.
    sp3 = os.path.join(tmp, "sphere.sp3")
    run(args.sandpaper, "compile", sphere, "--device", "sim3d", "-o", sp3)
    check(os.path.getsize(sp3) > 1000, "compile: the scene program is written")
    p = run(args.player, sp3, "--device", "sim3d", "--duration", "2", "--json")
    j = json.loads(p.stdout)
    check(j["ok"] and j["ticks"] == 2000 and j["ticks_in_contact"] > 0, "sandpaper-play: plays the scene program on sim3d, 2000 ticks, some in contact")
    run(args.player, sp3, "--device", "sim", expect=2)
    # A relief travels in the scene program (format version 2): compiled, then played by the player.
    relief_sp3 = os.path.join(tmp, "relief.sp3")
    run(args.sandpaper, "compile", relief, "--device", "sim3d", "-o", relief_sp3)
    p = run(args.player, relief_sp3, "--device", "sim3d", "--duration", "2", "--json")
    j = json.loads(p.stdout)
    check(j["ok"] and j["ticks_in_contact"] > 0, "sandpaper-play: plays the relief scene's program on sim3d, some ticks in contact")

    # run: the shipped scenes, 10 s at 1 kHz, no energy gained.
    for scene in (sphere, box, relief, "examples/3d/gltf-scene/scene.gltf"):
        p = run(args.sandpaper, "run", scene, "--device", "sim3d", "--duration", "10", "--json")
        j = json.loads(p.stdout)
        check(j["ok"] and j["energy"]["no_energy_gained"] and j["hand"]["stable"] and not j["not_reached"],
              f"run {os.path.basename(scene)}: 10 s on sim3d, no energy gained, stable, every object stroked")
    p = run(args.sandpaper, "run", sphere, "--device", "sim", expect=2)
    check("sim3d" in p.stderr, "run: a scene on a 2-axis device is refused, naming sim3d")

    # preview: a picture with the surfaces in it.
    out = os.path.join(tmp, "preview")
    run(args.sandpaper, "preview", box, "-o", out)
    pj = json.load(open(os.path.join(out, "preview.json")))
    check(os.path.getsize(os.path.join(out, "scene.png")) > 1000 and len(pj["surfaces"]) == 5, "preview: scene.png and a legend of the five surfaces")

    # A scene with an error: nothing written, the error at its place.
    bad = os.path.join(tmp, "bad.hsc")
    open(bad, "w").write('scene "bad" {\n  object "a" sphere radius 10 mm at 0 mm, 0 mm, 0 mm {\n    material "no-such-entry"\n  }\n}\n')
    p = run(args.sandpaper, "compile", bad, "-o", os.path.join(tmp, "bad.sp3"), "--json", expect=1)
    j = json.loads(p.stdout)
    check(not j["ok"] and any(d["code"] == "E0301" for d in j["diagnostics"]) and not os.path.exists(os.path.join(tmp, "bad.sp3")),
          "compile: a scene whose material has an error writes nothing and says E0301")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
