#!/usr/bin/env bash
# Run on the GPU host from the repository root after scripts/gpu/setup-and-build.sh, with OUT set.
# As shipped after the day's changes: every bundled scene at its own spacing (10 s of the dam break, 2 s of
# the others), then the dam break at 1M particles for 10 s.
. scripts/gpu/env.sh x
o=$OUT/s; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git log -1 --format=%h; } > $o/device.txt; cat $o/device.txt
for s in dam-break drop turbulent-jet hydrostatic falling-block; do
  n=120; [ $s = dam-break ] && n=600
  timeout 100 $B profile --scene $s --frames $n --warmup 0 --records $o/own-$s.csv > $o/own-$s.txt 2>&1
  echo "== $s own spacing, $n frames: rc $?"; grep -E "^scene|^simulation|fps and|^guard|^ranryu:" $o/own-$s.txt
done
OUT=$o NS=1000000 ETAS=1e-4 RUN_TIMEOUT=430 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its"
cd $OUT && tar czf s.tgz s && rm -rf s
