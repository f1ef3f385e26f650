#!/usr/bin/env python3
"""Trims a default-suite results.json to what the gate reads (times, samples, counts,
calibration): the images, histograms, hardware and profile are left out so that the
fixture stays small. Usage: trim.py IN.json OUT.json"""
import json, sys

r = json.load(open(sys.argv[1]))
r["profile"] = None
r["hardware"] = None
for s in r["scenes"]:
    s["hardware"] = None
    for v in s["variants"]:
        v["image"] = None
        v["heat_map"] = None
        v["histogram"] = []
json.dump(r, open(sys.argv[2], "w"), separators=(",", ":"))
