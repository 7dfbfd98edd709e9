#!/usr/bin/env python3
"""Where the dam break's fastest and densest particles were, frame by frame, from the records of call 4
(the shipped scene for ten seconds at 250k and 1M): over the first two seconds and the last six, the
frames whose fastest (densest) particle lies within two spacings of a side wall (x = 0 or 1 m, z = 0 or
0.1 m), those where the two lie within two spacings of each other, the fastest speed's median and the
fastest particle's median height (the settled pool is about 0.08 m deep).
    python3 docs/perf/2026-11-29-h200-step-leads/where.py"""
import csv, io, math, os, tarfile

here = os.path.dirname(os.path.abspath(__file__))
spacing = {"250000": 0.00317, "1000000": 0.002}
with tarfile.open(os.path.join(here, "call4/eta-where.tgz")) as t:
    for n, dx in spacing.items():
        rows = list(csv.DictReader(io.TextIOWrapper(t.extractfile(f"eta/db-{n}-1e-3.csv"))))
        print(f"{n} particles (spacing {dx} m)")
        for name, part in (("0-2 s", rows[:120]), ("4-10 s", rows[240:])):
            def at(r, k):
                return [float(r[f"{k}_{a}"]) for a in "xyz"]
            def by_wall(p):
                return min(p[0], 1.0 - p[0], p[2], 0.1 - p[2]) < 2 * dx
            fast = [at(r, "fastest") for r in part]
            dense = [at(r, "densest") for r in part]
            wall_fast = sum(by_wall(p) for p in fast)
            wall_dense = sum(by_wall(p) for p in dense)
            together = sum(math.dist(a, b) < 2 * dx for a, b in zip(fast, dense))
            speeds = sorted(float(r["max_speed"]) for r in part)
            heights = sorted(p[1] for p in fast)
            print(f"  {name}: fastest by a side wall in {wall_fast}/{len(part)} frames, densest in {wall_dense}, the two within "
                  f"2 dx in {together}; fastest speed median {speeds[len(speeds) // 2]:.2f} m/s, its height median "
                  f"{heights[len(heights) // 2]:.3f} m")
