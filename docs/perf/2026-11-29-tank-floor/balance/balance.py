#!/usr/bin/env python3
"""The tank at rest's momentum balance on an exported frame (docs/VALIDATION.md "What is left at the
floor"): does each fluid particle's balance at rest, a^p_i = -g with (D3) and the rows of (D9), pin the
floor layer's pressure, given the frame's positions? Builds the tank, psi_b and the rows as
../one-step/solve.py does (it runs that script's set-up, its lines before the first print), then solves
for the rows' kappa_b (and, in turn, the lowest layers' kappa) by least squares.
Usage: /usr/bin/python3 balance.py ../one-step/particles_00089.ply 0.0125 0.0024"""
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
setup = open(os.path.join(here, '..', 'one-step', 'solve.py')).read()
exec(setup[:setup.index('print(f"{n} fluid')])
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import lsqr
R = len(rows)
I, J, Vv = [], [], []
def add(r, c, v):
    I.append(r); J.append(c); Vv.append(v)
for i in range(n):
    for comp in range(3):
        row = 3 * i + comp
        # a_i = -sum_j m (k_i + k_j) gW_ij - sum_b psi_b (k_i + k_b) gW_ib
        for j, _, gr in FF[i]:
            add(row, i, -m * gr[comp]); add(row, j, -m * gr[comp])
        for k, _, gr in FB[i]:
            add(row, i, -psi[k] * gr[comp])
            if k in row_of: add(row, n + row_of[k], -psi[k] * gr[comp])
A = sp.csr_matrix((Vv, (I, J)), shape=(3 * n, n + R))
b = np.zeros(3 * n); b[1::3] = -g   # a_y = +9.81: the pressure holds each particle against gravity
yl = np.array([X[i][1] for i in range(n)])
layer = np.floor(yl / dx).astype(int)
top = max(yl) + 0.5 * dx
rho_g = np.array(R_gpu)
k_gpu = np.array(P_gpu) / rho_g ** 2
k_ref = rho0 * 9.81 * (top - yl) / rho0 ** 2
def report(name, x):
    res = A @ x - b
    kf = x[:n]
    print(f"{name}: |res| rms {np.sqrt(np.mean(res ** 2)):.4f} m/s^2 (y {np.sqrt(np.mean(res[1::3] ** 2)):.4f})")
    for L in (0, 1, 2, 3, 10, 19):
        s = layer == L
        if s.any():
            print(f"   layer {L:2d}: p {np.mean(kf[s]) * rho0 ** 2:8.1f} Pa, ref {np.mean(k_ref[s]) * rho0 ** 2:8.1f}, (p-ref)/(rho g dx) {np.mean(kf[s] - k_ref[s]) * rho0 / (9.81 * dx):+.2f}")
def per_layer_res(name, x):
    res = (A @ x - b)[1::3]
    out = []
    for L in range(0, 20):
        s = layer == L
        if s.any(): out.append(f"{L}:{np.mean(res[s]):+.2f}")
    print(f"{name}: mean a_y error by layer (m/s^2): " + " ".join(out))
Ab = A[:, n:]
x2 = np.zeros(n + R); x2[:n] = k_ref
x2[n:] = lsqr(Ab, b - A[:, :n] @ k_ref, atol=1e-14, btol=1e-14, iter_lim=50000)[0]
report("hydrostatic kappa, rows fitted", x2)
per_layer_res("   ", x2)
x = np.zeros(n + R); x[:n] = k_gpu
x[n:] = lsqr(Ab, b - A[:, :n] @ k_gpu, atol=1e-14, btol=1e-14, iter_lim=50000)[0]
report("the GPU's kappa (the exported frame's pressure), rows fitted", x)
per_layer_res("   ", x)
# hydrostatic above layer K, free (fitted) at and below it, rows fitted
for K in (0, 1, 2):
    free = np.where(layer <= K)[0]
    cols = np.concatenate([free, n + np.arange(R)])
    As = A[:, cols]
    base = x2.copy(); base[n:] = 0
    sol = lsqr(As, b - A @ base, atol=1e-14, btol=1e-14, iter_lim=50000)[0]
    y = base.copy(); y[cols] += sol
    report(f"hydrostatic above layer {K}, layers 0..{K} and rows fitted", y)
    per_layer_res("   ", y)
# the layers' heights and their scatter: the wall orders the floor layer
ys = [np.mean(yl[layer == L]) / dx for L in range(layer.max() + 1)]
print("layer mean y/dx:", " ".join(f"{v:.3f}" for v in ys))
print("gaps /dx:", " ".join(f"{ys[L + 1] - ys[L]:.3f}" for L in range(len(ys) - 1)))
print("rms y scatter in a layer /dx:", " ".join(f"{np.std(yl[layer == L]) / dx:.3f}" for L in range(len(ys))))
