#!/usr/bin/env python3
"""rtprof against its peers, interleaved: each round runs every (binary, variant) once
per SPD scene through `compare` (one thread, one repeat), and the medians over rounds
are printed per scene with their geometric mean (docs/benchmarks.md, issue 37).
usage: scripts/peer-race.py ROUNDS WxH diffuse|whitted SCENE... -- LABEL=RTPROF:VARIANT ...
e.g.   scripts/peer-race.py 5 1024x1024 diffuse gears teapot -- \
           rt=target/release/rtprof:bvh+simd+packets ep=target/release/rtprof:embree-packets
(the binary built with --features embree for the embree variants; scenes from
../shared/spd)"""
import json, os, resource, subprocess, sys, statistics
SPD = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shared', 'spd')
args = sys.argv[1:]
rounds, size, mode = int(args[0]), args[1], args[2]
sep = args.index('--')
scenes = args[3:sep]
runs = [a.split('=',1) for a in args[sep+1:]]
runs = [(l, b.split(':',1)) for l,b in runs]
flags = ['--diffuse-only'] if mode == 'diffuse' else ['--depth', '5']
times = {}
cpu = {}
for r in range(rounds):
    for s in scenes:
        for label, (binary, variant) in runs:
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            out = subprocess.run([binary, 'compare', os.path.join(SPD, f'{s}.nff'), '--variants', variant,
                                  '--size', size, '--threads', '1', '--repeats', '1', '--format', 'json'] + flags,
                                 capture_output=True, text=True)
            if out.returncode != 0:
                print(label, s, out.stderr[-500:], file=sys.stderr); continue
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu.setdefault((s, label), []).append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
            d = json.loads(out.stdout)
            v = d['variants'][0]
            times.setdefault((s, label), []).append(v['seconds']['median'])
labels = [l for l,_ in runs]
print('scene\t' + '\t'.join(labels))
for s in scenes:
    print(s + '\t' + '\t'.join(f"{statistics.median(times.get((s,l),[float('nan')]))*1000:.1f}" for l in labels))
geo = {}
for l in labels:
    xs = [statistics.median(times[(s,l)]) for s in scenes if (s,l) in times]
    geo[l] = statistics.geometric_mean(xs) if xs else float('nan')
print('process cpu median:')
for s in scenes:
    print(s + '\t' + '\t'.join(f"{statistics.median(cpu.get((s,l),[float('nan')]))*1000:.1f}" for l in labels))
print('min:')
for s in scenes:
    print(s + '\t' + '\t'.join(f"{min(times.get((s,l),[float('nan')]))*1000:.1f}" for l in labels))
print('geomean\t' + '\t'.join(f"{geo[l]*1000:.1f}" for l in labels))
