#!/usr/bin/env python3
"""Each run's errors and its first layers' offsets from rho0 g (H - z), in spacings of head (rho0 g dx):
    python3 layers.py h200/hs-*.json llvmpipe/*.json"""
import json, sys
for f in sys.argv[1:]:
    d = json.load(open(f))
    if 'layers' not in d:
        continue
    dx, L = d['spacing'], d['layers']
    head = d.get('rest_density', 1000.0) * 9.81 * dx
    print(f"{f:44s} interior {100*d['max_error_over_rho_g_H']:.2f} floor {100*d['floor_error_over_rho_g_H']:.2f}"
          f" pairs {100*d['pair_error_over_rho_g_H']:.2f} rms {d['mean_rms_speed']:.4f} |",
          ' '.join(f"{(l['pressure'] - l['reference']) / head:+.2f}" for l in L[:5]), '...',
          ' '.join(f"{(l['pressure'] - l['reference']) / head:+.2f}" for l in L[-3:]))
