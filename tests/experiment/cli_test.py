#!/usr/bin/env python3
"""`sandpaper experiment` end to end, as a lab would use it (issue 13's "done when"): the shipped
example design run for eight simulated subjects on the simulated joystick, analysed, the fitted map
installed into a calibration folder and used by a compile whose `explain` names it; a design with
bad stimuli refused before any trial; a session killed with SIGKILL mid-trial and resumed in the
same order; pooling of different designs refused."""
import argparse
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checklist import Checklist  # noqa: E402

DESIGN = "examples/experiments/roughness-magnitude.toml"
SIM = "simulated:exponent=0.76,noise=0.15,seed=3"


def run(sp, *args, **kw):
    return subprocess.run([sp, *args], capture_output=True, text=True, timeout=300, **kw)


def answers(folder):
    with open(os.path.join(folder, "results.jsonl")) as f:
        return [json.loads(l) for l in f if l.strip() and json.loads(l)["record"] == "answer"]


class Stderr:
    """Collects a process's stderr as it arrives; wait_for blocks until a text appears (no sleeps)."""

    def __init__(self, proc):
        self.text = ""
        self.closed = False
        self.cond = threading.Condition()
        self.proc = proc
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        while True:
            b = self.proc.stderr.read1(4096) if hasattr(self.proc.stderr, "read1") else self.proc.stderr.read(1)
            with self.cond:
                if not b:
                    self.closed = True
                    self.cond.notify_all()
                    return
                self.text += b.decode()
                self.cond.notify_all()

    def wait_closed(self, timeout=60):
        """Everything the process wrote, once it has closed stderr (exited)."""
        with self.cond:
            self.cond.wait_for(lambda: self.closed, timeout)
            return self.text

    def wait_for(self, needle, count=1, timeout=60):
        with self.cond:
            return self.cond.wait_for(lambda: self.text.count(needle) >= count or self.proc.poll() is not None, timeout) \
                and self.text.count(needle) >= count


