#!/usr/bin/env python3
"""The ten-second runs of calls 1 and 2 second by second: substeps a frame, density iterations a step
and the largest rho/rho0 over each second, for the shipped dam break, the proportional cut at lambda
0.75 (prop), and the step on the largest pair approach speed (vrel, vreli).
    python3 docs/perf/2026-11-29-h200-step-leads/seconds.py"""
import csv, io, os, tarfile

here = os.path.dirname(os.path.abspath(__file__))
runs = {"shipped": "call1/eta-shipped.tgz", "prop": "call1/eta-prop.tgz", "vrel": "call2/eta-vrel.tgz", "vreli": "call2/eta-vreli.tgz"}


def records(archive, n):
    with tarfile.open(os.path.join(here, archive)) as t:
        return list(csv.DictReader(io.TextIOWrapper(t.extractfile(f"eta/db-{n}-1e-3.csv"))))


for n in ("250000", "1000000"):
    data = {k: records(a, n) for k, a in runs.items()}
    print(f"{n} particles: substeps a frame / density iterations a step / largest rho/rho0, by second")
    for second in range(10):
        cells = []
        for k, rows in data.items():
            rr = rows[60 * second:60 * second + 60]
            steps = sum(float(r["substeps"]) for r in rr)
            iterations = sum(float(r["iterations"]) for r in rr)
            cells.append(f"{k} {steps / len(rr):5.1f} {iterations / steps:5.2f} {max(float(r['max_density']) for r in rr):.3f}")
        print(f"  {second}-{second + 1} s  " + " | ".join(cells))
    for k, rows in data.items():
        steps = sum(float(r["substeps"]) for r in rows)
        print(f"  {k}: {steps:.0f} steps, {sum(float(r['iterations']) for r in rows):.0f} density iterations")
