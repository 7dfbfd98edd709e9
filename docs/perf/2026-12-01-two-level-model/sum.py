#!/usr/bin/env python3
"""Prints the walks each scheme took, averaged over the measured steps of variants.txt (tl's output),
by the step's length (x1, x2, x4 the model's step of 1.28 ms), and the trajectories' iterations.
    python3 sum.py variants.txt traj-*.txt"""
import re, sys
from collections import defaultdict
for name in sys.argv[1:]:
    text = open(name).read()
    if 'shipped walks' not in text:   # a trajectory
        L = [l for l in text.splitlines() if 'warm-up step' in l and 'holes' in l]
        g = lambda p, l: re.search(p, l).group(1)
        it = [int(g(r'iterations (\d+)', l)) for l in L]; dv = [int(g(r' div (\d+)', l)) for l in L]
        ho = [int(g(r'holes (\d+)', l)) for l in L]; de = [int(g(r'of (\d+) deep', l)) for l in L]
        vm = [float(g(r'vmax ([\d.]+)', l)) for l in L]
        print(f'{name}: {len(L)} steps; density iterations a step {sum(it)/len(it):.2f} (steps 20-39: {sum(it[20:])/len(it[20:]):.2f}); '
              f'divergence {sum(dv)/len(dv):.2f}; deep particles at kappa = 0 after the solve (steps 20-39) '
              f'{sum(ho[20:])/len(ho[20:]):.0f} of {sum(de[20:])/len(de[20:]):.0f}; fastest at the end {vm[-1]:.3f} m/s')
        continue
    walks = defaultdict(list)
    for line in text.splitlines():
        if not line.startswith('step') and not line.startswith(' | x'):
            continue
        for part in line.split(' | '):
            m = re.match(r'(?:shipped walks (\d+))|(?:x(\d+): div \d+ shipped (\d+)C?)', part.strip())
            if not m:
                continue
            f = 1 if m.group(1) else int(m.group(2))
            walks[(f, 'shipped (D10)')].append(int(m.group(1) or m.group(3)))
            for v, n, cap in re.findall(r' ((?:UA|SA)\(H\d+,nu\d+\)) (\d+)(C?)/', part):
                walks[(f, v)].append(int(n))
    for f in (1, 2, 4):
        row = [(k[1], v) for k, v in walks.items() if k[0] == f]
        print(f'step x{f}: ' + '; '.join(f'{k} {sum(v)/len(v):.1f}' for k, v in row) + f'  ({len(row[0][1])} steps)')
    syn = defaultdict(list)
    for k, n in re.findall(r'SYNTH (\S+) (\d+)', text):
        syn[k].append(int(n))
    if syn:
        print('smooth synthetic error (20 times the hydrostatic kappa, from zero): ' +
              '; '.join(f'{k} {sum(v)/len(v):.1f}' for k, v in syn.items()))
