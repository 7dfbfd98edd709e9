#!/usr/bin/env python3
"""The DFSPH density solve (docs/DFSPH.md (D3), (D6), (D9)) on an exported frame of the tank at rest,
solved to round-off in double precision: is the floor layer's excess in the positions or in the GPU's
iterations? Usage: solve.py PLY DX DT"""
import math, struct, sys, time
ply, dx, dt = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rho0, g = 1000.0, -9.81
h = 2 * dx; m = rho0 * dx ** 3
b = open(ply, 'rb').read(); i0 = b.index(b'end_header\n') + len('end_header\n')
n = int(b[b.index(b'element vertex ') + 15:].split(b'\n')[0])
F = [struct.unpack_from('<8f', b, i0 + 32 * k) for k in range(n)]
X = [(p[0], p[1], p[2]) for p in F]; V = [(p[3], p[4], p[5]) for p in F]
P_gpu = [p[7] for p in F]; R_gpu = [p[6] for p in F]
# the tank's boundary (engine/sim/boundary.cpp): cell-centred lattice, 3 layers, open top
def axis(lo, hi, layers=3):
    out = [(lo - (l + 0.5) * dx, dx, -1) for l in range(layers - 1, -1, -1)]
    nc = max(1, math.ceil((hi - lo) / dx - 1e-4)); pitch = (hi - lo) / nc
    out += [(lo + (i + 0.5) * pitch, pitch, 0) for i in range(nc)]
    out += [(hi + (l + 0.5) * dx, dx, 1) for l in range(layers)]
    return out
ax, ay, az = axis(0, 0.3), axis(0, 0.4), axis(0, 0.1)
B, Vc = [], []
for z in az:
    for y in ay:
        if y[2] > 0: continue
        for x in ax:
            if x[2] or y[2] or z[2]:
                B.append((x[0], y[0], z[0])); Vc.append(x[1] * y[1] * z[1])
nb = len(B)
def W(r):
    q = r / h; t = max(1 - q, 0)
    s = 6 * q * q * (q - 1) + 1 if q <= 0.5 else 2 * t ** 3
    return 8 / math.pi / h ** 3 * s
def gradW(d, r):
    q = r / h; t = max(1 - q, 0)
    f = q * (3 * q - 2) if q <= 0.5 else -t * t
    l = 48 / math.pi / h ** 4
    return (l * f / r * d[0], l * f / r * d[1], l * f / r * d[2]) if r > 1e-12 else (0.0, 0.0, 0.0)
def grid(P):
    G = {}
    for k, p in enumerate(P):
        G.setdefault((int(math.floor(p[0] / h)), int(math.floor(p[1] / h)), int(math.floor(p[2] / h))), []).append(k)
    return G
def near(G, p):
    c = (int(math.floor(p[0] / h)), int(math.floor(p[1] / h)), int(math.floor(p[2] / h)))
    for i in (-1, 0, 1):
        for j in (-1, 0, 1):
            for k in (-1, 0, 1):
                yield from G.get((c[0] + i, c[1] + j, c[2] + k), ())
GF, GB = grid(X), grid(B)
def pairs(p, P, G):
    out = []
    for k in near(G, p):
        d = (p[0] - P[k][0], p[1] - P[k][1], p[2] - P[k][2]); r = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
        if r < h: out.append((k, r, gradW(d, r)))
    return out
t0 = time.time()
psi = []
for k, p in enumerate(B):
    s = sum(W(r) for _, r, _ in pairs(p, B, GB)); psi.append(rho0 * min(1 / s, Vc[k]))
FF = [pairs(X[i], X, GF) for i in range(n)]            # fluid j of fluid i, gradW at x_i - x_j
FB = [pairs(X[i], B, GB) for i in range(n)]            # boundary b of fluid i, gradW at x_i - x_b
rows = sorted({bb for i in range(n) for bb, _, _ in FB[i]})
row_of = {bb: k for k, bb in enumerate(rows)}
BF = [pairs(B[bb], X, GF) for bb in rows]              # fluid j of row b, gradW at x_b - x_j
wall = [sum(psi[k] * W(r) for k, r, _ in pairs(B[bb], B, GB)) for bb in rows]
print(f"{n} fluid, {nb} boundary, {len(rows)} rows, set-up {time.time() - t0:.1f} s", file=sys.stderr)
rho = [sum(m * W(r) for _, r, _ in FF[i]) + sum(psi[k] * W(r) for k, r, _ in FB[i]) for i in range(n)]
print(f"density: mean {sum(rho) / n / rho0:.5f} rho0 (GPU's {sum(R_gpu) / n / rho0:.5f})", file=sys.stderr)
vs = [(v[0], v[1] + g * dt, v[2]) for v in V]
def dot(a, c): return a[0] * c[0] + a[1] * c[1] + a[2] * c[2]
src = []
for i in range(n):
    rate = sum(m * dot((vs[i][0] - vs[j][0], vs[i][1] - vs[j][1], vs[i][2] - vs[j][2]), gr) for j, _, gr in FF[i]) + \
           sum(psi[k] * dot(vs[i], gr) for k, _, gr in FB[i])
    src.append(rho0 - (rho[i] + dt * rate))
for k, bb in enumerate(rows):
    rb = sum(m * W(r) for _, r, _ in BF[k]) + wall[k]
    rate = sum(-m * dot(vs[j], gr) for j, _, gr in BF[k])
    src.append(max(rho0, wall[k]) - (rb + dt * rate))
