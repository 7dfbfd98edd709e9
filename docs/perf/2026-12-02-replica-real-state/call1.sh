#!/usr/bin/env bash
# Call 1 (2026-12-02, evening): the CUDA replica of the walk (walk_real.cu) on the dam break's own
# particles, against the engine's passes on the same states. Every density solve fixed at 30
# iterations (as iteration-bench.sh), (D8) off, at about 246,078 particles: `record` exports the
# particles of frame 25 (the surge) and of frame 399 (the settled pool); `profile --detail` times the
# engine's accelerate and residual passes over frames 20-29 and 395-404 of the same run. The replica
# walks the exported positions (no walls) and, for the baseline, its jittered lattice.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT; here=docs/perf/2026-12-02-replica-real-state
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; nvcc --version | tail -1; } > "$root/device.txt"
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s30.json 246078 sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
echo "dx $dx" | tee -a "$root/device.txt"
patch -s -o /tmp/walk_real.cu docs/perf/2026-11-29-h200-walk-floor/walk_bench.cu $here/walk_real.patch
nvcc -O3 -arch=sm_90 -Xptxas -v /tmp/walk_real.cu -o /tmp/walk_real > "$root/nvcc.txt" 2>&1 || { tail -20 "$root/nvcc.txt"; exit 1; }
timeout 150 "$B" record --scene /tmp/s30.json --spacing "$dx" --frames 400 --export-particles ply --no-png \
  --shading particles --size 64x36 --out /tmp/rec --force --quiet > "$root/record.txt" 2>&1
echo "== record rc $?"; ls /tmp/rec | wc -l
for w in 20 395; do
  timeout 120 "$B" profile --scene /tmp/s30.json --spacing "$dx" --shading particles --size 640x360 \
    --frames 10 --warmup $w --detail > "$root/profile-$w.txt" 2>&1
  echo "== profile warmup $w rc $?"
  grep -E "dfsph\.pressure\.(accelerate|correct|solve)|dfsph\.density |^simulation|density solve" "$root/profile-$w.txt"
done
echo "== replica, lattice at 246k"; /tmp/walk_real 63 126 31 | tee "$root/replica-lattice.txt"
for f in 00025 00399; do
  echo "== replica, frame $f"; /tmp/walk_real --ply /tmp/rec/particles_$f.ply "$dx" | tee "$root/replica-$f.txt"
done
