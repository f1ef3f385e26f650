#!/usr/bin/env python3
"""Startup cost of rtprof: the whole-process wall time of tiny commands, and where a
1x1 render's time goes.

Runs, interleaved (one round = each command once, the order rotating from round to
round so that no command always follows the same one), N times each:

  true      /bin/true                                   (the floor: fork + exec + wait)
  version   rtprof --version                            (loader + runtime + clap)
  render    rtprof render one-sphere.nff --size 1x1 -o <tmp>.png
  traced    the same render with RTPROF_TRACE_STARTUP=1 (for the breakdown only; its
            wall time is not reported with the others)

and prints the median, minimum and 90th percentile wall time of each (from just before
posix_spawn to the return of wait4, in this process), with the median CPU time (user +
system) the child used. With --before OLD, OLD's --version and render (and its traced
render, if OLD prints marks) run in the same rounds, for a before/after comparison on
the same machine state.

The breakdown: with RTPROF_TRACE_STARTUP=1 rtprof prints, at its end, CLOCK_MONOTONIC
time stamps of its phase boundaries (terminal/src/startup.rs). This script takes the spawn time
and the wait4 return on the same clock, so the time before main (fork, exec, dynamic
loading and relocation, Rust runtime init) and after the last mark (returning from
main, destructors, exit, wait) are measured too. Each phase is the median over the
traced runs; the durations rtprof measured inside a phase (render.preprocessing and
render.tracing, as `rtprof render` prints them) are listed under it with the rest of
the phase.

Usage: scripts/startup-cost.py [--runs N] [--rtprof PATH] [--before PATH]
(--rtprof defaults to $CARGO_TARGET_DIR or target/, release/rtprof.)
Standard library only (python3 >= 3.8, Linux).
"""

import argparse
import os
import re
import statistics
import sys
import tempfile
import time

# One sphere in front of the eye, one light: the smallest whole scene.
ONE_SPHERE_NFF = """\
v
from 0 0 -5
at 0 0 0
up 0 1 0
angle 40
hither 1
resolution 1 1
b 0.1 0.1 0.1
l 5 5 -5
f 0.8 0.2 0.2 1 0 0 0 0
s 0 0 0 1
"""

TRACE_VARIABLE = "RTPROF_TRACE_STARTUP"
MARK = re.compile(r"^rtprof startup: at (\S+) \+(\d+\.\d+) ms(?: \(CLOCK_MONOTONIC (\d+) ns\))?$")
TOOK = re.compile(r"^rtprof startup: took (\S+) (\d+\.\d+) ms$")


def default_rtprof():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    target = os.environ.get("CARGO_TARGET_DIR") or os.path.join(root, "target")
    return os.path.join(target, "release", "rtprof")


