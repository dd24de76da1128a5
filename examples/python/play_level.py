#!/usr/bin/env python3
"""Play a roughness level by name on the simulated joystick and print what was felt.

    PYTHONPATH=build/python python3 examples/python/play_level.py coarse --seconds 0.5
"""
import argparse

import sandpaper


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("level", help="a roughness level: " + ", ".join(sandpaper.Library().roughness_levels()))
    parser.add_argument("--seconds", type=float, default=1.0, help="how long to play, s")
    parser.add_argument("--rate", type=float, default=1000.0, help="servo rate, Hz")
    args = parser.parse_args()

    material = sandpaper.Library().roughness_level(args.level)
    player = sandpaper.Player.simulated()
    player.load(material)
    player.start(rate_hz=args.rate, duration_s=args.seconds)
    report = player.wait()  # the GIL is released while the servo thread plays
    print(f"played {args.level}: {report['ticks']} ticks at {report['rate_hz']:.1f} Hz, "
          f"max lateral force {report['felt_max_lateral_force_N']:.3f} N of {material.compiled_max_lateral_force_N:.3f} N compiled "
          f"(roughness {material.compiled_roughness:.3f}), stop {report['stop_cause']}")
    return 0 if report["stop_cause"] == "completed" else 1


if __name__ == "__main__":
    raise SystemExit(main())
