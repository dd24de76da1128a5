#!/usr/bin/env python3
"""`run` measures the felt peak that `explain` predicts (docs/TEXTURES.md, "Felt at speed").

On a 1.5 mm grating at 100 mm/s and 1 kHz on the simulated joystick, a run reports felt_peak_N: the
mean over the ridges it crossed of each crossing's largest |F|. explain predicts the same quantity
averaged over where the first tick lands within one tick's travel (0.1 mm here). A scripted hand at
exactly 15 ticks a period meets the grating at one phase per stroke, so the runs start at eight
evenly spaced phases (--hand-start 0 to 0.0875 mm); their mean must agree with the prediction
within 5 %. Those runs are on the virtual clock: in real time a loaded machine's overruns move the
hand between ticks by more than one tick's travel, and how well a machine keeps time is bench/'s
business, not a pass/fail test's. One real-time run checks that the same measurement is reported
there. The run's largest |F| is reported beside it, never below it, and the compiled force apart
from both.
"""
import argparse
import json
import subprocess
import sys

MATERIAL = "grating period 1.5 mm; roughness 0.5"
SPEED_MM_S = 100
RATE_HZ = 1000
STEP_MM = SPEED_MM_S / RATE_HZ

failures = 0
passes = 0


def check(ok, what):
    global failures, passes
    print(("ok    " if ok else "FAIL  ") + what)
    if ok:
        passes += 1
    else:
        failures += 1


def run_json(sandpaper, *args):
    r = subprocess.run([sandpaper, *args, "--json"], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)} exited {r.returncode}: {r.stderr}")
    return json.loads(r.stdout)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    sandpaper = ap.parse_args().sandpaper

    explained = run_json(sandpaper, "explain", "-e", MATERIAL)
    predicted = next(f for f in explained["felt_at_speed"] if f["speed_mm_s"] == SPEED_MM_S and f["rate_hz"] == RATE_HZ)
    compiled = explained["compiled_max_lateral_force_N"]
    print(f"explain: compiled {compiled:.4f} N, felt at {SPEED_MM_S} mm/s and {RATE_HZ} Hz {predicted['felt_peak_N']:.4f} N")
    check(predicted["felt_peak_N"] < 0.9 * compiled, "the prediction loses force at this speed (a test that can tell)")

    peaks = []
    for k in range(8):
        start = k * STEP_MM / 8
        r = run_json(sandpaper, "run", "-e", MATERIAL, "--speed", str(SPEED_MM_S), "--rate", str(RATE_HZ),
                     "--duration", "1", "--hand-start", f"{start:.4f}", "--virtual-clock")
        print(f"  run from {start:.4f} mm: felt peak {r['felt_peak_N']:.4f} N over {r['felt_ridge_crossings']} crossings, "
              f"largest |F| {r['felt_max_lateral_force_N']:.4f} N, felt roughness {r['felt_roughness']:.3f}, "
              f"clock {r['clock']}, overruns {r['overruns']}")
        check(r["clock"] == "virtual" and r["overruns"] == 0, "the run is on the virtual clock, every tick on time")
        check(r["felt_ridge_crossings"] >= 100, f"{r['felt_ridge_crossings']} ridge crossings (100 mm at 2 per 1.5 mm, less the ramp)")
        check(r["felt_max_lateral_force_N"] >= r["felt_peak_N"], "the run's largest |F| is at least its felt peak")
        check(r["compiled_max_lateral_force_N"] == compiled and r["felt_roughness_from"] == "felt_peak_N",
              "the compiled force is reported apart, and the felt roughness comes from the felt peak")
        peaks.append(r["felt_peak_N"])
    mean = sum(peaks) / len(peaks)
    error = mean / predicted["felt_peak_N"] - 1
    check(abs(error) < 0.05, f"mean felt peak {mean:.4f} N is within 5 % of explain's {predicted['felt_peak_N']:.4f} N ({error * 100:+.2f} %)")

    r = run_json(sandpaper, "run", "-e", MATERIAL, "--speed", str(SPEED_MM_S), "--rate", str(RATE_HZ), "--duration", "1")
    print(f"  in real time: felt peak {r['felt_peak_N']:.4f} N over {r['felt_ridge_crossings']} crossings, "
          f"largest |F| {r['felt_max_lateral_force_N']:.4f} N, overruns {r['overruns']}")
    check(r["clock"] == "monotonic", "the real-time run is on the monotonic clock")
    check(r["felt_ridge_crossings"] >= 100 and 0 < r["felt_peak_N"] <= r["felt_max_lateral_force_N"] <= compiled * 1.0001,
          "it measures the felt peak too: over 100 crossings, no more than its largest |F|, no more than the compiled force")
    print(f"{passes} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
