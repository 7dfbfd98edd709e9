#!/usr/bin/env python3
"""The boundary's part of a fluid particle's density beside a flat lattice wall (engine/sim/boundary.h:
layers at the fluid's spacing dx, the outer one half a pitch inside the face, psi_b = dx^3), with
ranryu's cubic spline of support h = 2 dx (glsl/sim/kernel.glsl), in units of rho0: along the wall, as
the particle slides over one lattice pitch at 0.5 dx off the face (the corrugation), and across it at
0.4, 0.5 and 0.6 dx off the face.
    python3 docs/perf/2026-11-29-h200-step-leads/wall_sum.py"""
import math


def kernel(r, h):
    q = r / h
    if q > 1.0:
        return 0.0
    shape = 6.0 * q * q * (q - 1.0) + 1.0 if q <= 0.5 else 2.0 * (1.0 - q) ** 3
    return 8.0 / math.pi / h ** 3 * shape


def wall_part(x, y, height, dx=1.0, h=2.0, layers=4):
    return sum(kernel(math.dist((x, y, height), (i * dx, j * dx, -(l + 0.5) * dx)), h) * dx ** 3
               for i in range(-5, 6) for j in range(-5, 6) for l in range(layers))


for height in (0.4, 0.5, 0.6):
    along = [wall_part(k / 10.0, 0.0, height) for k in range(11)]
    diagonal = [wall_part(k / 10.0, k / 10.0, height) for k in range(11)]
    print(f"{height} dx off the face: {min(along):.4f}-{max(along):.4f} sliding along x, "
          f"{min(diagonal):.4f}-{max(diagonal):.4f} along the diagonal")
