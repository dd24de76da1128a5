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
- steady: the figures below that compare forces are taken once the firmware's fade-in (the device
  file's [firmware] fade_in, counted from the first tick) is over: before it, the firmware scales
  its torque down.
- firmware_peak_N: the firmware's torque on the scan axis in newtons, per ridge of the grating the
  hand crosses, averaged over ridges of each ridge's largest |F|, as explain's device output at
  speed is defined (compiler/include/sandpaper/compiler/felt_at_speed.hpp, device_output_at_speed).
  A ridge is a run of one sign of the host's commanded force (zeros do not end a run), from its
  first tick to the next ridge's, moved later by the median latency: what the firmware drove while
  it applied that ridge's forces, its own damper included.
- commanded_peak_N: the same mean over the host's commanded forces alone.
- position_rate_hz: how often the host's position changed during the steady play: the rate its
  ticks read the grating at (the lab's bus is slower than a real one; docs/USB_PID.md).
- wall_gaps_m: [(gap, count)], the gaps along the scan axis between successive positions the ticks
  read on a ridge's wall (either end commanded over a tenth of the run's largest |F| on that axis),
  in the steady play, to 1 um. Where a wall's peak falls decides how much of it the ticks read, and
  it falls in a gap with odds in proportion to the gap's length. The lab's positions are not evenly
  spaced (they reach the ticks 1, 2 or 3 ms apart) and are farther apart on the walls than between
  them (the lab's hand moves with the firmware's control steps, which the guest runs unevenly), so
  no one rate stands for them: predicted_peaks_over_gaps weighs explain's figure for each gap.
- changes_sent: of the changes of the ticks' command on the scan axis in the steady play, the
  fraction that reached the device as a report (the driver sends the latest value when the bus
  lets it, so a bus that keeps up sends each one, and one that does not sends fewer).
- command_rate_hz: how often new magnitudes reached the firmware's motor while the ticks commanded
  a force on the scan axis: the reports of the steady play carrying a non-zero magnitude that the
  firmware applied (not overwritten by the next before its update), per second of ticks whose
  command was not zero. The driver sends an axis only when its magnitude changed, and corduroy's
  force is zero between ridges, so the mean over the whole play would count the flats; the lab's
  reports arrive in bursts, and the firmware applies only the last of a burst.
- hand_speed_m_s: the hand's speed as the ticks saw it on the guest's clock, the median over 50 ms
  windows of the steady play.
