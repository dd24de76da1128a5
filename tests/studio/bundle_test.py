#!/usr/bin/env python3
"""The studio's bundled page holds one copy of each npm package (docs/STUDIO.md). Two copies of
@codemirror/state in one page break every command that compares its objects across packages: with
6.5.2 beside the 6.7 that @codemirror/commands wanted, undo and every editing command threw
"Cannot read properties of null (reading 'endSide')". Reads esbuild's metafile of the bundle
(its "inputs": every file bundled, by path) and names every package bundled from two folders.

Usage: bundle_test.py METAFILE. Exit 0 pass, 1 fail. Prints 'N passed, N failed'."""
import json
import sys
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


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    inputs = json.load(open(sys.argv[1]))["inputs"]
    folders = defaultdict(set)
    for path in inputs:
        p = package_of(path)
        if p:
            folders[p[1]].add(p[0])
    failed = 0
    if not folders:
        print("FAIL: the metafile names no npm package: is it the studio's bundle?")
        failed += 1
    for name, where in sorted(folders.items()):
        if len(where) > 1:
            print(f"FAIL: {name} is bundled {len(where)} times, from " + ", ".join(sorted(where)))
            failed += 1
    codemirror = sorted(n for n in folders if n.startswith("@codemirror/") or n == "codemirror")
    if "@codemirror/state" not in codemirror or "@codemirror/commands" not in codemirror:
        print("FAIL: the bundle has no @codemirror/state or @codemirror/commands: " + ", ".join(codemirror))
        failed += 1
    passed = 1 if failed == 0 else 0
    if passed:
        print(f"ok: one copy each of {len(folders)} packages, among them " + ", ".join(codemirror))
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
