#!/usr/bin/env python3
"""The packing of a recorded frame: M_yy = -sum_j V (y_j - y_i) dW/dy over the fluid neighbours (V = dx^3)
of each particle more than h from the side walls, the floor and the top particle, and sum_j V W (the
summation density's number part), from a binary PLY of `ranryu record --export-particles ply`.
Usage: packing_of_run.py FRAME.ply DX [TANK_DEPTH_Z]. Prints their means (M_yy's spread too)."""
import math, struct, sys
path, dx = sys.argv[1], float(sys.argv[2])
tank = [(0.0, 0.3), (0.0, 0.4), (0.0, float(sys.argv[3]) if len(sys.argv) > 3 else 0.1)]
data = open(path, 'rb').read()
end = data.index(b'end_header\n') + len(b'end_header\n')
header = data[:end].decode()
n = int([l for l in header.splitlines() if l.startswith('element vertex')][0].split()[2])
props = [l.split() for l in header.splitlines() if l.startswith('property')]
size = {'float': 4, 'uchar': 1, 'int': 4, 'uint': 4, 'double': 8}
fmt = '<' + ''.join({'float': 'f', 'uchar': 'B', 'int': 'i', 'uint': 'I', 'double': 'd'}[p[1]] for p in props)
stride = struct.calcsize(fmt)
names = [p[2] for p in props]
pts = []
for k in range(n):
    rec = dict(zip(names, struct.unpack_from(fmt, data, end + k * stride)))
    pts.append((rec['x'], rec['y'], rec['z']))
h = 2 * dx
top = max(p[1] for p in pts)
cell = {}
for i, p in enumerate(pts):
    cell.setdefault(tuple(int(math.floor(c / h)) for c in p), []).append(i)
l = 48 / (math.pi * h**3); kw = 8 / (math.pi * h**3)
def dw(r):
    q = r / h
    return l * q * (3 * q - 2) / h if q <= 0.5 else -l * (1 - q) ** 2 / h if q <= 1 else 0.0
def w(r):
    q = r / h
    return kw * (6 * q**3 - 6 * q**2 + 1) if q <= 0.5 else kw * 2 * (1 - q) ** 3 if q <= 1 else 0.0
ms, rs = [], []
V = dx**3
for i, p in enumerate(pts):
    if any(p[a] - tank[a][0] < h or tank[a][1] - p[a] < h for a in (0, 2)) or p[1] < h or p[1] > top - h:
        continue
    c = tuple(int(math.floor(x / h)) for x in p)
    m = 0.0; rho = 0.0
    for a in (-1, 0, 1):
        for b in (-1, 0, 1):
            for e in (-1, 0, 1):
                for j in cell.get((c[0] + a, c[1] + b, c[2] + e), ()):
                    d = [pts[j][t] - p[t] for t in range(3)]
                    r = math.sqrt(sum(x * x for x in d))
                    if r >= h: continue
                    rho += V * w(r)
                    if r > 0: m += -V * d[1] * d[1] * dw(r) / r
    ms.append(m); rs.append(rho)
mean = sum(ms) / len(ms)
sd = math.sqrt(sum((x - mean) ** 2 for x in ms) / len(ms))
print(f"{path}: {len(ms)} interior particles, M_yy mean {mean:.4f} (sd {sd:.4f}), number density sum {sum(rs)/len(rs):.4f}")
