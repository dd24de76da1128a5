#!/usr/bin/env python3
"""Compile a list of stimuli, play each for 0.3 s on the simulated joystick, and save every tick as CSV.

    PYTHONPATH=build/python python3 examples/python/stimuli_to_csv.py out.csv corduroy "roughness fine"

Columns: stimulus, t_s, x_m, y_m, fx_N, fy_N (SI units). A starting point for a magnitude-estimation
session run from Python: the same materials, played in a shuffled order, with the trace kept.
"""
import csv
import sys

import numpy as np

import sandpaper


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out, stimuli = argv[1], argv[2:]
    lib = sandpaper.Library()
    rows = 0
    with open(out, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["stimulus", "t_s", "x_m", "y_m", "fx_N", "fy_N"])
        for text in stimuli:
            material = lib.compile(text)  # raises sandpaper.CompileError with the diagnostics
            player = sandpaper.Player.simulated(record_ticks=300)
            player.load(material)
            player.start(rate_hz=1000, duration_s=0.3)
            report = player.wait()
            trace = player.trace()
            peak = float(np.hypot(trace[:, 3], trace[:, 4]).max()) if len(trace) else 0.0
            print(f"{text}: {report['ticks']} ticks, peak {peak:.3f} N, stop {report['stop_cause']}")
            for t, x, y, fx, fy in trace:
                writer.writerow([text, f"{t:.6f}", f"{x:.6g}", f"{y:.6g}", f"{fx:.6g}", f"{fy:.6g}"])
            rows += len(trace)
    print(f"wrote {len(stimuli)} stimuli, {rows} rows to {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv))
