#!/usr/bin/env bash
# Call 1 (2026-12-02): the Kappa block as (x_i, kappa_i) a particle, the walks that gather kappa_j (the
# accelerate pass, the divergence solve's finish, the integration) reading x_j with it in one load
# (glsl/sim/dfsph/dfsph.glsl RANRYU_KAPPA_VEC4), against git's HEAD (2a65106, the wall's gradient sum).
#     mkdir -p scratch/base-glsl && git archive HEAD glsl | tar x -C scratch/base-glsl
# 1. the iteration at 30 iterations a solve at 246k and 1M, `head` against `current`, one binary (the
#    tree's, whose Kappa buffer holds 4N + 2 N_b floats: git's HEAD shaders use its first N for kappa_i
#    and the next 2 N_b for the rows, whose first kappa_b then start from 0 rather than the initial
#    guess: timing only);
# 2. the dam break as shipped for ten seconds at 246,078 with the tree (particles at 640x360; the same
#    arithmetic as git's HEAD, so its records should equal call 1 of ../2026-12-02-wall-gradient to the
#    bit), then at 1M, then at 246,078 with the whole pipeline at 1920x1080 (issue 11's measure).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
VARIANTS="head current" TEN_S_VARIANTS="current" timeout 200 scripts/gpu/iteration-bench.sh 2>&1 | \
  grep -E "^==|pressure.solve|divergence.solve|divergence.finish|dfsph.density|dfsph.integrate|fps and|guard"
OUT=$root/db-1m SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=130 timeout 140 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -4
(cd "$root" && tar czf db-1m.tgz db-1m && rm -rf db-1m)
mkdir -p "$root/whole"
timeout 60 "$B" profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 \
  --records "$root/whole/db-246k.csv" > "$root/whole/db-246k.txt" 2>&1
echo "== whole pipeline 246k rc $?: $(grep -m1 'fps and real-time' "$root/whole/db-246k.txt")"
grep -h "^guard:\|^ranryu: simulation\|substeps/frame\|density solve" "$root/whole/db-246k.txt" | head -5
(cd "$root" && tar czf whole.tgz whole && rm -rf whole)
