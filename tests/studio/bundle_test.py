#!/usr/bin/env python3
"""The studio's bundled page holds one copy of each npm package (docs/STUDIO.md). Two copies of
@codemirror/state in one page break every command that compares its objects across packages: with
6.5.2 beside the 6.7 that @codemirror/commands wanted, undo and every editing command threw
"Cannot read properties of null (reading 'endSide')". Reads esbuild's metafile of the bundle
(its "inputs": every file bundled, by path) and names every package bundled from two folders.

With --scene3d, the 3-D view's bundle too (three.js, loaded by the page only when a scene opens):
one copy of each package in it, three.js in it and not in the page's own bundle (a material's page
never loads it), none of the editor in it (it shares nothing with the page but what the page hands it).

Both bundles are compiled into the studio and nothing is fetched at run time: neither names an
http(s) address other than XML namespaces (www.w3.org), which are names, never fetched.

Usage: bundle_test.py METAFILE [--scene3d METAFILE]. Exit 0 pass, 1 fail. Prints 'N passed, N failed'."""
import argparse
import json
import os
import re
from collections import defaultdict


def package_of(path):
    """('node_modules/', '@scope/name') for a file under node_modules, else None: the folder that
    holds the package (nested copies sit under another package's own node_modules) and its name."""
    marker = "node_modules/"
    i = path.rfind(marker)
    if i < 0:
        return None
    rest = path[i + len(marker):].split("/")
    name = "/".join(rest[:2]) if rest[0].startswith("@") else rest[0]
    return path[:i + len(marker)], name


def packages(meta):
    """{package name: set of folders it was bundled from}."""
    folders = defaultdict(set)
    for path in meta["inputs"]:
        p = package_of(path)
        if p:
            folders[p[1]].add(p[0])
    return folders


def remote_addresses(metafile, meta):
    """The http(s) addresses in the bundle's output files (found beside the metafile), XML namespaces apart."""
    found = set()
    for output in meta.get("outputs", {}):
        path = os.path.join(os.path.dirname(metafile), os.path.basename(output))
        if not path.endswith(".js") or not os.path.exists(path):
            continue
        text = open(path, encoding="utf-8", errors="replace").read()
        for url in re.findall(r"https?://[^\s\"'`)<>]+", text):
            if not url.startswith(("http://www.w3.org/", "https://www.w3.org/")):
                found.add(url)
    return found


class Checks:
    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, what):
        print(("ok:   " if ok else "FAIL: ") + what)
        if ok:
            self.passed += 1
        else:
            self.failed += 1


def one_copy_each(checks, name, folders):
    twice = {n: w for n, w in folders.items() if len(w) > 1}
    for n, where in sorted(twice.items()):
        checks.check(False, f"{name}: {n} is bundled {len(where)} times, from " + ", ".join(sorted(where)))
    if not twice:
        checks.check(bool(folders), f"{name}: one copy each of {len(folders)} packages" if folders
                     else f"{name}: the metafile names no npm package: is it the studio's bundle?")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("metafile", help="esbuild's metafile of the page's bundle (studio.meta.json)")
    ap.add_argument("--scene3d", help="esbuild's metafile of the 3-D view's bundle (scene3d.meta.json)")
    args = ap.parse_args()
    checks = Checks()

    meta = json.load(open(args.metafile))
    page = packages(meta)
    one_copy_each(checks, "the page", page)
    codemirror = sorted(n for n in page if n.startswith("@codemirror/") or n == "codemirror")
    checks.check("@codemirror/state" in codemirror and "@codemirror/commands" in codemirror,
                 "the page bundles CodeMirror: " + ", ".join(codemirror))
    urls = remote_addresses(args.metafile, meta)
    checks.check(not urls, "the page names no remote address" + (": " + ", ".join(sorted(urls)) if urls else ""))

    if args.scene3d:
        scene_meta = json.load(open(args.scene3d))
        scene = packages(scene_meta)
        one_copy_each(checks, "the 3-D view", scene)
        checks.check("three" in scene, "the 3-D view bundles three.js")
        checks.check("three" not in page, "the page's own bundle does not (it loads the 3-D view only for a scene)")
        shared = sorted(n for n in scene if n.startswith("@codemirror/") or n.startswith("@lezer/") or n == "codemirror")
        checks.check(not shared, "the 3-D view bundles none of the editor" + (": " + ", ".join(shared) if shared else ""))
        urls = remote_addresses(args.scene3d, scene_meta)
        checks.check(not urls, "the 3-D view names no remote address" + (": " + ", ".join(sorted(urls)) if urls else ""))

    print(f"{checks.passed} passed, {checks.failed} failed")
    return 1 if checks.failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
