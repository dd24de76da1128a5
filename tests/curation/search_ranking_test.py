#!/usr/bin/env python3
"""`sandpaper library search` ranks by the rule the catalog's page ranks by: the shared table
tests/curation/data/search_ranking.json (queries, their expected first three hits, and why, worked
out from the entries' files) is run against the CLI here and against the catalog in
tests/catalog/browser_test.py.

  search_ranking_test.py --sandpaper BIN --source SOURCE_DIR
"""
import argparse
import json
import os
import re
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--sandpaper', required=True)
    ap.add_argument('--source', required=True, help='the repository: library/ and examples/lab-library/')
    a = ap.parse_args()
    table = json.load(open(os.path.join(a.source, 'tests', 'curation', 'data', 'search_ranking.json')))
    paths = {'world': os.path.join(a.source, 'library'),
             'lab': os.path.join(a.source, 'examples', 'lab-library') + ':' + os.path.join(a.source, 'library')}
    # The shipped library's root id: library.toml's `id`, or the folder's name without one.
    toml = open(os.path.join(a.source, 'library', 'library.toml'), encoding='utf-8').read()
    m = re.search(r'^id\s*=\s*"([^"]+)"', toml, re.M)
    root_id = {'lab': 'lab', 'world': m.group(1) if m else 'library'}
    failures = 0
    for case in table['queries']:
        cmd = [a.sandpaper, 'library', 'search', *case['q'].split(), '--library', paths[case['library']], '--json', '--quiet',
               '--limit', '50']
        run = subprocess.run(cmd, capture_output=True, text=True)
        hits = json.loads(run.stdout) if run.returncode == 0 else []
        got = [h['name'] for h in hits[:3]]
        ok = got == case['top'] and (len(case['top']) == 3 or len(hits) == len(case['top']))
        if 'root' in case:
            ok = ok and [h.get('root') for h in hits[:3]] == [root_id[r] for r in case['root']]
        print('%s %-10s %-8s got %s%s' % ('ok  ' if ok else 'FAIL', case['q'], case['library'],
                                          [(h['name'], h.get('root')) if 'root' in case else h['name'] for h in hits[:5]],
                                          '' if ok else '; expected %s (%d hits in all)\n     because %s' % (
                                              case['top'], len(hits), case['why'])))
        if not ok:
            failures += 1
            if run.returncode not in (0, 1):
                print(run.stderr)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