def start_terminal(sp, folder, subject):
    """A session answered at the terminal (stdin a pipe), its stderr collected, at its first question."""
    p = subprocess.Popen([sp, "experiment", "run", DESIGN, "--subject", subject, "-o", folder, "--virtual-clock"],
                         stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    err = Stderr(p)
    ready = err.wait_for("Press Enter to begin")
    p.stdin.write(b"\n")
    p.stdin.flush()
    return p, err, ready


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sandpaper", required=True)
    sp = ap.parse_args().sandpaper
    c = Checklist()
    tmp = tempfile.mkdtemp(prefix="sandpaper-experiment-")
    try:
        cal = os.path.join(tmp, "calibration")
        shutil.copytree("calibration", cal)
        results = os.path.join(tmp, "results")

        # Eight simulated subjects on the example design.
        ok = True
        for s in range(1, 9):
            r = run(sp, "experiment", "run", DESIGN, "--subject", f"S0{s}", "-o", os.path.join(results, f"S0{s}"),
                    "--observer", SIM, "--virtual-clock", "--calibration", cal)
            ok = ok and r.returncode == 0 and "all 40 trials answered" in r.stdout
        c.check(ok, "the example design runs for 8 simulated subjects on the simulated joystick")
        c.check(len(answers(os.path.join(results, "S01"))) == 40, "every answer is in the results file (4 practice + 36)")

        r = run(sp, "experiment", "analyse", results, "--json")
        rep = json.loads(r.stdout) if r.returncode == 0 else {}
        me = rep.get("magnitude_estimation", {})
        c.check(r.returncode == 0 and rep.get("subjects") == 8 and me.get("n_trials") == 288,
                f"analyse --json pools 8 subjects, 288 trials (exit {r.returncode})")
        keys = ["slope", "slope_se", "intercept", "intercept_se", "r2", "r2_adj", "s", "df", "f", "subjects", "n_trials"]
        c.check(all(k in me for k in keys), "magnitude_estimation has calibrate fit's keys plus n_trials and subjects")
        fit = json.loads(run(sp, "calibrate", "fit", "examples/calibration/roughness-responses.csv", "--json").stdout)
        c.check(all(k in fit for k in keys[:9]), "calibrate fit --json has the same statistics keys")
        if me:
            c.check(abs(me["slope"] - 0.76) < 2 * me["slope_se"],
                    f"fitted slope {me['slope']:.4f} +- {me['slope_se']:.4f} is within two standard errors of 0.76")
        plot = me.get("plot", "")
        c.check(os.path.isfile(plot) and open(plot).read().startswith("<svg"), f"the fit's picture is written ({plot})")

        # Install the fitted map for the sim device and compile through it.
        map_path = os.path.join(cal, "maps", "sim-roughness.toml")
        r = run(sp, "experiment", "analyse", results, "--map-out", map_path, "--calibration", cal)
        c.check(r.returncode == 0 and os.path.isfile(map_path), f"--map-out writes {map_path} (exit {r.returncode}) {r.stderr}")
        text = open(map_path).read() if os.path.isfile(map_path) else ""
        c.check('use = "device"' in text and 'device = "sim"' in text and "8 subjects" in text and DESIGN in text,
                "the map is a device map for sim with its provenance (subjects, design)")
        r = run(sp, "experiment", "analyse", results, "--map-out", os.path.join(cal, "maps", "sim-roughness-2.toml"))
        c.check(r.returncode == 1 and "already has a roughness map" in r.stderr
                and not os.path.exists(os.path.join(cal, "maps", "sim-roughness-2.toml")),
                "a second roughness map for the same device is refused (the folder stays loadable)")
        r = run(sp, "experiment", "analyse", results, "--map-out", map_path, "--calibration", cal)
        c.check(r.returncode == 0, "re-fitting into the same file replaces it")
        r = run(sp, "explain", "-e", "grating period 2.5 mm; roughness 0.6", "--calibration", cal)
        c.check(r.returncode == 0 and "via sim-roughness (" in r.stdout and "compile     sim-roughness" in r.stdout,
                "explain names the fitted map as the one that compiled roughness 0.6")
        c.check("comparison  minsky1995-fig19" in r.stdout, "and lists the 1995 map beside it as a comparison")
        r = run(sp, "compile", "-e", "grating period 2.5 mm; roughness 0.6", "--calibration", cal, "--json", "-o",
                os.path.join(tmp, "x.patch"))
        got = json.loads(r.stdout).get("compiled_max_lateral_force_N") if r.returncode == 0 else None
        want = 3.74614 * 0.6 ** (1 / me.get("slope", 1))
        c.check(got is not None and abs(got - want) < 1e-3 * want,
                f"compile --device sim asks for F = 3.746 N x 0.6^(1/slope) = {want:.4f} N (got {got})")
        r = run(sp, "explain", "-e", "grating period 2.5 mm; roughness 0.6", "--calibration", cal, "--device",
                "openffboard-2axis")
        c.check(r.returncode == 0 and "compile     minsky1995-fig19" in r.stdout and "sim-roughness" not in r.stdout,
                "another device still compiles through the 1995 map")

        # A bad design is refused whole, before the first trial.
        bad = os.path.join(tmp, "bad.toml")
        with open(DESIGN) as f:
            design = f.read()
        with open(bad, "w") as f:
            f.write(design.replace('"a1p7", "a3p7"', '"a1p7", "corduroyy", "a1p100", "a3p7"'))
        r = run(sp, "experiment", "run", bad, "--subject", "S01", "-o", os.path.join(tmp, "bad-results"),
                "--observer", SIM, "--virtual-clock")
        c.check(r.returncode == 1 and "`corduroyy` does not compile" in r.stderr and "`a1p100` lies in the low-confidence region" in r.stderr,
                f"unknown and unbelievable stimuli are both listed (exit {r.returncode})")
        c.check(not os.path.exists(os.path.join(tmp, "bad-results")), "and nothing is written")
        r = run(sp, "experiment", "run", DESIGN, "--subject", "S01", "-o", os.path.join(results, "S01"), "--observer", SIM,
                "--virtual-clock")
        c.check(r.returncode == 1 and "already holds results" in r.stderr, "run into a used results folder is refused")
        with open(os.path.join(tmp, "fast.toml"), "w") as f:
            f.write(design.replace('device = "sim"', 'device = "sandpaper-1995"'))  # a 900 Hz joystick
        r = run(sp, "experiment", "run", os.path.join(tmp, "fast.toml"), "--subject", "S01", "-o", os.path.join(tmp, "fast"),
                "--observer", SIM, "--virtual-clock")
        c.check(r.returncode == 2 and "900" in r.stderr and not os.path.exists(os.path.join(tmp, "fast")),
                f"a servo rate the device refuses is a usage error before any folder is made (exit {r.returncode})")
        r = run(sp, "experiment", "run", DESIGN, "--subject", "S01", "-o", os.path.join(tmp, "x"), "--observer",
                "simulated:exponnent=1")
        c.check(r.returncode == 2 and "unknown parameter `exponnent`" in r.stderr, "a misspelt observer parameter is a usage error")

        # kill -9 in the middle of a session, then resume in the same order.
        killed = os.path.join(tmp, "killed", "S01")
        p, err, ready = start_terminal(sp, killed, "S01")
        for k in range(1, 4):
            ready = ready and err.wait_for("How rough", k)
            p.stdin.write(f"{k + 1}\n".encode())
            p.stdin.flush()
            ready = ready and err.wait_for(f"trial   {k} of 40")
        ready = ready and err.wait_for("How rough", 4)  # trial 4 presented, its answer not given
        p.send_signal(signal.SIGKILL)
        p.wait(timeout=60)
        c.check(ready and p.returncode == -signal.SIGKILL, "a terminal session is killed with SIGKILL at trial 4")
        got = answers(killed)
        c.check([a["response"] for a in got] == [2, 3, 4], f"the three answered trials are on disk ({len(got)})")
        with open(os.path.join(killed, "results.jsonl"), "a") as f:
            f.write('{"record":"answer","trial":3,"stim')  # as if killed while writing trial 4
        r = run(sp, "experiment", "resume", killed, "--observer", SIM, "--virtual-clock")
        c.check(r.returncode == 2 and "answered by observer `terminal`" in r.stderr and "--switch-observer" in r.stderr,
                f"resuming a terminal session with another observer is refused without --switch-observer (exit {r.returncode})")
        r = run(sp, "experiment", "resume", killed, "--observer", SIM, "--switch-observer", "--virtual-clock")
        c.check(r.returncode == 0 and "resuming at trial 4" in r.stderr and "all 40 trials answered" in r.stdout,
                f"resume continues at trial 4 and finishes (exit {r.returncode})")
        with open(os.path.join(killed, "results.jsonl")) as f:
            switches = [json.loads(l) for l in f if '"observer-switch"' in l]
        c.check(len(switches) == 1 and switches[0]["from"] == "terminal" and switches[0]["to"].startswith("simulated:")
                and switches[0]["trial"] == 3, f"the switch of observer is recorded at trial 4 ({switches})")
        got = answers(killed)
        ref = answers(os.path.join(results, "S01"))
        c.check([a["trial"] for a in got] == list(range(40)), "each trial answered once, in order")
        c.check([a["stimuli"] for a in got] == [a["stimuli"] for a in ref],
                "in the same order as an uninterrupted session of the same subject")
        r = run(sp, "experiment", "resume", killed, "--observer", SIM, "--virtual-clock")
        c.check(r.returncode == 0 and "every trial is answered already" in r.stdout, "resuming a finished session says so")

        # Ctrl-C while a question waits: the session stops cleanly and can be resumed.
        stopped = os.path.join(tmp, "stopped", "S02")
        p, err, ready = start_terminal(sp, stopped, "S02")
        p.stdin.write(b"3\n")
        p.stdin.flush()
        ready = ready and err.wait_for("trial   1 of 40") and err.wait_for("How rough", 2)
        p.send_signal(signal.SIGINT)
        # Not communicate(): it would read stderr too, away from the Stderr thread.
        p.stdin.close()
        out = p.stdout.read()
        p.wait(timeout=60)
        c.check(ready and p.returncode == 0 and b"continue with `sandpaper experiment resume" in out
                and "stopped at trial 2 of 40" in err.wait_closed(), f"Ctrl-C at a question stops the session (exit {p.returncode})")
        r = run(sp, "experiment", "resume", stopped, "--observer", SIM, "--switch-observer", "--virtual-clock")
        c.check(r.returncode == 0 and len(answers(stopped)) == 40, "and it resumes to the end")

        # A simulated session killed after 21 trials (results are flushed per trial: a kill -9 leaves
        # the header and the answered trials) resumes with its recorded observer, not the terminal.
        cut = os.path.join(tmp, "cut")
        shutil.copytree(os.path.join(results, "S02"), os.path.join(cut, "S02"))
        with open(os.path.join(cut, "S02", "results.jsonl")) as f:
            lines = f.readlines()
        with open(os.path.join(cut, "S02", "results.jsonl"), "w") as f:
            f.writelines(lines[:1 + 21])
        incomplete = os.path.join(tmp, "incomplete")
        for s in ("S01", "S03", "S04"):
            shutil.copytree(os.path.join(results, s), os.path.join(incomplete, s))
        shutil.copytree(os.path.join(cut, "S02"), os.path.join(incomplete, "S02"))
        r = run(sp, "experiment", "analyse", incomplete, "--json")
        rep = json.loads(r.stdout) if r.returncode == 0 else {}
        left = [x for x in rep.get("runs", []) if not x["included"]]
        c.check(r.returncode == 0 and rep.get("subjects") == 3 and len(left) == 1 and left[0]["subject"] == "S02"
                and left[0]["answered_recorded"] == 17 and left[0]["recorded_trials"] == 36
                and rep.get("magnitude_estimation", {}).get("n_trials") == 3 * 36,
                f"analyse leaves out S02, 17 of 36 recorded trials answered, and fits 3 subjects ({r.returncode}, {left})")
        r = run(sp, "experiment", "analyse", incomplete)
        c.check(r.returncode == 0 and "17 of 36 recorded trials answered, incomplete: left out" in r.stdout
                and "12 to practice trials, 108 to recorded trials" in r.stdout, f"and says so in text: {r.stdout[:400]}")
        r = run(sp, "experiment", "analyse", incomplete, "--json", "--include-incomplete")
        rep = json.loads(r.stdout) if r.returncode == 0 else {}
        c.check(r.returncode == 0 and rep.get("subjects") == 4 and rep.get("magnitude_estimation", {}).get("n_trials") == 3 * 36 + 17,
                "--include-incomplete pools it")
        r = run(sp, "experiment", "resume", os.path.join(cut, "S02"), "--virtual-clock", stdin=subprocess.DEVNULL)
        got = answers(os.path.join(cut, "S02"))
        c.check(r.returncode == 0 and "resuming at trial 22" in r.stderr and "observer simulated:" in r.stderr
                and "all 40 trials answered" in r.stdout, f"resume takes the recorded simulated observer (exit {r.returncode}) {r.stderr[-300:]}")
        c.check([a["trial"] for a in got] == list(range(40)), "and ends with every trial answered once")

        # Each dimension's design: six simulated subjects, the fitted map installed for the sim device,
        # and explain then compiles through it.
        for percept, design_file, exponent, predictor in (("softness", "softness-magnitude.toml", -0.8, "stiffness"),
                                                          ("viscosity", "viscosity-magnitude.toml", 0.42, "damping"),
                                                          ("slipperiness", "slipperiness-magnitude.toml", -1.0, "friction")):
            dres = os.path.join(tmp, "dim", percept)
            ok = True
            for s in range(1, 7):
                r = run(sp, "experiment", "run", "examples/experiments/" + design_file, "--subject", f"S0{s}", "-o",
                        os.path.join(dres, f"S0{s}"), "--observer", f"simulated:dimension={percept},noise=0.15,seed={s}",
                        "--virtual-clock", "--calibration", cal)
                ok = ok and r.returncode == 0
            c.check(ok, f"the {percept} design runs for 6 simulated subjects ({r.stderr[-300:]})")
            map_path = os.path.join(cal, "maps", f"sim-{percept}.toml")
            r = run(sp, "experiment", "analyse", dres, "--map-out", map_path, "--calibration", cal, "--json")
            rep = json.loads(r.stdout) if r.returncode == 0 else {}
            me = rep.get("magnitude_estimation", {})
            c.check(r.returncode == 0 and abs(me.get("slope", 99) - exponent) < 2 * me.get("slope_se", 0),
                    f"{percept}: slope {me.get('slope')} +- {me.get('slope_se')} recovers the observer's default exponent {exponent}")
            c.check(rep.get("map", {}).get("predictor") == predictor and os.path.isfile(map_path), f"{percept}: --map-out writes {map_path}")
            value = {"softness": "0.7", "viscosity": "0.5", "slipperiness": "0.6"}[percept]
            r = run(sp, "explain", "-e", f"{percept} {value}", "--device", "sim", "--calibration", cal, "--json")
            ex = json.loads(r.stdout) if r.returncode == 0 else {}
            pj = (ex.get("explain", ex).get("percepts") or [{}])[0]
            c.check(r.returncode == 0 and pj.get("map", {}).get("id") == f"sim-{percept}"
                    and abs(pj["map"]["slope"] - me.get("slope", 0)) < 1e-4,
                    f"{percept}: explain then compiles through the installed map ({pj.get('map', {}).get('id')})")

        # Runs of different designs are not pooled unless asked.
        other = os.path.join(tmp, "other.toml")
        with open(other, "w") as f:
            f.write(design.replace("repetitions = 3", "repetitions = 2"))
        r = run(sp, "experiment", "run", other, "--subject", "S09", "-o", os.path.join(results, "S09"), "--observer", SIM,
                "--virtual-clock")
        r = run(sp, "experiment", "analyse", results)
        c.check(r.returncode == 1 and "different designs" in r.stderr, "analyse refuses to pool different designs")
        r = run(sp, "experiment", "analyse", results, "--allow-mixed-designs", "--json")
        c.check(r.returncode == 0 and json.loads(r.stdout)["subjects"] == 9, "--allow-mixed-designs pools them")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return c.finish()


if __name__ == "__main__":
    sys.exit(main())
