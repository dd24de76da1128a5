"""The lab's figures from what one run left behind: the host's trace and run summary
(`sandpaper run --device usb --trace T --json`) and the device's logs (sandpaper-lab-device
--log: reports.csv, torque.csv). Every time is CLOCK_MONOTONIC of the one guest, so host ticks and
device events compare directly.

Definitions (docs/USB_PID.md "In the lab"):
- received_hz[axis]: Set Constant Force reports for that axis's effect that reached the device,
  per second of play.
- updates_hz[axis]: of those, the ones the firmware applied: a driver torque update on that axis
  came after the report and before the next one, per second of play.
- latency_ms: for each applied value, from the start of the host tick that computed it (the
  latest tick at or before the report's arrival whose command equals the report's magnitude) to
  the firmware's first driver update after the report.
- firmware_peak_N: the firmware's torque on the scan axis in newtons, split into ridges (runs of
  one sign; zeros do not end a run) and averaged over ridges of each ridge's largest |F|, as
  explain's felt-at-speed peak is defined (compiler/include/sandpaper/compiler/felt_at_speed.hpp).
- unmatched_reports[axis]: Set Constant Force reports during play whose magnitude no tick of the
  200 before its arrival computed (through the device file's scale): a mis-scaled, corrupted or
  stale report. 0 when the firmware receives what the ticks computed.
- rms_error_N: the firmware's torque in newtons against the force the host commanded at the same
  instant (the last tick at or before each driver update), RMS over the play.
"""
import csv
import math
import tomllib
from pathlib import Path

SET_EFFECT, SET_CONSTANT_FORCE = 0x01, 0x05  # OpenFFBoard report IDs (ffb_defs.h; docs/USB_PID.md)


# What the firmware (OpenFFBoard 160af91) does to a Set Constant Force magnitude M on its way to
# the driver, with its defaults: torque = M x 204/255 (the axis's effect ratio, Axis.h:244-248)
# x 5000/32767 (the axis power, Axis.cpp:735-783), clipped to +-5000; a positive torque pushes the
# handle toward decreasing reported position (the firmware's own spring answers +x with positive
# torque; Axis.cpp:781 inverts the axis). usb-lab/firmware/README.md has the chain.
TORQUE_PER_COMMAND = 204 / 255 * 5000 / 32767


def round_half_away(x: float) -> int:
    return int(math.copysign(math.floor(abs(x) + 0.5), x))


def device_chain(device_file: Path):
    """(command, torque_N) for measure(): the command units the driver sends for a force, from the
    device file's scale, sense and limit as the driver uses them; and the newtons at the handle
    for a driver torque, through TORQUE_PER_COMMAND and the same scale."""
    device = tomllib.loads(Path(device_file).read_text())
    newtons = [device["force"][a]["newtons_per_command_unit"] for a in ("x", "y")]
    sense = [device["force"][a].get("command_sense", 1) for a in ("x", "y")]
    limit = device["force"]["command_max"]

    def command(axis, f):
        return max(-limit, min(limit, round_half_away(sense[axis] * f / newtons[axis])))

    def torque_N(axis, t):
        return -t / TORQUE_PER_COMMAND * newtons[axis]  # a positive torque pushes toward -axis

    return command, torque_N


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_reports(path):
    out = []
    for row in read_csv(path):
        out.append((int(row["t_ns"]), row["pipe"], int(row["type"]), bytes.fromhex(row["bytes"])))
    return out


def read_torques(path):
    return [(int(r["t_ns"]), int(r["axis"]), int(r["torque"])) for r in read_csv(path)]


def read_trace(path):
    return [tuple(float(r[k]) for k in ("t_s", "x_m", "y_m", "force_x_N", "force_y_N")) for r in read_csv(path)]


def int16(lo, hi):
    v = lo | (hi << 8)
    return v - 0x10000 if v >= 0x8000 else v


def effect_axes(reports):
    """Effect block index -> axis (0 X, 1 Y), from the Set Effect reports' Axes Enable bits (byte 13)."""
    axes = {}
    for _, _, _, b in reports:
        if len(b) >= 14 and b[0] == SET_EFFECT:
            enable = b[13]
            if enable & 1:
                axes[b[1]] = 0
            elif enable & 2:
                axes[b[1]] = 1
    return axes


def force_reports(reports, axes):
    """Per axis: [(t_ns, magnitude)] of every Set Constant Force that reached the device."""
    per_axis = ([], [])
    for t, _, _, b in reports:
        if len(b) >= 4 and b[0] == SET_CONSTANT_FORCE and b[1] in axes:
            per_axis[axes[b[1]]].append((t, int16(b[2], b[3])))
    return per_axis


