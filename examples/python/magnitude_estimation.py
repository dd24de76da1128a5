#!/usr/bin/env python3
"""A small magnitude-estimation session run from Python with the simulated observer.

    PYTHONPATH=build/python python3 examples/python/magnitude_estimation.py results.csv [--seed 3]

Five gratings of one period (2.5 mm) whose force amplitude doubles from 0.2 N to 3.2 N, each
presented three times in a shuffled order on the simulated joystick (the scripted hand scanning at
50 mm/s). After each, the experiments' simulated observer (docs/EXPERIMENTS.md: estimates
modulus * F^0.76 with log-normal noise) says how rough it felt. The session is saved as CSV
(trial, stimulus, compiled and felt peak lateral force in N, estimate), and the exponent of the
estimates on the felt force is fitted in log-log coordinates, as Minsky 1995 fitted its roughness
map (Fig. 19: log R = 0.76 log F - 0.51). `sandpaper experiment run` does the same from a design
file, with people too; this is the Python way in.
"""
import argparse
import csv
import random

import numpy as np

import sandpaper

AMPLITUDES_N = [0.2, 0.4, 0.8, 1.6, 3.2]
REPETITIONS = 3


def run_session(lib, observer, seed):
    """Each stimulus REPETITIONS times in a seeded shuffle; one row per trial."""
    stimuli = [f"grating period 2.5 mm hill 50% amplitude {a} N" for a in AMPLITUDES_N]
    materials = [lib.compile(s) for s in stimuli]
    order = [i for i in range(len(stimuli)) for _ in range(REPETITIONS)]
    random.Random(seed).shuffle(order)
    rows = []
    player = sandpaper.Player.simulated()
    for trial, i in enumerate(order):
        player.load(materials[i])
        player.start(rate_hz=1000, duration_s=0.5)
        felt = player.wait()["felt_max_lateral_force_N"]  # what the running loop sent, N
        rows.append({"trial": trial, "stimulus": stimuli[i], "compiled_N": materials[i].compiled_max_lateral_force_N,
                     "felt_N": felt, "estimate": observer.estimate(felt)})
    return rows


def fit_exponent(rows):
    """Least squares in log-log coordinates: (exponent, R^2)."""
    x = np.log10([r["felt_N"] for r in rows])
    y = np.log10([r["estimate"] for r in rows])
    slope, intercept = np.polyfit(x, y, 1)
    residual = y - (slope * x + intercept)
    return slope, 1 - residual.var() / y.var()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", help="CSV file to write")
    ap.add_argument("--seed", type=int, default=3, help="seeds the order and the observer's noise")
    args = ap.parse_args()
    lib = sandpaper.Library()
    observer = sandpaper.SimulatedObserver(f"exponent=0.76,noise=0.15,seed={args.seed}", subject="S01")
    rows = run_session(lib, observer, args.seed)
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    exponent, r2 = fit_exponent(rows)
    print(f"wrote {len(rows)} trials to {args.out}; fitted exponent {exponent:.3f} "
          f"(the observer's 0.76), R^2 {r2:.3f}")


if __name__ == "__main__":
    main()
