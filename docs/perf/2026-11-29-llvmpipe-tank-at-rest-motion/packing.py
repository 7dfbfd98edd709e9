#!/usr/bin/env python3
"""The summation density (docs/SPH.md (2)) and the gradient's normalisation M_yy = -sum_j V (y_j - y_i)
dW/dy of docs/DFSPH.md (D11) for the cubic spline of docs/SPH.md (1), h = 2 dx, on three packings of the
same number density 1/dx^3 (dx = 1): a column held still by the pressure p reads grad p = rho g / M_yy."""
import math

H = 2.0


def w(r):
    q, k = r / H, 8.0 / (math.pi * H**3)
    return k * (6 * q**3 - 6 * q**2 + 1) if q <= 0.5 else k * 2 * (1 - q) ** 3 if q <= 1 else 0.0


def dw(r):   # dW/dr
    q, l = r / H, 48.0 / (math.pi * H**3)
    return l * q * (3 * q - 2) / H if q <= 0.5 else -l * (1 - q) ** 2 / H if q <= 1 else 0.0


def lattice(a, basis):
    r = range(-4, 5)
    return [(a * (i + b[0]), a * (j + b[1]), a * (k + b[2])) for i in r for j in r for k in r for b in basis]


PACKINGS = {
    "cubic": lattice(1.0, [(0, 0, 0)]),
    "body-centred cubic": lattice(2 ** (1 / 3), [(0, 0, 0), (0.5, 0.5, 0.5)]),
    "face-centred cubic": lattice(4 ** (1 / 3), [(0, 0, 0), (0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)]),
}
for name, pts in PACKINGS.items():
    rho = sum(w(math.dist(p, (0, 0, 0))) for p in pts)
    m = sum(-p[1] * p[1] * dw(r) / r for p in pts if 0 < (r := math.dist(p, (0, 0, 0))) < H)
    print(f"{name:20s} rho/rho0 {rho:.4f}  M_yy {m:.4f}  hydrostatic gradient reads {1 / m:.4f} rho g")
