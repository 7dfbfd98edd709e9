#!/usr/bin/env bash
# The calls as they ran on the GPU host (each after scripts/gpu/setup-and-build.sh, .gl carried).
# 1. before-250k/: the boundary rows as the default, no iteration step yet (a build of that tree):
#    SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet" RUN_TIMEOUT=170 scripts/gpu/scenes-seconds.sh 10
#    SOLVER=dfsph PARTICLES=250000 SCENES="hydrostatic" RUN_TIMEOUT=230 scripts/gpu/scenes-seconds.sh 10
# 2. max-time-step-250k/ (same build): VARIANTS="drop/base: drop/dt15:sph.max_time_step=0.0015 drop/dt08:sph.max_time_step=0.0008 ..." FRAMES=300 dtvar.sh
# 3. s250/, off/: OFF="dam-break/off:sph.shrink_step_above=0" gpu1.sh
# 4. s1m-*/: TAG=1m-drop PARTICLES=1000000 SCENES=drop RUN_TIMEOUT=570 gpu1.sh; likewise turbulent-jet (560) and dam-break (300);
#    s1m-tank/: TAG=1m-tank PARTICLES=1000000 SCENES=hydrostatic SECS=2 RUN_TIMEOUT=330 gpu1.sh
# 5. band/: OUT=$out/band VARIANTS="dam-break/b5-10:sph.grow_step_below=5,sph.shrink_step_above=10 dam-break/b15-30:sph.grow_step_below=15,sph.shrink_step_above=30
#    dam-break/b20-40:sph.grow_step_below=20,sph.shrink_step_above=40 drop/b5-10:... drop/b15-30:... drop/b20-40:..." FRAMES=600 RUN_TIMEOUT=90 dtvar.sh

# ---- gpu1.sh
# scratch: DFSPH defaults (rows + iteration step) at ~250k, 10 s: drop, jet, tank; the dam break as shipped at 246k.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
export OUT=$out/s${TAG:-250}; mkdir -p $OUT
SOLVER=dfsph PARTICLES=${PARTICLES:-250000} SCENES="${SCENES:-dam-break drop turbulent-jet hydrostatic}" RUN_TIMEOUT=${RUN_TIMEOUT:-150} scripts/gpu/scenes-seconds.sh ${SECS:-10}
python3 scratch/summ.py $OUT/*.csv
for f in $OUT/*.txt; do echo "== $f"; grep -E "^simulation|density solve|divergence solve|fps and" $f; done
tar czf $out/s${TAG:-250}.tgz -C $out s${TAG:-250} && rm -rf $OUT
if [ -n "${OFF:-}" ]; then
  export OUT=$out/off; mkdir -p $OUT
  VARIANTS="$OFF" FRAMES=600 RUN_TIMEOUT=150 scratch/dtvar.sh
  tar czf $out/off.tgz -C $out off && rm -rf $OUT
fi

# ---- dtvar.sh
# scratch: DFSPH at ~N particles on SCENE with variants of keys, FRAMES frames, records.
. scripts/gpu/env.sh dtvar-out
for spec in $VARIANTS; do
  sc=${spec%%/*}; rest=${spec#*/}; name=${rest%%:*}; keys=${rest#*:}
  f="$out/$sc-$name.json"
  dx=$(python3 scripts/gpu/scene-at.py "$sc" "$f" "${PARTICLES:-250000}" ${keys//,/ })
  timeout ${RUN_TIMEOUT:-150} $B profile --scene "$f" --solver dfsph --spacing "$dx" --shading particles --size 640x360 \
    --frames "${FRAMES:-300}" --warmup 0 --records "$out/$sc-$name.csv" > "$out/$sc-$name.txt" 2>&1
  echo "$sc $name rc=$? $(grep -m1 -E 'fps and real-time|simulation unstable' $out/$sc-$name.txt)"
done
python3 scratch/summ.py $out/*.csv

# ---- summ.py (python3), the summaries printed
# import csv, sys
# for fn in sys.argv[1:]:
#     rows = list(csv.DictReader(open(fn)))
#     print(fn.split('/')[-1], len(rows), "frames")
#     step = int(__import__("os").environ.get("STEP", "120"))
#     for k in range(0, len(rows), step):
#         blk = rows[k:k+step]
#         st = sum(int(r['substeps']) for r in blk); it = sum(int(r['iterations']) for r in blk)
#         un = sum(int(r['unconverged']) for r in blk)
#         print(f"  {k:3d}-{k+len(blk)-1:3d} t={float(blk[-1]['time']):5.2f} sub/f {st/len(blk):5.1f} it/step {it/max(st,1):5.1f} it/frame {it/len(blk):6.1f} capped {un:4d} maxrho {max(float(r['max_density']) for r in blk):.3f} maxv {max(float(r['max_speed']) for r in blk):.2f}")
