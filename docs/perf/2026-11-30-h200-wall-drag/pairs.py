#!/usr/bin/env python3
"""Nearest-neighbour distances of a ranryu particle PLY: are the dense particles paired?
    pairs.py FILE.ply DX"""
import struct, sys, math
path, dx = sys.argv[1], float(sys.argv[2])
data = open(path, 'rb').read()
end = data.index(b'end_header\n') + len(b'end_header\n')
header = data[:end].decode().split('\n')
n = int([l for l in header if l.startswith('element vertex')][0].split()[-1])
props = [l.split()[-1] for l in header if l.startswith('property')]
rec = 4 * len(props)
fmt = '<' + 'f' * len(props)
ix, iy, iz, idn = props.index('x'), props.index('y'), props.index('z'), props.index('density')
P = []
for t in struct.iter_unpack(fmt, data[end:end + n * rec]):
    P.append((t[ix], t[iy], t[iz], t[idn]))
rho0 = 1000.0
live = [i for i, p in enumerate(P) if p[1] > -0.5]
cell = dx
grid = {}
for i in live:
    x, y, z, _ = P[i]
    grid.setdefault((int(math.floor(x / cell)), int(math.floor(y / cell)), int(math.floor(z / cell))), []).append(i)
def nearest(i):
    x, y, z, _ = P[i]
    cx, cy, cz = int(math.floor(x / cell)), int(math.floor(y / cell)), int(math.floor(z / cell))
    best = 1e9
    for a in (-1, 0, 1):
        for b in (-1, 0, 1):
            for c in (-1, 0, 1):
                for j in grid.get((cx + a, cy + b, cz + c), ()):
                    if j != i:
                        q = P[j]
                        d = (q[0] - x) ** 2 + (q[1] - y) ** 2 + (q[2] - z) ** 2
                        if d < best: best = d
    return math.sqrt(best) / dx
bins = [0.3, 0.5, 0.7, 0.9, 9e9]
def hist(ids):
    h = [0] * len(bins)
    for i in ids:
        r = nearest(i)
        for k, b in enumerate(bins):
            if r < b: h[k] += 1; break
    return h
floor = [i for i in live if P[i][1] < 4 * dx]
print(f"{len(live)} particles, {len(floor)} within 4 dx of the floor")
print("nearest/dx bins <0.3 <0.5 <0.7 <0.9 >=0.9")
print("  floor layers:", hist(floor))
dens = sorted(live, key=lambda i: -P[i][3])[:15]
print("densest: rho/rho0, y/dx, nearest/dx")
for i in dens:
    print(f"  {P[i][3] / rho0:.3f} {P[i][1] / dx:.2f} {nearest(i):.3f}")
dh = [0] * 5
for i in live:
    r = P[i][3] / rho0
    dh[0 if r < 1.01 else 1 if r < 1.03 else 2 if r < 1.1 else 3 if r < 1.2 else 4] += 1
print("density bins <1.01 <1.03 <1.1 <1.2 >=1.2:", dh)
