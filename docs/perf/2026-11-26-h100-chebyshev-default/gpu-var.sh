#!/usr/bin/env bash
# VARIANTS="scene/name:key=v,key=v ..." at ~PARTICLES (250000) for FRAMES (600), SOLVER (dfsph); summary per run.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
o=$out/${TAG:-var}; mkdir -p $o
for spec in ${VARIANTS}; do
  sn=${spec%%:*}; keys=${spec#*:}; scene=${sn%%/*}; name=${sn#*/}
  f="$o/$scene-$name.json"
  n=${PARTICLES:-250000}; [ "$n" = own ] && n=1000
  dx=$(python3 scripts/gpu/scene-at.py $scene "$f" "$n" ${keys//,/ })
  sp=(--spacing "$dx"); [ "${PARTICLES:-}" = own ] && sp=()
  t0=$(date +%s)
  timeout --preserve-status ${RUN_TIMEOUT:-90} $B profile --scene "$f" --solver ${SOLVER:-dfsph} "${sp[@]}" --shading particles --size 640x360 \
    --frames "${FRAMES:-600}" --warmup 0 --records "$o/$scene-$name.csv" > "$o/$scene-$name.txt" 2>&1
  rc=$?
  python3 - "$o/$scene-$name.csv" "$o/$scene-$name.txt" "$scene/$name" $rc $(( $(date +%s) - t0 )) <<'PY'
import csv,sys,re
rows=list(csv.DictReader(open(sys.argv[1]))) if open(sys.argv[1]).read(1) else []
txt=open(sys.argv[2]).read()
fps=re.search(r'([0-9.]+) fps and real-time factor ([0-9.]+)',txt)
g=[l for l in txt.splitlines() if l.startswith('guard') or l.startswith('ranryu: sim')]
it=re.search(r'density solve: ([0-9.]+) iterations/step.*?(\d+) steps stopped',txt)
n=len(rows)
sub=sum(float(r['substeps']) for r in rows)/max(n,1)
print(f"{sys.argv[3]}: rc {sys.argv[4]} wall {sys.argv[5]}s frames {n} t={rows[-1]['time'] if rows else '-'} "
      f"fps/rtf {fps.groups() if fps else '-'} substeps {sub:.1f} it {it.groups() if it else '-'} "
      f"maxrho {max((float(r['max_density']) for r in rows),default=0):.3f} maxv {max((float(r['max_speed']) for r in rows),default=0):.2f} "
      f"v_last2s {max((float(r['max_speed']) for r in rows[-120:]),default=0):.2f} {' | '.join(g)}")
PY
done