N = n + len(rows)
def apply(kap):
    """delta(kappa): (D3)'s accelerations, then the density change they make over dt (fluid, then rows)."""
    a = []
    for i in range(n):
        ax_ = ay_ = az_ = 0.0; ki = kap[i]
        for j, _, gr in FF[i]:
            c = m * (ki + kap[j]); ax_ -= c * gr[0]; ay_ -= c * gr[1]; az_ -= c * gr[2]
        for k, _, gr in FB[i]:
            r_ = row_of[k]; c = psi[k] * (ki + kap[n + r_]); ax_ -= c * gr[0]; ay_ -= c * gr[1]; az_ -= c * gr[2]
        a.append((ax_, ay_, az_))
    out = []
    for i in range(n):
        s = 0.0; ai = a[i]
        for j, _, gr in FF[i]:
            aj = a[j]; s += m * ((ai[0] - aj[0]) * gr[0] + (ai[1] - aj[1]) * gr[1] + (ai[2] - aj[2]) * gr[2])
        for k, _, gr in FB[i]:
            s += psi[k] * dot(ai, gr)
        out.append(dt * dt * s)
    for k in range(len(rows)):
        out.append(dt * dt * sum(-m * dot(a[j], gr) for j, _, gr in BF[k]))
    return out, a
wgt = [m] * n + [psi[bb] for bb in rows]                 # lambda = w kappa: the symmetric form
# symmetry check on random vectors: u.P(v) = v.P(u), P(lambda) = -delta(lambda / w)
import random
random.seed(1)
u = [random.random() for _ in range(N)]; v = [random.random() for _ in range(N)]
Pu = apply([u[k] / wgt[k] for k in range(N)])[0]; Pv = apply([v[k] / wgt[k] for k in range(N)])[0]
print(f"symmetry: u.Pv = {sum(u[k] * Pv[k] for k in range(N)):.9e}, v.Pu = {sum(v[k] * Pu[k] for k in range(N)):.9e}", file=sys.stderr)
# CG on the active set (kappa > 0), the rest held at 0; the active set shrinks until kappa >= 0 everywhere
active = [True] * N
for outer in range(6):
    lam = [0.0] * N
    def P(x):
        d = apply([x[k] / wgt[k] if active[k] else 0.0 for k in range(N)])[0]
        return [d[k] if active[k] else 0.0 for k in range(N)]
    # delta(kappa) = s  <=>  P'(lambda) = s with P' = delta(lambda / w), negative definite: solve -P' x = -s
    rhs = [-src[k] if active[k] else 0.0 for k in range(N)]
    r = rhs[:]; p = r[:]; rr = sum(x * x for x in r); r0 = math.sqrt(rr)
    for it in range(3000):
        Ap = [-x for x in P(p)]
        alpha = rr / sum(p[k] * Ap[k] for k in range(N))
        for k in range(N):
            lam[k] += alpha * p[k]; r[k] -= alpha * Ap[k]
        rn = sum(x * x for x in r)
        if math.sqrt(rn) < 1e-11 * r0: break
        p = [r[k] + rn / rr * p[k] for k in range(N)]; rr = rn
    kap = [lam[k] / wgt[k] if active[k] else 0.0 for k in range(N)]
    neg = [k for k in range(N) if active[k] and kap[k] < 0]
    print(f"pass {outer}: CG {it + 1} iterations, residual {math.sqrt(rn) / r0:.2e}, {len(neg)} negative", file=sys.stderr)
    if not neg: break
    for k in neg: active[k] = False
delta, acc = apply(kap)
H = 0.25
print("layer  n   mean y/dx   p exact   p GPU     ref   (exact-ref)/(rho g dx)  (GPU-ref)/(rho g dx)  a_y exact mean")
layers = {}
for i in range(n):
    layers.setdefault(int(X[i][1] / dx), []).append(i)
for L in sorted(layers)[:8] + sorted(layers)[-3:]:
    ids = layers[L]
    pe = sum(kap[i] * rho[i] ** 2 for i in ids) / len(ids); pg = sum(P_gpu[i] for i in ids) / len(ids)
    ref = rho0 * 9.81 * (H - (L + 0.5) * dx); ay_ = sum(acc[i][1] for i in ids) / len(ids)
    print(f"{L:4d} {len(ids):4d} {sum(X[i][1] for i in ids) / len(ids) / dx:9.3f} {pe:9.1f} {pg:9.1f} {ref:8.1f} {(pe - ref) / (rho0 * 9.81 * dx):+10.2f} {(pg - ref) / (rho0 * 9.81 * dx):+10.2f} {ay_:+10.3f}")
rowy = {}
for k, bb in enumerate(rows):
    if B[bb][1] < 0: rowy.setdefault(round(B[bb][1] / dx, 2), []).append(kap[n + k] * rho0 ** 2)
for y in sorted(rowy, reverse=True):
    ref = rho0 * 9.81 * (H - y * dx)
    print(f"floor rows at y = {y:+.2f} dx: {len(rowy[y])}, p_b {sum(rowy[y]) / len(rowy[y]):9.1f}, hydrostatic there {ref:9.1f}, ({(sum(rowy[y]) / len(rowy[y]) - ref) / (rho0 * 9.81 * dx):+.2f} rho g dx)")
