#!/usr/bin/env python3
"""Every grating entry's catalog thumbnail shows the grating's own frequency, whatever its orientation.

Writes the shipped library's catalog with `sandpaper library catalog`, reads each grating entry's
`entries/<name>-thumb.png` (decoded here, standard library only), and measures the picture's
strongest spatial frequency along the grating's normal: the pixels, less their mean and under a 2-D
Hann window, projected onto the normal (u = x cos t + y sin t, mm) and Fourier-transformed there
(the projection-slice theorem: a slice of the picture's 2-D spectrum). The scale is the catalog's
stated one (docs/CATALOG.md: 128 pixels over 40 mm). The expected frequency is 1 / period, with the
period and orientation read from the entry's own file (or the `like` entry it builds on), not from
the catalog. A light along the ridges shades both walls alike and shows 2 / period: a 45 deg
twill's 1.2 mm came out at 0.6 mm.
"""
import argparse
import cmath
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

WINDOW_MM = 40.0  # the thumbnails' square (docs/CATALOG.md)
SIDE = 128        # its pixels


def read_grey_png(path):
    """An 8-bit greyscale PNG as (width, height, rows of ints)."""
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', path
    pos, idat, width = 8, b'', None
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b'IHDR':
            width, height, depth, colour, _, _, interlace = struct.unpack('>IIBBBBB', body)
            assert depth == 8 and colour == 0 and interlace == 0, (path, depth, colour, interlace)
        elif kind == b'IDAT':
            idat += body
        elif kind == b'IEND':
            break
    raw = zlib.decompress(idat)
    rows, prev, stride = [], [0] * width, width + 1
    for y in range(height):
        f, line = raw[y * stride], list(raw[y * stride + 1:(y + 1) * stride])
        for x in range(width):
            a = line[x - 1] if x > 0 else 0
            b = prev[x]
            c = prev[x - 1] if x > 0 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            else:
                assert f == 0, (path, f)
        rows.append(line)
        prev = line
    return width, height, rows


def strongest_frequency(rows, normal_rad, f_lo=0.1, f_hi=2.6, step=0.002):
    """The frequency (cycles/mm) of the largest power along the normal, and its share of the power scanned."""
    n = len(rows)
    mm = WINDOW_MM / n
    mean = sum(sum(r) for r in rows) / (n * n)
    hann = [math.sin(math.pi * (i + 0.5) / n) ** 2 for i in range(n)]
    c, s = math.cos(normal_rad), math.sin(normal_rad)
    # Bins an eighth of a pixel wide along u: a phase error of at most pi/8 per cycle of a pixel.
    bin_mm = mm / 8
    bins = {}
    for row in range(n):
        y = WINDOW_MM / 2 - (row + 0.5) * mm  # row 0 is the top, +y up
        for col in range(n):
            x = (col + 0.5) * mm - WINDOW_MM / 2
            k = round((x * c + y * s) / bin_mm)
            bins[k] = bins.get(k, 0.0) + (rows[row][col] - mean) * hann[row] * hann[col]
    profile = [(k * bin_mm, v) for k, v in bins.items() if v != 0.0]
    best_f, best_p, total = 0.0, -1.0, 0.0
    f = f_lo
    while f <= f_hi:
        w = -2j * math.pi * f
        acc = sum(v * cmath.exp(w * u) for u, v in profile)
        p = abs(acc) ** 2
        total += p
        if p > best_p:
            best_f, best_p = f, p
        f += step
    return best_f, (best_p / total if total > 0 else 0.0)


def gratings(library):
    """name -> (period mm, orientation deg, file) for each entry with a grating, own or by `like`."""
    files, names = {}, {}
    for folder, _, fs in os.walk(library):
        for fn in fs:
            if fn.endswith('.hmat'):
                text = open(os.path.join(folder, fn), encoding='utf-8').read()
                m = re.search(r'material\s+"([^"]+)"', text)
                if not m:
                    continue
                files[m.group(1)] = text
                names[m.group(1)] = m.group(1)
                for a in re.findall(r'^\s*alias\s+([\w-]+)', text, re.M):
                    names[a] = m.group(1)
    out = {}
    for name in files:
        period = orientation = None
        at, seen = name, set()
        while at in files and at not in seen:
            seen.add(at)
            g = re.search(r'^\s*grating\s+period\s+([0-9.]+)\s*mm(.*)$', files[at], re.M)
            if g:
                if period is None:
                    period = float(g.group(1))
                o = re.search(r'orientation\s+(-?[0-9.]+)\s*deg', g.group(2))
                if o and orientation is None:
                    orientation = float(o.group(1))
            like = re.search(r'^\s*like\s+([\w-]+)', files[at], re.M)
            at = names.get(like.group(1)) if like else None
        if period is not None:
            out[name] = (period, orientation or 0.0)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--sandpaper', required=True)
    ap.add_argument('--library', required=True)
    ap.add_argument('--out', help='keep the catalog here (default: a temporary folder)')
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix='thumb-freq-')
    out = a.out or os.path.join(work, 'catalog')
    try:
        subprocess.run([a.sandpaper, 'library', 'catalog', '-o', out, '--library', a.library, '--quiet'], check=True)
        found = gratings(a.library)
        assert len(found) >= 8, found  # corduroy, pinwale, denim, gabardine, ... (a regex gone wrong finds none)
        failures, checked = [], 0
        for name, (period, orientation) in sorted(found.items()):
            if WINDOW_MM / period >= SIDE / 2:
                continue  # under two pixels a period along x: drawn as grey, not as ridges (catalog_tests)
            if WINDOW_MM / period < 4:
                continue  # fewer than four periods across the window: no frequency to measure
            thumb = os.path.join(out, 'entries', name + '-thumb.png')
            width, height, rows = read_grey_png(thumb)
            assert (width, height) == (SIDE, SIDE), (name, width, height)
            f, share = strongest_frequency(rows, math.radians(orientation))
            expected = 1.0 / period
            checked += 1
            line = '%-22s period %.2f mm at %5.1f deg: strongest %.3f cycles/mm (share %.2f), expected %.3f' % (
                name, period, orientation, f, share, expected)
            print(line)
            # One cycle across the window either way (1/40 cycles/mm) and the Hann window's main lobe.
            if abs(f - expected) > 2.0 / WINDOW_MM:
                failures.append(line)
        assert checked >= 8, checked
        if failures:
            print('FAIL: thumbnails whose strongest frequency is not the grating\'s own:\n  ' + '\n  '.join(failures))
            return 1
        print('ok: %d grating thumbnails show 1 / period' % checked)
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == '__main__':
    sys.exit(main())