def percentile(values, q):
    if not values:
        return None
    s = sorted(values)
    k = (len(s) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


def ridge_peaks(samples):
    """Largest |v| of each run of one sign in `samples` (zeros do not end a run)."""
    peaks, sign, peak = [], 0, 0.0
    for v in samples:
        s = 1 if v > 0 else -1 if v < 0 else 0
        if s == 0:
            continue
        if s != sign and sign != 0:
            peaks.append(peak)
            peak = 0.0
        sign = s
        peak = max(peak, abs(v))
    if sign != 0:
        peaks.append(peak)
    return peaks


def mean_ridge_peak(samples):
    """Mean over whole ridges: the first and last runs may be cut by the start and end of play."""
    peaks = ridge_peaks(samples)
    inner = peaks[1:-1] if len(peaks) > 2 else peaks
    return sum(inner) / len(inner) if inner else 0.0


def measure(run, trace, reports, torques, command, torque_N, scan_axis=0):
    """`run`: the host's run JSON; `command(axis, F_N)`: the command units the driver sends for a
    force (the device calibration's scale, rounded and clamped as the driver does);
    `torque_N(axis, torque)`: newtons at the handle for a driver torque (the device file's chain)."""
    start_ns = int(run["clock_start_ns"])
    ticks = [(start_ns + round(t * 1e9), (fx, fy)) for t, _, _, fx, fy in trace]
    if not ticks:
        raise ValueError("the host's trace has no ticks")
    play_start, play_end = ticks[0][0], ticks[-1][0]
    seconds = (play_end - play_start) * 1e-9
    per_axis_reports = force_reports(reports, effect_axes(reports))
    per_axis_torque = ([], [])
    for t, axis, torque in torques:
        if axis in (0, 1) and play_start <= t <= play_end + 50_000_000:
            per_axis_torque[axis].append((t, torque))

    received, applied, latencies, unmatched = [0, 0], [0, 0], [], [0, 0]
    for axis in (0, 1):
        # Reports from play start to the end: the shutdown's zero force comes after the last tick.
        rs = [r for r in per_axis_reports[axis] if play_start <= r[0] <= play_end]
        received[axis] = len(rs)
        updates = [t for t, _ in per_axis_torque[axis]]
        u = 0
        k = 0  # ticks[k] is the first tick after the report, searched forward as reports are
        for i, (t_r, magnitude) in enumerate(rs):
            while k < len(ticks) and ticks[k][0] <= t_r:
                k += 1
            # The tick that computed this magnitude: the latest of the 200 before its arrival.
            source = next((j for j in range(k - 1, max(-1, k - 200), -1)
                           if command(axis, ticks[j][1][axis]) == magnitude), None)
            if source is None:
                unmatched[axis] += 1
            while u < len(updates) and updates[u] < t_r:
                u += 1
            next_report = rs[i + 1][0] if i + 1 < len(rs) else None
            if u >= len(updates) or (next_report is not None and updates[u] >= next_report):
                continue  # overwritten before the firmware's next update used it
            applied[axis] += 1
            if source is not None:
                latencies.append((updates[u] - ticks[source][0]) * 1e-6)

    # The firmware's force at the handle against the host's command at each driver update.
    errors = []
    k = 0
    for t, torque in per_axis_torque[scan_axis]:
        while k + 1 < len(ticks) and ticks[k + 1][0] <= t:
            k += 1
        if t < ticks[0][0]:
            continue
        errors.append(torque_N(scan_axis, torque) - ticks[k][1][scan_axis])
    firmware_forces = [torque_N(scan_axis, torque) for _, torque in per_axis_torque[scan_axis]]
    return {
        "seconds": seconds,
        "received_hz": [received[a] / seconds for a in (0, 1)],
        "updates_hz": [applied[a] / seconds for a in (0, 1)],
        "latency_ms": {"p50": percentile(latencies, 0.5), "p99": percentile(latencies, 0.99), "n": len(latencies)},
        "firmware_peak_N": mean_ridge_peak(firmware_forces),
        "commanded_peak_N": mean_ridge_peak([f[scan_axis] for _, f in ticks]),
        "firmware_max_N": max((abs(f) for f in firmware_forces), default=0.0),
        "rms_error_N": math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else None,
        "unmatched_reports": unmatched,
    }
