#!/usr/bin/env bash
cd "$(dirname "$0")"
nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv,noheader; date -u
nvcc --version | tail -2
nvcc -O3 -arch=sm_90 -Xptxas -v walk_bench.cu -o walk_bench 2>&1 | grep -E "registers|error|spill" | head -20
[ -x walk_bench ] || exit 1
echo "== 1M"; ./walk_bench 100 200 50
echo "== 1M, 256 a block"; ./walk_bench 100 200 50 256
echo "== 246k"; ./walk_bench 63 126 31
echo "== ncu, 1M, the engine's layout"
timeout 120 ncu --clock-control none --kernel-name regex:accelerate --launch-skip 1 --launch-count 1 \
  --section SpeedOfLight --section Occupancy --section LaunchStats --section WarpStateStats --section MemoryWorkloadAnalysis \
  ./walk_bench 100 200 50 > $OUT/ncu-accelerate.txt 2>&1; echo "ncu rc $?"
grep -E "Duration|Registers|Achieved Occupancy|Theoretical Occupancy|Memory Throughput|L1/TEX Hit|L2 Hit|Compute \(SM\)|DRAM Throughput|Stall|Warp Cycles Per Issued|Issued Warp|Active Warps|Eligible|Block Limit" $OUT/ncu-accelerate.txt | head -60
echo "== ncu, loads only"
timeout 100 ncu --clock-control none --kernel-name regex:loads_only --launch-skip 1 --launch-count 1 \
  --section SpeedOfLight --section Occupancy --section WarpStateStats --section MemoryWorkloadAnalysis \
  ./walk_bench 100 200 50 > $OUT/ncu-loads.txt 2>&1; echo "ncu rc $?"
grep -E "Duration|L1/TEX Hit|L2 Hit|Memory Throughput|Warp Cycles Per Issued|Achieved Occupancy" $OUT/ncu-loads.txt | head -20