- unmatched_reports[axis]: Set Constant Force reports during play whose magnitude no tick of the
  200 before its arrival computed (through the device file's scale): a mis-scaled, corrupted or
  stale report. 0 when the firmware receives what the ticks computed.
- rms_error_N: the firmware's torque in newtons against the force the host commanded at the same
  instant (the last tick at or before each driver update), RMS over the play.
"""
import csv
import json
import math
import subprocess
import tomllib
from pathlib import Path

SET_EFFECT, SET_CONSTANT_FORCE = 0x01, 0x05  # OpenFFBoard report IDs (ffb_defs.h; docs/USB_PID.md)


# What the firmware (OpenFFBoard 160af91) does to a Set Constant Force magnitude M on its way to
# the driver, with its defaults: torque = M x 204/255 (the axis's effect ratio, Axis.h:244-248)
# x 5000/32767 (the axis power, Axis.cpp:735-783), clipped to +-5000; a positive torque pushes the
# handle toward decreasing reported position (the firmware's own spring answers +x with positive
# torque; Axis.cpp:781 inverts the axis). usb-lab/firmware/README.md has the chain.
TORQUE_PER_COMMAND = 204 / 255 * 5000 / 32767


def seconds_of(text: str) -> float:
    """A time as the device files write it: "2 s", "101 ms"."""
    value, unit = text.split()
    return float(value) * {"s": 1.0, "ms": 1e-3, "us": 1e-6}[unit]


def firmware_fade_in_s(device_file: Path) -> float:
    """The device file's [firmware] fade_in, s (0 without one)."""
    device = tomllib.loads(Path(device_file).read_text())
    fade = device.get("firmware", {}).get("fade_in")
    return seconds_of(fade) if fade else 0.0


def round_half_away(x: float) -> int:
    return int(math.copysign(math.floor(abs(x) + 0.5), x))


def device_chain(device_file: Path):
    """(command, torque_N) for measure(): the command units the driver sends for a force, from the
    device file's scale, sense and limit as the driver uses them; and the newtons at the handle
    for a driver torque, through TORQUE_PER_COMMAND and the same scale."""
    device = tomllib.loads(Path(device_file).read_text())
    # A wheel's file has [force.x] alone: nothing is ever sent or felt on its y.
    axes = [a for a in ("x", "y") if a in device["force"]]
    newtons = [device["force"][a]["newtons_per_command_unit"] for a in axes]
    sense = [device["force"][a].get("command_sense", 1) for a in axes]
    limit = device["force"]["command_max"]

    def command(axis, f):
        if axis >= len(axes):
            return 0
        return max(-limit, min(limit, round_half_away(sense[axis] * f / newtons[axis])))

    def torque_N(axis, t):
        if axis >= len(axes):
            return 0.0
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
    """Effect block index -> axis (0 X, 1 Y), from the Set Effect reports: the Axes Enable bits of
    byte 13, or with its Direction Enable bit (0x04, as Linux's hid-pidff sends every effect) the
    direction in bytes 14-15, hundredths of a degree, which the firmware applies as sin() to X and
    -cos() to Y (HidFFB.cpp, 160af91): 90 degrees is X alone and 180 degrees Y alone, each with
    factor +1 (other directions would scale or invert the magnitude, and are not counted)."""
    axes = {}
    for _, _, _, b in reports:
        if len(b) >= 14 and b[0] == SET_EFFECT:
            enable = b[13]
            if enable & 4 and len(b) >= 16:
                direction = b[14] | (b[15] << 8)
                if direction == 9000:
                    axes[b[1]] = 0
                elif direction == 18000:
                    axes[b[1]] = 1
            elif enable & 1:
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


def run_starts(ticks, axis):
    """Times at which the commanded force on `axis` starts a run of a new sign (zeros continue a run)."""
    starts, sign = [], 0
    for t, f in ticks:
        s = 1 if f[axis] > 0 else -1 if f[axis] < 0 else 0
        if s != 0 and s != sign:
            starts.append(t)
            sign = s
    return starts


def device_ridge_peaks(starts, updates, shift_ns):
    """Per ridge (from one start to the next, moved by shift_ns), the largest |F| of the piecewise
    constant force `updates` [(t_ns, F_N)]: the value held at the window's start and every update in it."""
    peaks, u, held = [], 0, 0.0
    for a, b in zip(starts, starts[1:]):
        a, b = a + shift_ns, b + shift_ns
        while u < len(updates) and updates[u][0] < a:
            held = updates[u][1]
            u += 1
        peak = abs(held)
        while u < len(updates) and updates[u][0] < b:
            held = updates[u][1]
            peak = max(peak, abs(held))
            u += 1
        peaks.append(peak)
    return peaks


def measure(run, trace, reports, torques, command, torque_N, scan_axis=0, fade_in_s=0.0, axes=None):
    """`run`: the host's run JSON; `command(axis, F_N)`: the command units the driver sends for a
    force (the device calibration's scale, rounded and clamped as the driver does);
    `torque_N(axis, torque)`: newtons at the handle for a driver torque (the device file's chain);
    `fade_in_s`: the firmware's fade-in, s, left out of the force figures; `axes`: effect block ->
    axis the host meant each effect for, when the Set Effect reports do not say it (effect_axes)."""
    start_ns = int(run["clock_start_ns"])
    ticks = [(start_ns + round(t * 1e9), (fx, fy)) for t, _, _, fx, fy in trace]
    if not ticks:
        raise ValueError("the host's trace has no ticks")
    play_start, play_end = ticks[0][0], ticks[-1][0]
    seconds = (play_end - play_start) * 1e-9
    per_axis_reports = force_reports(reports, effect_axes(reports) if axes is None else axes)
    per_axis_torque = ([], [])
    for t, axis, torque in torques:
        if axis in (0, 1) and play_start <= t <= play_end + 50_000_000:
            per_axis_torque[axis].append((t, torque))

    # Past the fade-in: the steady play, which the force and rate figures below are of.
    steady_start = play_start + round(fade_in_s * 1e9)

    received, applied, latencies, unmatched = [0, 0], [0, 0], [], [0, 0]
    # How often new magnitudes reached the firmware while they changed: the driver sends an axis
    # only when its magnitude changed, so between ridges nothing is sent, and the mean rate over the
    # play is not the rate within a ridge. The median gap between arrivals is.
    arrivals = [t for t, _ in per_axis_reports[scan_axis] if steady_start <= t <= play_end]
    gaps = [b - a for a, b in zip(arrivals, arrivals[1:])]
    command_gap_ns = percentile(gaps, 0.5)
    forcing_ns = sum(b[0] - a[0] for a, b in zip(ticks, ticks[1:])
                     if a[0] >= steady_start and command(scan_axis, a[1][scan_axis]) != 0)
    forcing_applied = 0  # of those, the ones the firmware applied before the next overwrote them
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
            if axis == scan_axis and t_r >= steady_start and magnitude != 0:
                forcing_applied += 1
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

    # Ridges of the commanded force in the steady play, the firmware's torque over each.
    steady_ticks = [(t, f) for t, f in ticks if t >= steady_start]
    steady_updates = [(t, torque_N(scan_axis, torque)) for t, torque in per_axis_torque[scan_axis]
                      if t >= steady_start - 100_000_000]
    shift_ns = round((percentile(latencies, 0.5) or 0.0) * 1e6)
    starts = run_starts(steady_ticks, scan_axis)
    # The first ridge may be cut by the start of the steady play; the last has no end.
    ridges = device_ridge_peaks(starts[1:], steady_updates, shift_ns)
    positions = [(x, y) for _, x, y, _, _ in trace]
    steady_positions = [p for (t, _), p in zip(ticks, positions) if t >= steady_start]
    changes = sum(1 for p, q in zip(steady_positions, steady_positions[1:]) if p != q)
    changed = sum(1 for a, b in zip(steady_ticks, steady_ticks[1:])
                  if command(scan_axis, a[1][scan_axis]) != command(scan_axis, b[1][scan_axis]))
    sent = sum(1 for t, _ in per_axis_reports[scan_axis] if steady_start <= t <= play_end)
    # Gaps between successive positions the ticks read on the walls: from one change of position to
    # the next, kept when the force at either end is a wall's.
    on_wall = 0.1 * max((abs(f[scan_axis]) for _, f in steady_ticks), default=0.0)
    wall_gaps = {}
    read = [(p[scan_axis], f[scan_axis]) for (t, f), p in zip(ticks, positions) if t >= steady_start]
    last = 0
    for i in range(1, len(read)):
        if read[i][0] != read[last][0]:
            if on_wall > 0 and max(abs(read[i][1]), abs(read[last][1])) > on_wall:
                um = round(abs(read[i][0] - read[last][0]) * 1e6)
                wall_gaps[um] = wall_gaps.get(um, 0) + 1
            last = i
    steady_s = (play_end - steady_start) * 1e-9
    # The hand's speed as the ticks saw it on the guest's clock: the median over 50 ms windows of
    # the steady play (a scan's turns are a few of them).
    steady_trace = [(t, p[scan_axis]) for (t, _), p in zip(ticks, positions) if t >= steady_start]
    speeds, j = [], 0
    for t, x in steady_trace:
        while j < len(steady_trace) and steady_trace[j][0] < t + 50_000_000:
            j += 1
        if j < len(steady_trace):
            speeds.append(abs(steady_trace[j][1] - x) / ((steady_trace[j][0] - t) * 1e-9))
    return {
        "seconds": seconds,
        "received_hz": [received[a] / seconds for a in (0, 1)],
        "updates_hz": [applied[a] / seconds for a in (0, 1)],
        "latency_ms": {"p50": percentile(latencies, 0.5), "p99": percentile(latencies, 0.99), "n": len(latencies)},
        "steady_s": steady_s,
        "firmware_peak_N": sum(ridges) / len(ridges) if ridges else None,
        "ridges": len(ridges),
        "commanded_peak_N": mean_ridge_peak([f[scan_axis] for _, f in steady_ticks]),
        "position_rate_hz": changes / steady_s if steady_s > 0 else None,
        "wall_gaps_m": sorted((um * 1e-6, n) for um, n in wall_gaps.items() if um > 0),
        "changes_sent": sent / changed if changed else None,
        "command_rate_hz": forcing_applied / (forcing_ns * 1e-9) if forcing_ns > 0 else None,
        "command_median_gap_ms": command_gap_ns * 1e-6 if command_gap_ns else None,
        "hand_speed_m_s": percentile(speeds, 0.5),
        "firmware_max_N": max((abs(f) for f in firmware_forces), default=0.0),
        "rms_error_N": math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else None,
        "unmatched_reports": unmatched,
    }


def rates_on_the_firmwares_clock(m: dict, speed_mm_s: float) -> tuple:
    """(position_rate_hz, command_rate_hz) of measure()'s result `m`, per second of the firmware's
    clock. The lab's hand moves one FFB period per control step (OpenFFBoardFirmware::move_stick),
    so at the nominal speed on the firmware's clock; a guest that runs fewer steps than periods moves
    it slower on the guest's clock, where the ticks and the bus count. explain reads the grating
    at its nominal speed, so the rates go to the same clock: times nominal / measured speed."""
    hand = m.get("hand_speed_m_s")
    scale = speed_mm_s * 1e-3 / hand if hand else 1.0
    return tuple(m[k] * scale if m.get(k) else None for k in ("position_rate_hz", "command_rate_hz"))


def predicted_peaks_over_gaps(sandpaper: Path, material: Path, device: str, speed_mm_s: float, m: dict) -> dict:
    """explain's prediction for the positions `m` (measure()'s result) read on the walls: for each
    gap g of m["wall_gaps_m"], explain's entry with evenly spaced positions g apart (position rate
    speed / g on the firmware's clock, where the hand moves at its nominal speed), averaged with
    weights g x count (a wall's peak falls in a gap in proportion to its length). Without wall gaps,
    explain's entry at the run's position rate. Commands: when the bus sent at least 95 % of the
    ticks' changes (m["changes_sent"]), the device file's bus interval, as explain assumes (the
    driver sends each change at the next frame, so commands follow the positions, not a clock of
    their own); else the run's command rate. The mean of commanded_peak_N, device_peak_N and
    damping_N; "gaps": how many gaps were weighed; "command_rate_hz": the rate given to explain
    (None: the bus interval)."""
    position_hz, command_hz = rates_on_the_firmwares_clock(m, speed_mm_s)
    if (m.get("changes_sent") or 0) >= 0.95:
        command_hz = None
    gaps = m.get("wall_gaps_m") or []
    if not gaps:
        entry = predicted_device_peak(sandpaper, material, device, speed_mm_s, position_hz, command_hz)
        return {**entry, "gaps": 0, "command_rate_hz": command_hz}
    # Gaps within 2 % of each other are one class: explain's answer changes little across them,
    # and each class is one explain run.
    classes = []
    for g, n in sorted(gaps):
        if classes and g <= classes[-1][0] * 1.02:
            c = classes[-1]
            c[1] += g * n
            c[2] += n
        else:
            classes.append([g, g * n, n])
    total = sum(c[1] for c in classes)
    mean = {"commanded_peak_N": 0.0, "device_peak_N": 0.0, "damping_N": 0.0}
    for _, weight, n in classes:
        g = weight / n  # the class's mean gap
        entry = predicted_device_peak(sandpaper, material, device, speed_mm_s, speed_mm_s * 1e-3 / g, command_hz)
        for k in mean:
            mean[k] += weight / total * entry[k]
    return {**mean, "gaps": sum(n for _, n in gaps), "command_rate_hz": command_hz}


def predicted_device_peak(sandpaper: Path, material: Path, device: str, speed_mm_s: float,
                          position_rate_hz: float | None, command_rate_hz: float | None = None) -> dict:
    """explain's prediction of what `device` outputs as a hand scans `material` at `speed_mm_s`,
    the ticks reading the grating at `position_rate_hz` (None: the servo rate) and new commands
    reaching the firmware at `command_rate_hz` (None: the device file's bus interval): the entry of
    `sandpaper explain --json`'s device_output_at_speed for that speed (docs/USB_PID.md)."""
    cmd = [str(sandpaper), "explain", str(material), "--device", device, "--json", "--design-speed", str(speed_mm_s)]
    if position_rate_hz:
        cmd += ["--position-rate", str(position_rate_hz)]
    if command_rate_hz:
        cmd += ["--command-rate", str(command_rate_hz)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    for entry in json.loads(out).get("device_output_at_speed", []):
        if abs(entry["speed_mm_s"] - speed_mm_s) < 1e-9:
            return entry
    raise ValueError(f"explain gave no device output at {speed_mm_s} mm/s for {material} on {device}")
