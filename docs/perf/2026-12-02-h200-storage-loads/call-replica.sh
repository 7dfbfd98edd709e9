#!/usr/bin/env bash
# The walk's replica (docs/perf/2026-11-29-h200-walk-floor/walk_bench.cu) with walk_bench_strong.patch: the
# accelerate walk with every load as the GL driver issues a storage block's (ld.relaxed.cta, SASS
# LDG.E.STRONG.SM), and with the masks loaded before the walk (per run, and in one loop over every run).
# Run from the repository root on the GPU host.
set -u
d=$(mktemp -d)
cp docs/perf/2026-11-29-h200-walk-floor/walk_bench.cu "$d/" && patch -s -d "$d" walk_bench.cu < docs/perf/2026-12-02-h200-storage-loads/walk_bench_strong.patch || exit 1
cd "$d"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for fm in "" "-use_fast_math"; do
  nvcc -O3 -arch=sm_90 $fm walk_bench.cu -o wb || exit 1
  cuobjdump --dump-sass wb | grep -oE "LDG[A-Z0-9.]*" | sort | uniq -c
  echo "== $fm 1M"; ./wb 100 200 50
  echo "== $fm 246k"; ./wb 63 126 31
done
