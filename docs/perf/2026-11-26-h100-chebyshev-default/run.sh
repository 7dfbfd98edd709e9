#!/usr/bin/env bash
# The calls as they ran on the GPU host (each a `run` of the device tool with .gl carried), with
# gpu-var.sh (this folder) copied to scratch/:
#    gpu-var.sh sets keys with scripts/gpu/scene-at.py; "base:" sets none.
# 1. VARIANTS="dam-break/base: dam-break/w075:sph.warm_start=0.75 drop/base: drop/w075:sph.warm_start=0.75
#      drop/w075cheb:sph.warm_start=0.75,sph.chebyshev=0.98 turbulent-jet/base: turbulent-jet/w075:sph.warm_start=0.75"
#    TAG=v250 RUN_TIMEOUT=80 bash scratch/gpu-var.sh                                       -> 250k-w075/
# 2. VARIANTS="drop/cheb:sph.chebyshev=0.98 turbulent-jet/cheb:sph.chebyshev=0.98
#      turbulent-jet/w075cheb:sph.warm_start=0.75,sph.chebyshev=0.98" TAG=v250b RUN_TIMEOUT=75 bash scratch/gpu-var.sh  -> 250k-cheb/
#    VARIANTS="drop/cheb:sph.chebyshev=0.98" PARTICLES=1000000 TAG=v1m RUN_TIMEOUT=270 bash scratch/gpu-var.sh       -> 1m/
# 3. VARIANTS="drop/base: drop/cheb:sph.chebyshev=0.98 turbulent-jet/base: turbulent-jet/cheb:sph.chebyshev=0.98"
#      PARTICLES=own TAG=own RUN_TIMEOUT=60 bash scratch/gpu-var.sh                         -> own-spacing/
#    VARIANTS="turbulent-jet/cheb:sph.chebyshev=0.98" PARTICLES=1000000 TAG=j1m RUN_TIMEOUT=240 bash scratch/gpu-var.sh -> 1m/
