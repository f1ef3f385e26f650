#!/usr/bin/env python3
"""The repository's performance baseline (benches/baseline.json): refresh it, or check a
run against it as .ci/run does. docs/benchmarks.md ("The performance baseline") says how
to read it and when to refresh it.

    scripts/perf-baseline.py refresh [--keep DIR]
        Builds the release binary as CI does (--features embree), runs the instruction
        counts (scripts/instruction-counts.sh) and the quick suite with Embree, and writes
        the suite's results.json, trimmed to what the gate reads, to benches/baseline.json
        (a temporary file, then renamed). Prints the strict gate of the new baseline
        against the old one, so that the commit message can say what moved and why.

    scripts/perf-baseline.py check RTPROF RESULTS.json
        `RTPROF gate --strict benches/baseline.json RESULTS.json`: exit 1 when it fails,
        with what to do. Then the rule on commit messages: the last commit that changed
        benches/baseline.json names why in a line `Perf-baseline: <reason>`.

The baseline is a results file of schema rtprof.results/3, so `rtprof gate`, `rtprof
report` and anything else that reads results read it too.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASELINE = os.path.join(ROOT, "benches", "baseline.json")
# The line a commit that changes the baseline must carry.
TRAILER = "Perf-baseline:"


def run(cmd, **kw):
    print("+", " ".join(cmd), file=sys.stderr)
    return subprocess.run(cmd, cwd=ROOT, check=True, **kw)


def target_dir():
    return os.environ.get("CARGO_TARGET_DIR") or os.path.join(ROOT, "target")


def trim(results):
    """What the gate reads: times, samples, counts, references, instruction counts. The
    pictures, histograms, profile, hardware model and per-pixel maps are left out."""
    results["profile"] = None
    results["hardware"] = None
    results["criterion"] = []
    for scene in results["scenes"]:
        scene["hardware"] = None
        scene["pixel_maps"] = []
        scene["bvh_quality"] = []
        for v in scene["variants"]:
            v["image"] = None
            v["heat_map"] = None
            v["histogram"] = []
            v["quality"] = None
            v["vs_f64_reference"] = None
            v["efficiency"] = None
            v["ray_rates"] = None
    # The instruction counts' file times say when they were measured on the machine
    # that measured them; in the tree they would change at every refresh.
    for count in results["instructions"]:
        count["measured"] = None
    return results


def dumps(results):
    """Indented JSON with each list of numbers on one line: a refresh's diff shows the
    entries that moved, one line each."""
    text = json.dumps(results, indent=1, ensure_ascii=False)
    return re.sub(
        r"\[\s*((?:-?[\d.eE+-]+,\s*)*-?[\d.eE+-]+)\s*\]",
        lambda m: "[" + re.sub(r",\s*", ", ", m.group(1)) + "]",
        text,
    ) + "\n"


def write_atomically(path, text):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".baseline-")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def refresh(args):
    keep = None
    if args[:1] == ["--keep"] and len(args) == 2:
        keep = args[1]
    elif args:
        sys.exit("usage: scripts/perf-baseline.py refresh [--keep DIR]")
    # What CI's build and instruction counts need (Embree's library, valgrind).
    run(["bash", "scripts/install-packages.sh", "libembree-dev", "valgrind"], stdout=subprocess.DEVNULL)
    run(["cargo", "build", "--release", "--features", "embree"])
    rtprof = os.path.join(target_dir(), "release", "rtprof")
    run(["bash", "scripts/instruction-counts.sh"], stdout=subprocess.DEVNULL)
    out = keep or tempfile.mkdtemp(prefix="rtprof-baseline-")
    # The suite picks up the instruction counts from the target directory.
    run([rtprof, "suite", "--quick", "--embree", "--no-pdf", "-o", out],
        env=dict(os.environ, CARGO_TARGET_DIR=target_dir()))
    results = trim(json.load(open(os.path.join(out, "results.json"))))
    if not results["instructions"]:
        sys.exit("perf-baseline: the suite picked up no instruction counts; run scripts/instruction-counts.sh")
    old = None
    if os.path.exists(BASELINE):
        fd, old = tempfile.mkstemp(suffix=".json")
        os.close(fd)
        shutil.copyfile(BASELINE, old)
    write_atomically(BASELINE, dumps(results))
    print(f"perf-baseline: wrote {os.path.relpath(BASELINE, ROOT)} "
          f"({len(results['scenes'])} scenes, {len(results['instructions'])} instruction counts)")
    if old:
        print("\nThe new baseline against the old one (what the commit message should explain):\n")
        subprocess.run([rtprof, "gate", "--strict", old, BASELINE], cwd=ROOT)
        os.remove(old)
    print(f"\nCommit benches/baseline.json with a line '{TRAILER} <why the figures moved>' "
          "in the message (.ci/run checks it).")


def commit_rule():
    """The last commit that changed the baseline says why. Returns an error or None."""
    try:
        log = subprocess.run(
            ["git", "log", "-1", "--format=%H%n%B", "--", "benches/baseline.json"],
            cwd=ROOT, check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        return f"cannot read the history of benches/baseline.json ({e}); the check needs a git clone"
    if not log.strip():
        return "benches/baseline.json is in no commit; commit it with a '" + TRAILER + " <why>' line"
    commit, _, message = log.partition("\n")
    reasons = [line[len(TRAILER):].strip() for line in message.splitlines()
               if line.startswith(TRAILER)]
    if not any(reasons):
        return (f"commit {commit[:12]} changed benches/baseline.json without a "
                f"'{TRAILER} <why>' line in its message")
    print(f"perf-baseline: {commit[:12]} changed the baseline: {reasons[0]}")
    return None


def check(args):
    if len(args) != 2:
        sys.exit("usage: scripts/perf-baseline.py check RTPROF RESULTS.json")
    rtprof, results = args
    gate = subprocess.run([rtprof, "gate", "--strict", BASELINE, results], cwd=ROOT)
    if gate.returncode != 0:
        print("\nperf-baseline: the run moved beyond the baseline's thresholds (above). If the "
              "change is intended, refresh the baseline in the same commit and say why:\n"
              "    scripts/perf-baseline.py refresh\n"
              f"    git commit -m '...' -m '{TRAILER} <why>' benches/baseline.json ...",
              file=sys.stderr)
        sys.exit(gate.returncode)
    problem = commit_rule()
    if problem:
        sys.exit(f"perf-baseline: {problem}")


def main():
    if len(sys.argv) < 2 or sys.argv[1] not in ("refresh", "check"):
        sys.exit(__doc__)
    {"refresh": refresh, "check": check}[sys.argv[1]](sys.argv[2:])


if __name__ == "__main__":
    main()