def run(argv, env, stderr_path=None):
    """Runs argv with stdout (and stderr unless stderr_path) to /dev/null; returns
    (spawn ns, exit ns, CPU seconds, status) on CLOCK_MONOTONIC."""
    actions = [
        (os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
        (os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0),
        (
            os.POSIX_SPAWN_OPEN,
            2,
            stderr_path or os.devnull,
            os.O_WRONLY | os.O_CREAT | os.O_TRUNC,
            0o644,
        ),
    ]
    start = time.monotonic_ns()
    pid = os.posix_spawn(argv[0], argv, env, file_actions=actions)
    _, status, usage = os.wait4(pid, 0)
    end = time.monotonic_ns()
    return start, end, usage.ru_utime + usage.ru_stime, status


def percentile(values, p):
    ordered = sorted(values)
    index = min(len(ordered) - 1, max(0, round(p / 100 * (len(ordered) - 1))))
    return ordered[index]


def breakdown(stderr_text, spawn_ns, exit_ns):
    """The phases of one traced run, ([(name, ms)] in order, [(name, ms)] measured
    inside them), or None when rtprof printed no marks."""
    marks, took = [], []
    for line in stderr_text.splitlines():
        m = MARK.match(line)
        if m:
            marks.append((m.group(1), float(m.group(2)), m.group(3)))
            continue
        t = TOOK.match(line)
        if t:
            took.append((t.group(1), float(t.group(2))))
    if not marks or marks[0][0] != "main" or marks[0][2] is None:
        return None  # an rtprof without RTPROF_TRACE_STARTUP
    main_ns = int(marks[0][2])
    phases = [("spawn to main (exec, loader, runtime init)", (main_ns - spawn_ns) / 1e6)]
    for (_, before, _), (name, at, _) in zip(marks, marks[1:]):
        phases.append((f"to {name}", at - before))
    phases.append(("last mark to wait4 return (exit)", (exit_ns - main_ns) / 1e6 - marks[-1][1]))
    return phases, took


def measure(args, tmp):
    """Runs the rounds. Returns (commands, walls, cpus, traces): commands as (name,
    argv), walls and cpus in ms by command name, traces as {binary label: [(phases,
    took)]} for the binaries that print startup marks."""
    scene = os.path.join(tmp, "one-sphere.nff")
    with open(scene, "w") as f:
        f.write(ONE_SPHERE_NFF)
    image = os.path.join(tmp, "out.png")
    trace = os.path.join(tmp, "trace.txt")
    env = {k: v for k, v in os.environ.items() if k != TRACE_VARIABLE}
    env["RTPROF_PROGRESS"] = "never"
    traced_env = dict(env, **{TRACE_VARIABLE: "1"})

    def render(binary):
        return [binary, "render", scene, "--size", "1x1", "-o", image]

    binaries = [("rtprof", os.path.abspath(args.rtprof))]
    if args.before:
        binaries = [("before", os.path.abspath(args.before)), ("after", binaries[0][1])]
    commands = [("true", ["/bin/true"])]
    for label, binary in binaries:
        prefix = "" if label == "rtprof" else label + " "
        commands += [(prefix + "--version", [binary, "--version"])]
        commands += [(prefix + "render 1x1", render(binary))]
    for _, argv in commands:
        if run(argv, env)[3] != 0:
            sys.exit(f"startup-cost: {' '.join(argv)} failed")
    traced = []  # (label, argv) of the binaries that print marks
    for label, binary in binaries:
        start, end, _, status = run(render(binary), traced_env, trace)
        with open(trace) as f:
            if status == 0 and breakdown(f.read(), start, end):
                traced.append((label, render(binary)))
    jobs = [(name, argv, False) for name, argv in commands]
    jobs += [(label, argv, True) for label, argv in traced]

    walls = {name: [] for name, _ in commands}
    cpus = {name: [] for name, _ in commands}
    traces = {label: [] for label, _ in traced}
    for i in range(args.runs):
        shift = i % len(jobs)
        for name, argv, is_traced in jobs[shift:] + jobs[:shift]:
            if is_traced:
                start, end, _, _ = run(argv, traced_env, trace)
                with open(trace) as f:
                    one = breakdown(f.read(), start, end)
                if one:
                    traces[name].append(one)
                continue
            start, end, cpu, _ = run(argv, env)
            walls[name].append((end - start) / 1e6)
            cpus[name].append(cpu * 1e3)
    return commands, walls, cpus, traces


def phase_medians(runs):
    """{phase or inner duration: median ms} over the traced runs of one binary, in the
    order printed: each phase, then the durations measured inside it and its rest."""
    medians = {}
    names = [name for name, _ in runs[0][0]]
    took_names = [name for name, _ in runs[0][1]]
    whole = [r for r in runs if len(r[0]) == len(names) and len(r[1]) == len(took_names)]
    for k, name in enumerate(names):
        medians[name] = statistics.median(r[0][k][1] for r in whole)
        # Durations rtprof measured inside this phase ("render.tracing" in "to render").
        inner = [(j, t) for j, t in enumerate(took_names) if name == "to " + t.split(".")[0]]
        for j, label in inner:
            medians["  " + label] = statistics.median(r[1][j][1] for r in whole)
        if inner:
            rest = [r[0][k][1] - sum(r[1][j][1] for j, _ in inner) for r in whole]
            medians["  " + inner[0][1].split(".")[0] + ".rest"] = statistics.median(rest)
    medians["(sum of the phases)"] = sum(medians[n] for n in names)
    return medians


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=50, help="runs of each command (50)")
    parser.add_argument("--rtprof", default=default_rtprof(), help="the rtprof binary")
    parser.add_argument("--before", help="an older rtprof binary to compare, interleaved")
    args = parser.parse_args()
    if args.runs < 1:
        sys.exit("startup-cost: --runs must be at least 1")
    with tempfile.TemporaryDirectory(prefix="rtprof-startup-") as tmp:
        commands, walls, cpus, traces = measure(args, tmp)

    print(f"whole process, {args.runs} runs each, interleaved (ms):")
    print(f"  {'command':<20} {'median':>7} {'min':>7} {'p90':>7} {'cpu med':>8}")
    for name, _ in commands:
        w = walls[name]
        print(
            f"  {name:<20} {statistics.median(w):7.2f} {min(w):7.2f} "
            f"{percentile(w, 90):7.2f} {statistics.median(cpus[name]):8.2f}"
        )
    if not traces:
        print(f"\nno rtprof printed startup marks ({TRACE_VARIABLE}=1): no breakdown")
        return
    columns = {label: phase_medians(runs) for label, runs in traces.items()}
    rows = []
    for medians in columns.values():
        rows += [name for name in medians if name not in rows]
    rows.append(rows.pop(rows.index("(sum of the phases)")))
    print(f"\nrender 1x1 by phase ({TRACE_VARIABLE}=1, median of {args.runs} runs, ms):")
    print(f"  {'phase':<48}" + "".join(f" {label:>7}" for label in columns))
    for name in rows:
        cells = "".join(
            f" {medians[name]:7.3f}" if name in medians else f" {'-':>7}"
            for medians in columns.values()
        )
        print(f"  {name:<48}{cells}")


if __name__ == "__main__":
    main()
