#!/usr/bin/env bash
# The calls as they ran on the GPU host (NVIDIA H100 80GB HBM3, driver 580.159.04, 2026-11-26), each a
# `run` of the device tool with .gl carried; the two scratch scripts they used follow, as they were.
# 1. 1m-first-second/ (w05 compl drop0 w05drop0 w0 w05compl), the tree of commit 1a3529e:
#    VARIANTS="w05::sph.warm_start=0.5 compl::sph.complementarity_error=true drop0:drop0: w05drop0:drop0:sph.warm_start=0.5
#              w0::sph.warm_start=0 w05compl::sph.warm_start=0.5,sph.complementarity_error=true" FRAMES=60 RUN_TIMEOUT=82 bash gpu-tank.sh
# 2. dam-break-246k/ (the same tree): TAG=v250 VARIANTS="dam-break/base:: dam-break/drop0:drop0:
#    dam-break/w05drop0:drop0:sph.warm_start=0.5 hydrostatic/drop0:drop0: hydrostatic/w05drop0:drop0:sph.warm_start=0.5"
#    RUN_TIMEOUT=100 bash gpu-var.sh   (the two tank runs lost their records to the double SIGTERM fixed in 9a471cb)
# 3. 1m-first-second/ (cheb w05cheb drop01cheb w05drop01cheb drop01): VARIANTS="cheb::sph.chebyshev=0.98
#    w05cheb::sph.warm_start=0.5,sph.chebyshev=0.98 drop01cheb:drop01:sph.chebyshev=0.98
#    w05drop01cheb:drop01:sph.warm_start=0.5,sph.chebyshev=0.98 drop01:drop01:" FRAMES=60 RUN_TIMEOUT=80 bash gpu-tank.sh
# 4. tank-10s/w05cheb-*: media/scenes/hydrostatic.json with "warm_start": 0.5, "chebyshev": 0.98 in "sph":
#    OUT=$out/t1m SOLVER=dfsph PARTICLES=1000000 SCENES=hydrostatic RUN_TIMEOUT=565 scripts/gpu/scenes-seconds.sh 10
#    OUT=$out/t250 SOLVER=dfsph PARTICLES=250000 SCENES=hydrostatic RUN_TIMEOUT=300 scripts/gpu/scenes-seconds.sh 10
#    timeout 120 $B profile --scene media/scenes/hydrostatic.json --solver dfsph --frames 600 --warmup 0 --records own.csv
# 5. 1m-first-second/w075cheb: VARIANTS="w075cheb::sph.warm_start=0.75,sph.chebyshev=0.98" FRAMES=60 RUN_TIMEOUT=90 bash gpu-tank.sh
# 6. tank-10s/w075cheb-*: the scene as committed (0.75, 0.98), the three runs of 4 (RUN_TIMEOUT 400, 130, 40).

# ---- gpu-tank.sh
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh x
o=$out/tank; mkdir -p $o
for v in drop0:0.0 drop01:0.001; do rm -rf /tmp/g-${v%%:*} && cp -r glsl /tmp/g-${v%%:*} && sed -i "s/return 0.01 \* sph.rest_density;/return ${v#*:} * sph.rest_density;/" /tmp/g-${v%%:*}/sim/dfsph/dfsph.glsl; done
for spec in ${VARIANTS}; do
  name=${spec%%:*}; rest=${spec#*:}; sd=${rest%%:*}; keys=${rest#*:}
  f="$o/$name.json"
  dx=$(python3 scripts/gpu/scene-at.py hydrostatic "$f" "${PARTICLES:-1000000}" ${keys//,/ })
  sdarg=(); [ -n "$sd" ] && sdarg=(--shader-dir /tmp/g-$sd)
  timeout --preserve-status ${RUN_TIMEOUT:-80} $B profile "${sdarg[@]}" --scene "$f" --solver dfsph --spacing "$dx" --shading particles --size 640x360 \
    --frames "${FRAMES:-60}" --warmup 0 --records "$o/$name.csv" > "$o/$name.txt" 2>&1
done

# ---- gpu-var.sh: the same for "scene/name:shaderdir:key=v,key=v" at ~PARTICLES (250000), FRAMES (600) frames
