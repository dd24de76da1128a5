#!/usr/bin/env python3
"""A roughness shown by `sandpaper library search` used as a `--roughness` bound keeps the entry shown
with it, as the catalog's roughness fields do (catalog.browser): silk-satin and sandpaper-p400 state
`roughness very-fine`, 0.09822 (calibration/levels/roughness-levels.toml), shown as 0.0982.

  roughness_shown_bound_test.py --sandpaper BIN --library DIR
"""
import argparse
import json
import subprocess
import sys

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def search(sp, library, bounds, text=False):
    cmd = [sp, 'library', 'search', '--roughness', bounds, '--library', library, '--quiet', '--limit', '1000']
    run = subprocess.run(cmd + ([] if text else ['--json']), capture_output=True, text=True)
    if text:
        return run.stdout
    return {h['name']: h for h in json.loads(run.stdout)} if run.returncode == 0 else {}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--sandpaper', required=True)
    ap.add_argument('--library', required=True)
    a = ap.parse_args()
    very_fine = {'silk-satin', 'sandpaper-p400'}
    lines = search(a.sandpaper, a.library, '0.09..0.1', text=True).splitlines()
    for n in very_fine:
        line = next((l for l in lines if l.split()[:1] == [n]), '')
        check('roughness 0.0982 ' in line, f'{n} is shown with roughness 0.0982 ({line.strip()!r})')
    below = search(a.sandpaper, a.library, '..0.0982')
    check(very_fine <= set(below), f'..0.0982 keeps the entries shown as 0.0982 (got {sorted(below)})')
    exact = search(a.sandpaper, a.library, '0.0982..0.0982')
    check(very_fine <= set(exact) and all('%.3g' % h['compiled_roughness'] == '0.0982' for h in exact.values()),
          f'0.0982..0.0982 keeps exactly the entries shown as 0.0982 (got {sorted(exact)})')
    above = search(a.sandpaper, a.library, '0.0983..')
    check(not (very_fine & set(above)) and len(above) > 0, '0.0983.. leaves them out and keeps others')
    # The stored value as a bound keeps them as before.
    check(very_fine <= set(search(a.sandpaper, a.library, '..0.09822')), '..0.09822 keeps them')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
