#!/usr/bin/env bash
# The walk's replica with every load as the GL driver issues them (ld.relaxed.cta, SASS LDG.E.STRONG.SM).
cd "$(dirname "$0")"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for fm in "" "-use_fast_math"; do
  nvcc -O3 -arch=sm_90 $fm walk_bench_strong.cu -o wb || exit 1
  cuobjdump --dump-sass wb | grep -oE "LDG[A-Z0-9.]*" | sort | uniq -c
  echo "== $fm 1M"; ./wb 100 200 50
  echo "== $fm 246k"; ./wb 63 126 31
done
