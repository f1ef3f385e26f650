#!/usr/bin/env python3
"""What the probe costs (docs/instrumenting.md, "What it costs"), on the C fixture
(probe/tests/c/spheres.c, brute-force spheres) and on RTIOW (scripts/rtiow-probe.sh).

    scripts/probe-cost.py [--rounds N] [--work DIR] [--no-valgrind]

Four builds or settings of each program:
  out       compiled out (-DRTPROF_DISABLE): the baseline;
  off       compiled in, no RTPROF_PROBE_FILE: one flag test per macro;
  counters  on, RTPROF_PROBE_HZ=0: counters only (phase marks stay one flag test);
  phases    on, RTPROF_PROBE_HZ=1000: counters, phase marks and the sampler.

Two measures:
  instructions  valgrind --tool=cachegrind --cache-sim=no (exact and repeatable; the
                sampler's share is overstated there: valgrind runs ~50x slower, so the
                CPU-time timer fires ~50x more often per instruction);
  CPU time      user + system time of each run (os.wait4), the four settings run in
                turn, N rounds (default 15); each round's ratio to that round's `out`
                run; the median ratio with the 2.5 and 97.5 percentiles of a bootstrap
                of the rounds' median (a shared machine: rounds interleave so drift hits
                every setting alike).
Prints a Markdown table; exits 1 when a setting exceeds its budget (off 1 %, counters
5 %, phases 10 %): judged on the instruction counts when valgrind is there (exact; the
CPU times move by a few percent with code layout alone: the fixture compiled in runs
faster than compiled out), else on the median CPU-time ratio.
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUDGET = {"off": 0.01, "counters": 0.05, "phases": 0.10}
SETTINGS = ["out", "off", "counters", "phases"]


def build(work):
    """The two programs' two binaries: {program: {"out": path, "in": path}}."""
    fixture = os.path.join(ROOT, "probe/tests/c/spheres.c")
    bins = {"fixture": {}, "rtiow": {}}
    for variant, flags in [("out", ["-DRTPROF_DISABLE"]), ("in", [])]:
        path = os.path.join(work, f"spheres-{variant}")
        subprocess.run(
            [os.environ.get("CC", "cc"), "-std=c99", "-O2", "-g", "-pthread", "-I",
             os.path.join(ROOT, "probe"), *flags, fixture, "-o", path, "-lm"],
            check=True)
        bins["fixture"][variant] = path
        out = subprocess.run(
            ["bash", os.path.join(ROOT, "scripts/rtiow-probe.sh"),
             os.path.join(work, f"rtiow-{variant}"), "probe", *flags],
            check=True, capture_output=True, text=True)
        bins["rtiow"][variant] = out.stdout.strip()
    return bins


def command(bins, program, setting, args, probe_file):
    """(argv, environment) of one run."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("RTPROF_PROBE")}
    binary = bins[program]["out" if setting == "out" else "in"]
    if setting in ("counters", "phases"):
        env["RTPROF_PROBE_FILE"] = probe_file
        env["RTPROF_PROBE_HZ"] = "0" if setting == "counters" else "1000"
    return [binary, *args], env


def cpu_seconds(argv, env):
    """User + system seconds of one run (its output discarded)."""
    with open(os.devnull, "wb") as null:
        child = subprocess.Popen(argv, env=env, stdout=null, stderr=null)
        _, status, usage = os.wait4(child.pid, 0)
    if status != 0:
        sys.exit(f"probe-cost: {argv} failed ({status})")
    return usage.ru_utime + usage.ru_stime


def instructions(argv, env):
    out = subprocess.run(
        ["valgrind", "--tool=cachegrind", "--cache-sim=no",
         "--cachegrind-out-file=/dev/null", *argv],
        env=env, capture_output=True, text=True, check=True)
    match = re.search(r"I\s+refs:\s+([\d,]+)", out.stderr)
    if not match:
        sys.exit(f"probe-cost: no instruction count from valgrind for {argv}")
    return int(match.group(1).replace(",", ""))


def median(values):
    s = sorted(values)
    n = len(s)
    return s[n // 2] if n % 2 else (s[n // 2 - 1] + s[n // 2]) / 2


def bootstrap(ratios, rng):
    """2.5 and 97.5 percentiles of the median over 2000 resamples."""
    medians = sorted(median([rng.choice(ratios) for _ in ratios]) for _ in range(2000))
    return medians[50], medians[1949]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--work", help="build directory (default: a temporary one)")
    parser.add_argument("--no-valgrind", action="store_true")
    options = parser.parse_args()
    if options.rounds < 3:
        sys.exit("probe-cost: --rounds must be at least 3")
    work = options.work or tempfile.mkdtemp(prefix="rtprof-probe-cost-")
    os.makedirs(work, exist_ok=True)
    bins = build(work)
    probe_file = os.path.join(work, "probe.txt")
    # Workloads: about 0.3 s each natively; smaller under valgrind (about 20 s there).
    timed = {"fixture": ["320", "240", "1", "80"], "rtiow": ["4", "300"]}
    counted = {"fixture": ["320", "240", "1", "4"], "rtiow": ["2", "200"]}
    use_valgrind = not options.no_valgrind and shutil.which("valgrind")
    rng = random.Random(57)
    failed = False
    print("| program | setting | instructions | vs out | CPU time: median ratio to out "
          "| 95 % interval | budget |")
    print("|---|---|---:|---:|---:|---|---:|")
    for program in ["fixture", "rtiow"]:
        counts = {}
        if use_valgrind:
            for setting in SETTINGS:
                counts[setting] = instructions(
                    *command(bins, program, setting, counted[program], probe_file))
        times = {s: [] for s in SETTINGS}
        for _ in range(options.rounds):
            order = SETTINGS[:]
            rng.shuffle(order)
            for setting in order:
                times[setting].append(
                    cpu_seconds(*command(bins, program, setting, timed[program], probe_file)))
        for setting in SETTINGS:
            ratios = [t / o for t, o in zip(times[setting], times["out"])]
            mid = median(ratios)
            low, high = bootstrap(ratios, rng)
            if setting == "out":
                instr = f"{counts['out']:,}" if counts else "-"
                print(f"| {program} | out | {instr} | 1 | {median(times['out']):.3f} s "
                      f"(median) | | |")
                continue
            instr = f"{counts[setting]:,}" if counts else "-"
            extra = (f"{counts[setting] / counts['out'] - 1:+.2%}" if counts else "-")
            budget = BUDGET[setting]
            judged = counts[setting] / counts["out"] if counts else mid
            over = judged - 1 > budget
            failed |= over
            print(f"| {program} | {setting} | {instr} | {extra} | {mid - 1:+.2%} "
                  f"| {low - 1:+.2%} to {high - 1:+.2%} | {budget:.0%}{' OVER' if over else ''} |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
