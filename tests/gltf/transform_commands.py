#!/usr/bin/env python3
"""ctest gltf.transform.commands: every command of `gltf-transform --help` that a person runs on an
asset, run by the real glTF-Transform CLI (tests/gltf/node_modules/.bin/gltf-transform) with the
documented configuration (interop/gltf-transform/gltf-transform.config.mjs, docs/GLTF.md "In glTF
pipelines") on the assets `sandpaper export` writes from the shipped examples. `sandpaper compile`
then reads each result, and the test asserts the outcome the table below names:

  same    the result compiles to the program the original asset compiles to (every force table,
          force, roughness and patch place; provenance and warnings, which name the file, aside)
  E07xx   the import refuses with that code (exit 1, the code on stderr, nothing written)
  tool    glTF-Transform itself stops with an error and writes nothing

Anything else fails, above all a result that compiles to a different program (patches lost, forces
changed) with exit 0. Usage: transform_commands.py SANDPAPER SOURCE_DIR OUT_DIR
"""
import json
import os
import shutil
import subprocess
import sys

sandpaper, src, out = (os.path.abspath(a) for a in sys.argv[1:4])
here = os.path.join(src, "tests", "gltf")
cli = os.path.join(here, "node_modules", ".bin", "gltf-transform")

# (command, its arguments): what a person types after `gltf-transform COMMAND IN OUT`.
COMMANDS = [
    ("copy", []), ("optimize", []), ("optimize", ["--texture-compress", "webp"]),
    ("optimize", ["--compress", "draco", "--texture-compress", "webp"]),
    ("dedup", []), ("prune", []), ("center", []), ("instance", []), ("flatten", []), ("join", []),
    ("draco", []), ("meshopt", []), ("quantize", []), ("dequantize", []), ("weld", []), ("unweld", []),
    ("tangents", []), ("unwrap", []), ("reorder", []), ("simplify", []),
    ("metalrough", []), ("palette", []), ("unlit", []),
    ("resize", ["--width", "64", "--height", "64"]), ("png", []), ("webp", []), ("jpeg", []), ("avif", []),
    ("resample", []), ("sparse", []),
]

# What each command does to Sandpaper's haptics with the extension registered (docs/GLTF.md, "What
# glTF-Transform's commands do"): "same" unless said here. Texture commands re-encode every texture;
# the extension keeps the haptic ones as read. quantize (and meshopt, optimize) scale the nodes to undo
# integer positions, which the import reads. join (and optimize, which joins) leaves a workspace's
# patches apart: each has a visual material of its own. resize stops on a grating's one-row texture
# (sharp is asked for a height of 0), so corduroy and the sampler, which holds gratings, get no output.
def expected(command, asset):
    if command.startswith("resize") and not asset.startswith("gravel"):
        return "tool"
    return "same"


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def program(compiled, kind):
    """The program a compile wrote, without what names the file it came from."""
    if kind == "patch":
        j = json.loads(run([sandpaper, "inspect", compiled, "--json", "--tables"], check=True).stdout)
    else:
        j = json.load(open(compiled))
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k not in ("provenance", "warnings")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    return strip(j)


def compile_asset(asset, kind, stem):
    """(outcome, detail): "compiled" with the program, or the first error code."""
    target = stem + (".patch" if kind == "patch" else ".json")
    r = run([sandpaper, "compile", asset, "-o", target])
    if r.returncode == 0:
        return "compiled", program(target, kind)
    codes = [w.split("[")[1].split("]")[0] for w in r.stderr.split() if w.startswith("error[")]
    if r.returncode != 1 or not codes:
        return "crashed", f"exit {r.returncode}: {r.stderr.strip()[:300]}"
    if os.path.exists(target):
        return "wrote-on-error", target
    return codes[0], next(line for line in r.stderr.splitlines() if "error[" in line)[:300]


def main():
    if not shutil.which("node") or not os.path.exists(cli) or not os.path.isdir(os.path.join(here, "node_modules", "sharp")):
        print("SKIPPED: node or tests/gltf/node_modules (glTF-Transform's CLI, sharp) is absent; tools/install-deps.sh installs them")
        return 77
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    ext = os.path.join(out, "ext")  # the extension resolves @gltf-transform/* beside itself
    shutil.copytree(os.path.join(src, "interop", "gltf-transform"), ext)
    os.symlink(os.path.join(here, "node_modules"), os.path.join(ext, "node_modules"))
    config = os.path.join(ext, "gltf-transform.config.mjs")
    assets = {"corduroy.gltf": ("examples/corduroy.hmat", "patch"), "gravel.gltf": ("examples/gravel.hmat", "patch"),
              "sampler.gltf": ("examples/workspace/sampler.hws", "workspace"),
              "sampler.glb": ("examples/workspace/sampler.hws", "workspace")}
    originals = {}
    for name, (material, kind) in assets.items():
        path = os.path.join(out, name)
        run([sandpaper, "export", material, "--format", "gltf", "-o", path], cwd=src, check=True)
        outcome, prog = compile_asset(path, kind, os.path.join(out, name + ".original"))
        assert outcome == "compiled", (name, prog)
        originals[name] = prog
    failed = 0
    table = []
    for command, args in COMMANDS:
        label = " ".join([command] + args)
        for name, (_, kind) in assets.items():
            folder = os.path.join(out, label.replace(" ", "_").replace("--", ""), name.replace(".", "_"))
            os.makedirs(folder)
            result = os.path.join(folder, name)
            t = run([cli, command, os.path.join(out, name), result, *args, "--config", config], cwd=folder)
            if t.returncode != 0:
                outcome, detail = "tool", (t.stderr.strip() or t.stdout.strip()).splitlines()[-1:]
            else:
                outcome, detail = compile_asset(result, kind, os.path.join(folder, "compiled"))
                if outcome == "compiled":
                    outcome = "same" if detail == originals[name] else "DIFFERENT"
            want = expected(label, name)
            ok = outcome == want
            failed += not ok
            table.append((label, name, outcome))
            shown = "" if outcome in ("same", "DIFFERENT") else f": {detail}"
            print(f"{'ok  ' if ok else 'FAIL'}  gltf-transform {label} {name}: {outcome} (expected {want}){shown}", flush=True)
    # The patches merged into one mesh (merge_meshes.mjs, an artist's "join objects"): each primitive
    # keeps its haptic material through its own visual material, so the workspace is the same.
    for name in ("sampler.gltf", "sampler.glb"):
        folder = os.path.join(out, "merged-mesh", name.replace(".", "_"))
        os.makedirs(folder)
        result = os.path.join(folder, name)
        t = run(["node", os.path.join(here, "merge_meshes.mjs"), os.path.join(ext, "mpeg-haptic-material.js"),
                 os.path.join(out, name), result])
        outcome, detail = ("tool", t.stderr.strip().splitlines()[-1:]) if t.returncode != 0 else \
            compile_asset(result, "workspace", os.path.join(folder, "compiled"))
        meshes = len(json.load(open(result))["meshes"]) if t.returncode == 0 and name.endswith(".gltf") else None
        if outcome == "compiled":
            outcome = "same" if detail == originals[name] else "DIFFERENT"
        ok = outcome == "same" and meshes in (1, None)
        failed += not ok
        table.append(("merged mesh", name, outcome))
        print(f"{'ok  ' if ok else 'FAIL'}  the seven patches merged into one mesh ({t.stdout.strip()}) {name}: {outcome} "
              f"(expected same){'' if outcome in ('same', 'DIFFERENT') else ': ' + str(detail)}", flush=True)
    print(f"{failed} failed of {len(table)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
