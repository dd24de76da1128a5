#!/usr/bin/env python3
"""The player's start-up time and memory (docs/performance.md, "A player that is only a runtime").

  python3 bench/player_bench.py BIN_DIR [--old-sandpaper OLD_BIN] [--seconds 60] [--json-out FILE]

Measures, for the runtime-only `sandpaper-play` (and, side by side, a previous build's `sandpaper`
when given): the median wall time of `--help` over 40 runs; the maximum resident set size of
playing a 2.5 mm grating at 1 kHz for SECONDS (memory locked when the servo gets SCHED_FIFO);
and the same for a 4096 x 4096 height-field program, against the size of its grids.
Printed and written as JSON, never asserted: timing on a shared machine is noisy.
"""
import argparse, json, os, resource, statistics, subprocess, sys, tempfile, time


def median_start_ms(cmd, runs=40):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        times.append((time.perf_counter() - t0) * 1e3)
    return statistics.median(times)


def max_rss_mb(cmd):
    """Runs cmd to completion in a fresh child (via a tiny wrapper, so RUSAGE_CHILDREN is its own)."""
    j = run_measured(cmd)
    return j["maxrss_kb"] / 1024.0, j["rc"], j["out"]


def run_measured(cmd):
    """Wall time (s), maximum RSS (KB), exit code and stdout of cmd, run in a fresh wrapper process."""
    wrapper = ("import resource, subprocess, sys, json, time;"
               "t = time.perf_counter();"
               "r = subprocess.run(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.PIPE);"
               "t = time.perf_counter() - t;"
               "print(json.dumps({'rc': r.returncode, 'maxrss_kb': resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss,"
               "'seconds': t, 'out': r.stdout.decode(errors='replace'), 'err': r.stderr.decode(errors='replace')}))")
    out = subprocess.run([sys.executable, "-c", wrapper, *cmd], stdout=subprocess.PIPE, check=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin_dir")
    ap.add_argument("--old-sandpaper", help="a previous build's sandpaper binary, measured side by side")
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--json-out")
    a = ap.parse_args()
    sp = os.path.join(a.bin_dir, "sandpaper")
    play = os.path.join(a.bin_dir, "sandpaper-play")
    results = {"seconds": a.seconds}
    with tempfile.TemporaryDirectory() as tmp:
        grating = os.path.join(tmp, "grating.patch")
        subprocess.run([sp, "compile", "-e", "roughness 0.6; grating period 2.5 mm", "-o", grating], check=True,
                       stdout=subprocess.DEVNULL)
        # A 4096 x 4096 height field: the shipped gravel photograph scaled up (oiiotool, OpenImageIO's own).
        here = os.path.dirname(os.path.abspath(__file__))
        photo = os.path.join(here, "..", "library", "images", "gravel.png")
        big = os.path.join(tmp, "big.png")
        hf = os.path.join(tmp, "big.patch")
        have_big = False
        if os.path.exists(photo):
            subprocess.run(["oiiotool", photo, "--resize", "4096x4096", "-d", "uint16", "-o", big], check=True)
            with open(os.path.join(tmp, "big.hmat"), "w") as f:
                f.write('material "big" {\n  heightmap "big.png" size 204.8 mm\n  roughness 0.6\n}\n')
            compiles = {}
            for label, extra, out_file in (("float32", [], hf), ("--compact", ["--compact"], os.path.join(tmp, "big-compact.patch"))):
                j = run_measured([sp, "compile", os.path.join(tmp, "big.hmat"), "-o", out_file, *extra])
                compiles[label] = {"seconds": j["seconds"], "max_rss_MB": j["maxrss_kb"] / 1024.0, "rc": j["rc"],
                                   "patch_MB": os.path.getsize(out_file) / 2**20 if j["rc"] == 0 else None}
                if j["rc"] != 0:
                    print("4096^2 height field did not compile:", j["err"].strip()[:400])
            if a.old_sandpaper:
                j = run_measured([a.old_sandpaper, "compile", os.path.join(tmp, "big.hmat"), "-o", os.path.join(tmp, "old.patch")])
                compiles["previous build"] = {"seconds": j["seconds"], "max_rss_MB": j["maxrss_kb"] / 1024.0, "rc": j["rc"]}
            results["heightfield_4096_compile"] = compiles
            results["heightfield_grids_MB"] = 2 * 4096 * 4096 * 4 / 2**20
            have_big = compiles["float32"]["rc"] == 0
        results["start_ms"] = {"sandpaper-play --help": median_start_ms([play, "--help"]),
                               "sandpaper --help": median_start_ms([sp, "--help"])}
        if a.old_sandpaper:
            results["start_ms"]["previous sandpaper --help"] = median_start_ms([a.old_sandpaper, "--help"])
        run = ["run", grating, "--duration", str(a.seconds), "--json"]
        rss = {}
        mb, rc, out = max_rss_mb([play, grating, "--duration", str(a.seconds), "--json"])
        rep = json.loads(out) if rc == 0 else {}
        rss["sandpaper-play grating"] = {"max_rss_MB": mb, "rc": rc, "memory_locked": rep.get("memory_locked"),
                                         "realtime": rep.get("realtime_scheduling"), "stalls": rep.get("stalls"),
                                         "overruns": rep.get("overruns"), "ticks": rep.get("ticks")}
        if a.old_sandpaper:
            mb, rc, out = max_rss_mb([a.old_sandpaper, *run])
            rss["previous sandpaper run grating"] = {"max_rss_MB": mb, "rc": rc}
        if have_big:
            short = ["--duration", "5", "--json"]
            mb, rc, _ = max_rss_mb([play, os.path.join(tmp, "big-compact.patch"), *short])
            rss["sandpaper-play 4096^2 height field, --compact patch (5 s)"] = {"max_rss_MB": mb, "rc": rc}
            mb, rc, _ = max_rss_mb([play, hf, *short])
            rss["sandpaper-play 4096^2 height field (5 s)"] = {"max_rss_MB": mb, "rc": rc}
            if a.old_sandpaper:
                mb, rc, _ = max_rss_mb([a.old_sandpaper, "run", hf, *short])
                rss["previous sandpaper run 4096^2 height field (5 s)"] = {"max_rss_MB": mb, "rc": rc}
        results["rss"] = rss
    print(json.dumps(results, indent=2))
    if a.json_out:
        with open(a.json_out, "w") as f:
            json.dump(results, f, indent=2)


if __name__ == "__main__":
    main()
