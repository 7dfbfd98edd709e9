#!/usr/bin/env bash
cd "$(dirname "$0")"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
nvcc -O3 -arch=sm_90 walk_bench.cu -o walk_bench || exit 1
nvcc -O3 -arch=sm_90 -use_fast_math walk_bench.cu -o walk_fast || exit 1
cuobjdump --dump-sass walk_bench | awk '/Function : .*accelerateILb0/,/EXIT/' | grep -cE "^\s+/\*[0-9a-f]+\*/" | sed 's/^/accelerate SASS instructions (IEEE): /'
cuobjdump --dump-sass walk_fast | awk '/Function : .*accelerateILb0/,/EXIT/' | grep -cE "^\s+/\*[0-9a-f]+\*/" | sed 's/^/accelerate SASS instructions (fast math): /'
for b in walk_bench walk_fast; do
  echo "== $b 1M"; ./$b 100 200 50
  echo "== $b 246k"; ./$b 63 126 31
done
timeout 100 ncu --clock-control none --kernel-name regex:accelerate_rsqrt --launch-skip 1 --launch-count 1 \
  --section SpeedOfLight --section Occupancy --section WarpStateStats ./walk_bench 100 200 50 > $OUT/ncu-rsqrt.txt 2>&1
grep -E "Duration|Compute \(SM\) Throughput|Warp Cycles Per Issued|Active Threads Per Warp|Achieved Occupancy" $OUT/ncu-rsqrt.txt
cp walk_bench.cu $OUT/
