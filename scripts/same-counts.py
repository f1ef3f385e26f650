#!/usr/bin/env python3
"""Checks that merged shard results equal an unsharded run of the same suite.

    scripts/same-counts.py WHOLE/results.json MERGED/results.json MERGED_DIR

Equal means: the same scenes in the same order, each with the same variants and the
same counts (counts are exact, so any difference is a bug; times are not compared, they
were measured at another moment), the same suite variants, no shard left in the merged
suite, and every image the merged results name present in MERGED_DIR. Exit 1 with the
first difference otherwise. Used by .ci/run and scripts/slurm-suite.sh.
"""
import json
import os
import sys


def table(results):
    return [
        (s["name"], [(v["variant"], v["counts"]) for v in s["variants"]])
        for s in results["scenes"]
    ]


def main(whole_path, merged_path, merged_dir):
    whole, merged = (json.load(open(p)) for p in (whole_path, merged_path))
    a, b = table(whole), table(merged)
    if a != b:
        names = ([s for s, _ in a], [s for s, _ in b])
        if names[0] != names[1]:
            sys.exit(f"same-counts: scenes differ: {names[0]} against {names[1]}")
        for (scene, va), (_, vb) in zip(a, b):
            if va != vb:
                sys.exit(f"same-counts: {scene}: the merged variants or counts differ")
    if merged["suite"]["variants"] != whole["suite"]["variants"]:
        sys.exit("same-counts: the suites' variants differ")
    if merged["suite"].get("shard") is not None:
        sys.exit("same-counts: the merged results still name a shard")
    images = [v["image"] for s in merged["scenes"] for v in s["variants"] if v.get("image")]
    missing = [i for i in images if not os.path.isfile(os.path.join(merged_dir, i))]
    if missing:
        sys.exit(f"same-counts: the merge lacks {missing[:3]}")
    print(
        f"same-counts: {len(merged['scenes'])} scenes, "
        f"{sum(len(v) for _, v in b)} scene × variants: same counts as the unsharded run"
    )


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
