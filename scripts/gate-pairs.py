#!/usr/bin/env python3
"""Pairwise gates of N suite runs, and a 25 % slow-down planted in an edited copy.
usage: scripts/gate-pairs.py RTPROF RUN_DIR... [--slow VARIANT]
(the measurement of docs/gate.md: false verdicts between runs of one binary, and
whether a planted slow-down of VARIANT is caught)"""
import json, subprocess, sys, os, math, itertools, tempfile
args = sys.argv[1:]
slow = None
if '--slow' in args:
    i = args.index('--slow'); slow = args[i+1]; del args[i:i+2]
binary, runs = args[0], args[1:]
def gate(a, b):
    out = subprocess.run([binary, 'gate', a, b, '--format', 'json'], capture_output=True, text=True)
    if out.returncode == 2:
        sys.exit(f'gate refused {a} {b}: {out.stderr}')
    return json.loads(out.stdout), out.returncode
total = alarms = 0
worst = {}
for a, b in itertools.combinations(range(len(runs)), 2):
    g, rc = gate(f'{runs[a]}/results.json', f'{runs[b]}/results.json')
    bad = [e for e in g['entries'] if e['verdict'] in ('slower', 'faster')]
    total += len(g['entries']); alarms += len(bad)
    for e in g['entries']:
        c = e['change']['median']
        m = e['measure']
        if m not in worst or abs(math.log(c)) > abs(math.log(worst[m][0])):
            worst[m] = (c, f"{e['scene']} {e['width']}x{e['height']} {e['variant']} (runs {a+1}-{b+1})")
    print(f'runs {a+1}-{b+1}: exit {rc}, {len(g["entries"])} entries, {len(bad)} slower/faster' +
          ''.join(f"\n   {e['verdict']} {e['scene']} {e['variant']} {e['measure']} {100*(e['change']['median']-1):+.1f} % (threshold {100*e['threshold']:.0f} %)" for e in bad))
print(f'all pairs: {total} entries, {alarms} false verdicts')
for m, (c, what) in sorted(worst.items()):
    print(f'  largest change, {m}: {100*(c-1):+.1f} % {what}')
if slow:
    caught = scenes = 0
    for a, b in itertools.pairwise(range(len(runs))):
        r = json.load(open(f'{runs[b]}/results.json'))
        for s in r['scenes']:
            for v in s['variants']:
                if v['variant'] == slow:
                    v['samples'] = [x * 1.25 for x in v['samples']]
                    v['cpu_samples'] = [x * 1.25 for x in v['cpu_samples']]
                    for k in ('median', 'low', 'high'):
                        v['time'][k] *= 1.25
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, 'results.json')
            json.dump(r, open(p, 'w'))
            g, rc = gate(f'{runs[a]}/results.json', p)
        es = [e for e in g['entries'] if e['variant'] == slow]
        hit = [e for e in es if e['verdict'] == 'slower']
        caught += len(hit); scenes += len(es)
        print(f'{slow} 25 % slower in a copy of run {b+1}, gated against run {a+1}: exit {rc}, caught on {len(hit)} of {len(es)} scenes'
              + ''.join(f"\n   missed {e['scene']} {100*(e['change']['median']-1):+.1f} % (threshold {100*e['threshold']:.0f} %)" for e in es if e['verdict'] != 'slower'))
    print(f'slow-down caught on {caught} of {scenes}')
