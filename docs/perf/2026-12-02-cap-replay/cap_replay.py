#!/usr/bin/env python3
"""Replays a run's records (ranryu profile --records CSV) through the CPU's iteration-cap rule
(engine/sim/solvers/dfsph.cpp begin_frame(), next_iteration_cap(), iterations_at_plan()) with another
factor and margin, and counts what each would have issued and where a frame's most-needed step would
have passed its cap. An offline estimate on the run's own trajectory: a stop would change it."""
import csv, math, sys

def replay(rows, factor, add, most=100, least=1, lag=2, window=16, which=('most_iterations', 'iterations', 'issued')):
    # which: the density solve's columns, or ('most_divergence_iterations', ...) for the divergence solve's
    recent = [0] * window
    nxt = 0
    issued = stops = steps = 0
    cap = most
    for k, r in enumerate(rows):
        if k >= lag:
            rec = rows[k - lag]
            sub = int(rec['substeps'])
            if sub > 0:
                need_rec = int(rec[which[0]])
                recent[nxt] = need_rec
                nxt = (nxt + 1) % window
                planned = int(r['substeps'])
                scaled = need_rec if planned <= 0 or sub <= planned else math.ceil(need_rec * sub / planned)
                needed = max([scaled] + recent)
                stopped = int(rec['unconverged' if which[0] == 'most_iterations' else 'unconverged_divergence']) > 0
                want = most if stopped else math.ceil(factor * needed) + add
                cap = min(max(want, least), most)
        s = int(r['substeps'])
        steps += s
        issued += cap * s
        if int(r[which[0]]) > cap:
            stops += 1
    return issued / steps, stops

for f in sys.argv[1:]:
    rows = list(csv.DictReader(open(f)))
    steps = sum(int(r['substeps']) for r in rows)
    run = sum(int(r['iterations']) for r in rows) / steps
    actual = sum(int(r['issued']) for r in rows) / steps
    most = sum(int(r['most_iterations']) for r in rows) / len(rows)
    print(f'{f}: {len(rows)} frames, {steps} steps, {run:.2f} iterations a step run, {actual:.2f} issued (recorded), '
          f'a frame\'s most-needed step {most:.1f} on average')
    for factor, add in [(1.5, 2), (1.25, 2), (1.25, 1), (1.1, 1), (1.0, 1)]:
        i, st = replay(rows, factor, add)
        print(f'   density cap {factor}x+{add}: {i:.2f} issued a step (empty {i - run:.2f}), frames whose most passed the cap: {st}')
    # The divergence solve's cap follows the same rule (its least 1, its most the scene's too).
    div = ('most_divergence_iterations', 'divergence_iterations', 'issued_divergence')
    run_v = sum(int(r['divergence_iterations']) for r in rows) / steps
    actual_v = sum(int(r['issued_divergence']) for r in rows) / steps
    print(f'   divergence solve: {run_v:.2f} iterations a step run, {actual_v:.2f} issued (recorded)')
    for factor, add in [(1.5, 2), (1.0, 1)]:
        i, st = replay(rows, factor, add, which=div)
        print(f'   divergence cap {factor}x+{add}: {i:.2f} issued a step (empty {i - run_v:.2f}), frames whose most passed the cap: {st}')
