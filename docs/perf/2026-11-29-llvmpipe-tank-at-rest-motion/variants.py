#!/usr/bin/env python3
"""Writes the variants of the tank at rest measured here: media/scenes/hydrostatic.json under DFSPH with
one or two `sph` keys changed, into the folder given (default: the working directory)."""
import json
import os
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "."
root = os.path.join(os.path.dirname(__file__), "..", "..", "..")
base = json.load(open(os.path.join(root, "media", "scenes", "hydrostatic.json")))
base["sph"].pop("why", None)
base["sph"]["solver"] = "dfsph"
VARIANTS = {
    "base": {},
    "w1": {"warm_start": 1.0},
    "w1c0": {"warm_start": 1.0, "chebyshev": 0},
    "w1p3e4": {"warm_start": 1.0, "max_particle_density_error": 3e-4},
    "eta5": {"max_density_error": 1e-5},
    "p1e3": {"max_particle_density_error": 1e-3},
    "p3e4": {"max_particle_density_error": 3e-4},
    "cheb0": {"chebyshev": 0},
    "nu2": {"viscosity": 1e-2},
    "cfl2": {"dfsph_cfl": 0.2},
    "mi10": {"min_iterations": 10},
    "dt5": {"max_time_step": 5e-4},
    "akinci": {"boundary_rows": False},
    "div1": {"max_divergence_iterations": 1},
    "div4": {"max_divergence_error": 1e-4},
    "div5": {"max_divergence_error": 1e-5},
    "div4gc": {"max_divergence_error": 1e-4, "gradient_correction": True},
    "div5gc": {"max_divergence_error": 1e-5, "gradient_correction": True},
    "div5w1": {"max_divergence_error": 1e-5, "warm_start": 1.0},
    "div5e5": {"max_divergence_error": 1e-5, "max_density_error": 1e-5},
}
for name, keys in VARIANTS.items():
    s = json.loads(json.dumps(base))
    s["sph"].update(keys)
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump(s, f, indent=1)
# A tank three times as deep between its front and back walls (0.3 m), with div5's keys.
wide = json.loads(json.dumps(base))
wide["sph"]["max_divergence_error"] = 1e-5
wide["tank"]["max"][2] = 0.3
wide["particles"]["blocks"][0]["max"][2] = 0.3
with open(os.path.join(out, "div5wide.json"), "w") as f:
    json.dump(wide, f, indent=1)
