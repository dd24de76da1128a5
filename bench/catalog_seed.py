#!/usr/bin/env python3
"""Seeds a catalog's record from a library index, without drawing any entry: for timing the
catalog's in-place update at sizes whose full build takes hours (100,000 entries: about 2 h here).

    bench/catalog_seed.py INDEX OUT_DIR
    bench/catalog_seed.py --hashes FILE INDEX [INDEX ...] OUT_DIR

The second form seeds a layered library's catalog: FILE holds "NAME<TAB>HASH" lines as
`sandpaper_layered_inputs LAB WORLD` prints them (the entries the path shows, with their hashes
over the path), and the INDEXes are the roots' indexes, front first; each entry's row comes from
the first index that has it.

Writes OUT_DIR/inputs.sqlite (every entry of the index as drawn with the index's input hashes and
the default picture settings), the catalog marker and an empty data file, but no entry's page or
pictures. An in-place update (docs/CATALOG.md, "Incremental") never opens an unchanged entry's
files, so it does the same work in this folder as in a catalog drawn in full; bench/library_scale.sh
compares the two at 10,000 entries. The folder is not a catalog to publish: its pages are missing.
"""
import json
import pathlib
import sqlite3
import sys

# As catalog.cpp's settings_of() writes the default CatalogOptions (nlohmann's sorted keys).
SETTINGS = '{"arrays":false,"picture_side":384,"thumbnail_side":128,"thumbnail_window_m":0.04}'


def main() -> int:
    args = sys.argv[1:]
    hashes: dict[str, str] | None = None
    if args[:1] == ["--hashes"] and len(args) >= 4:
        hashes = dict(line.rstrip("\n").split("\t") for line in open(args[1]) if line.strip())
        args = args[2:]
    if len(args) < 2 or (hashes is None and len(args) != 2):
        print("\n".join(line.strip() for line in __doc__.strip().splitlines()[3:5]), file=sys.stderr)
        return 2
    indexes, out = [pathlib.Path(a) for a in args[:-1]], pathlib.Path(args[-1])
    if out.exists() and any(out.iterdir()):
        print(f"catalog_seed: {out} is not empty", file=sys.stderr)
        return 2
    (out / "entries").mkdir(parents=True, exist_ok=True)
    (out / "assets").mkdir(exist_ok=True)
    (out / ".sandpaper-catalog").write_text("seeded by bench/catalog_seed.py: not a catalog to publish\n")
    (out / "catalog-data.js").write_text("")
    rec = sqlite3.connect(out / "inputs.sqlite")
    rec.executescript(
        "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);"
        "CREATE TABLE entries(name TEXT PRIMARY KEY, hash TEXT NOT NULL, family TEXT NOT NULL,"
        " describes TEXT NOT NULL, licence TEXT NOT NULL, deprecated_by TEXT NOT NULL, aliases TEXT NOT NULL,"
        " roughness REAL, max_lateral_force_N REAL NOT NULL, page TEXT NOT NULL, thumbnail TEXT NOT NULL, files TEXT NOT NULL);")
    rec.execute("INSERT INTO meta VALUES ('settings', ?)", (SETTINGS,))
    n = 0
    seen: set[str] = set()
    for index in indexes:
        n += seed_from(index, rec, hashes, seen)
    rec.commit()
    print(f"catalog_seed: {n} entries recorded in {out / 'inputs.sqlite'} (no page drawn)")
    return 0


def seed_from(index: pathlib.Path, rec: sqlite3.Connection, hashes: dict[str, str] | None, seen: set[str]) -> int:
    """Records the entries of one index (those in `hashes`, with those hashes, if given) not seen yet."""
    src = sqlite3.connect(f"file:{index}?mode=ro", uri=True)
    aliases: dict[str, list[str]] = {}
    for alias, name in src.execute("SELECT alias, name FROM aliases ORDER BY alias"):
        aliases.setdefault(name, []).append(alias)
    rows = src.execute(
        "SELECT e.name, i.hash, e.family, e.describes, e.licence, e.deprecated_by, e.roughness, e.max_lateral_force_N "
        "FROM entries e JOIN inputs i ON i.name = e.name")
    n = 0
    for name, hash_, family, describes, licence, deprecated_by, roughness, force in rows:
        if name in seen or (hashes is not None and name not in hashes):
            continue
        seen.add(name)
        if hashes is not None:
            hash_ = hashes[name]
        textured = force > 0
        files = [f"{name}.html"] + ([f"{name}.png", f"{name}-thumb.png"] if textured else [])
        rec.execute("INSERT INTO entries VALUES (?,?,?,?,?,?,?,?,?,?,?,?)",
                    (name, hash_, family, describes, licence, deprecated_by, json.dumps(aliases.get(name, [])),
                     roughness if textured else None, force, f"entries/{name}.html",
                     f"entries/{name}-thumb.png" if textured else "", json.dumps(files)))
        n += 1
    return n


if __name__ == "__main__":
    sys.exit(main())
