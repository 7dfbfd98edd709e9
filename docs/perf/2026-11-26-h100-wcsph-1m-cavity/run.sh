#!/usr/bin/env bash
# The calls as they ran on the GPU host (each a `run` of the device tool with .gl carried); gpu-var.sh is
# in docs/perf/2026-11-26-h100-chebyshev-default/, gpu-av.sh in this folder, both copied to scratch/.
# VARIANTS="dam-break/base: dam-break/c47:sph.speed_of_sound=47" SOLVER=wcsph PARTICLES=1000000 FRAMES=75 TAG=w1m RUN_TIMEOUT=110 bash scratch/gpu-var.sh
# VARIANTS="dam-break/base:" SOLVER=wcsph PARTICLES=1000000 FRAMES=72 TAG=w1m RUN_TIMEOUT=100 bash scratch/gpu-var.sh   (with the guard's positions)
# ALPHAS="0.02 0.05" bash scratch/gpu-av.sh
# VARIANTS="dam-break/av01:sph.artificial_viscosity=0.1" SOLVER=wcsph PARTICLES=1000000 FRAMES=600 TAG=w10 RUN_TIMEOUT=575 bash scratch/gpu-var.sh
# validate/: for dx in 0.005 0.0025; for FILE in the scene with sph.artificial_viscosity 0 and 0.1:
#   $B validate dam-break --solver wcsph --spacing $dx --scene FILE --json wcsph-$dx-{0,av}.json
