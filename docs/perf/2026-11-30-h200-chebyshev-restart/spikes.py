#!/usr/bin/env python3
# The dam break's ten-second records of this folder's calls: frames whose largest density passed 1.1 rho0
# (all, with the densest particle in the floor's five layers, after t = 4 s), the largest, and the last
# six seconds' steps a frame and density iterations a step. python3 spikes.py [FOLDER] reads FOLDER's
# call*/eta-*.tgz (this folder's by default).
import csv, glob, os, sys
here = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
for tgz in sorted(glob.glob(os.path.join(here, "call*", "eta-*.tgz"))):
    import tarfile
    with tarfile.open(tgz) as t:
        for m in sorted(t.getmembers(), key=lambda m: m.name):
            if not m.name.endswith(".csv"):
                continue
            rows = list(csv.DictReader(line.decode() for line in t.extractfile(m)))
            dx = 0.002 if "1000000" in m.name else 0.00317
            spikes = [r for r in rows if float(r["max_density"]) > 1.1]
            last = rows[-360:]
            steps = sum(float(r["substeps"]) for r in last)
            print(f"{os.path.basename(os.path.dirname(tgz))}/{os.path.basename(tgz)[4:-4]:22s} {os.path.basename(m.name):22s} "
                  f"frames {len(rows)}, past 1.1: {len(spikes)}, floor {sum(float(r['densest_y']) < 5 * dx for r in spikes)}, "
                  f"after 4 s {sum(float(r['time']) > 4 for r in spikes)}, largest {max(float(r['max_density']) for r in rows):.3f}; "
                  f"last 6 s {steps / len(last):.1f} steps a frame, {sum(float(r['iterations']) for r in last) / steps:.2f} iterations a step")
