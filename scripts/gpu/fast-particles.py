#!/usr/bin/env python3
"""Where a run's fastest particles are: reads `ranryu record --export-particles ply` frames and prints,
for each, the fastest particles with their distance to each tank wall (the floor and the four side
walls; a lid is not counted) and to the free surface in spacings, their density and pressure, and how
many particles past a speed lie near 0, 1, 2 or 3 walls.

usage: fast-particles.py --spacing DX --tank x0,y0,z0,x1,y1,z1 [--top N] [--speed V] FILE.ply...

Pure Python (no numpy needed on the GPU machine); a million particles take a few seconds a file.
"""
import argparse
import array
import math
import struct
import sys


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    names, types, n = [], [], 0
    for line in data[:end].decode().splitlines():
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            n = int(words[2])
        elif words and words[0] == "property":
            types.append(words[1])
            names.append(words[2])
    if all(t == "float" for t in types):
        values = array.array("f")
        values.frombytes(data[end:end + 4 * len(names) * n])
        if sys.byteorder != "little":
            values.byteswap()
        k = len(names)
        columns = {name: values[c::k] for c, name in enumerate(names)}
        return names, n, lambda i, name: columns[name][i]
    fmt = "<" + "".join("B" if t == "uchar" else "f" for t in types)
    size = struct.calcsize(fmt)
    rows = [struct.unpack_from(fmt, data, end + i * size) for i in range(n)]
    return names, n, lambda i, name: rows[i][names.index(name)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, required=True)
    ap.add_argument("--tank", required=True, help="x0,y0,z0,x1,y1,z1 of the tank in metres")
    ap.add_argument("--top", type=int, default=12)
    ap.add_argument("--speed", type=float, default=0.5, help="the speed past which particles are counted (m/s)")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    lo = [float(v) for v in args.tank.split(",")[:3]]
    hi = [float(v) for v in args.tank.split(",")[3:]]
    dx = args.spacing
    for path in args.files:
        names, n, get = read_ply(path)
        xs = list(zip(*([get(i, c) for i in range(n)] for c in ("x", "y", "z"))))
        vs = list(zip(*([get(i, c) for i in range(n)] for c in ("vx", "vy", "vz"))))
        speed = [math.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2) for v in vs]
        # The free surface over a column: the highest particle within a spacing of (x, z), on a grid.
        top = {}
        for p in xs:
            key = (int((p[0] - lo[0]) / dx), int((p[2] - lo[2]) / dx))
            top[key] = max(top.get(key, -1e9), p[1])

        def below_surface(p):
            key = (int((p[0] - lo[0]) / dx), int((p[2] - lo[2]) / dx))
            best = max(top.get((key[0] + a, key[1] + b), -1e9) for a in (-1, 0, 1) for b in (-1, 0, 1))
            return (best - p[1]) / dx

        def walls(p):   # distance to each of the five walls (no lid), in spacings
            return [(p[0] - lo[0]) / dx, (hi[0] - p[0]) / dx, (p[1] - lo[1]) / dx, (p[2] - lo[2]) / dx, (hi[2] - p[2]) / dx]

        order = sorted(range(n), key=lambda i: -speed[i])
        print(f"{path}: {n} particles, fastest {speed[order[0]]:.3f} m/s")
        print("  index     speed    vx      vy      vz     | -x    +x    floor  -z    +z   | below surface | rho     p")
        has = "density" in names
        for i in order[:args.top]:
            w = walls(xs[i])
            rho = get(i, "density") if has else float("nan")
            p = get(i, "pressure") if "pressure" in names else float("nan")
            print(f"  {i:8d} {speed[i]:7.3f} {vs[i][0]:7.3f} {vs[i][1]:7.3f} {vs[i][2]:7.3f} | "
                  + " ".join(f"{d:5.1f}" for d in w) + f" | {below_surface(xs[i]):6.1f} | {rho:7.1f} {p:9.1f}")
        fast = [i for i in range(n) if speed[i] > args.speed]
        near = [0, 0, 0, 0]
        surface = 0
        for i in fast:
            near[min(3, sum(1 for d in walls(xs[i]) if d < 2.0))] += 1
            surface += below_surface(xs[i]) < 3.0
        print(f"  past {args.speed} m/s: {len(fast)} particles; within 2 spacings of 0/1/2/3 walls: "
              f"{near[0]}/{near[1]}/{near[2]}/{near[3]}; within 3 spacings of the surface: {surface}")


if __name__ == "__main__":
    main()
