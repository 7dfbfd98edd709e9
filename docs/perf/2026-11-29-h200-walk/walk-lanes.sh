#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: what a DFSPH iteration costs with each particle's
# neighbour walk split over several invocations (docs/PERFORMANCE.md "A particle's walk over several
# invocations"). Each variant is a copy of glsl/ run with --shader-dir:
#     head     the iteration passes of git's HEAD (BASE_GLSL, default scratch/base-glsl: the development
#              machine fills it before the call, `git archive HEAD glsl | tar x -C scratch/base-glsl`)
#     XxY      accelerate.comp and correct_pressure.comp laid out as local_size_x = X particles and
#              local_size_y = Y lanes a particle (XxY invocations a workgroup)
# Runs, with every variant of VARIANTS: the dam break with every density solve fixed at ITERATIONS
# iterations (sph.min_iterations = sph.max_iterations; the step rule (D8) off), so that the solve's
# time over its iterations is an iteration's cost, at about each particle count of COUNTS (default
# "64000 246078 1000000"), FRAMES frames after WARMUP, particle shading at 640x360. Prints the DFSPH
# passes. Then the variants of TEN_S_VARIANTS (default none) run the dam break as shipped for ten
# simulated seconds at about 250k particles. Reports under $OUT/lanes (tarred as $OUT/lanes.tgz).
#     VARIANTS="head 32x3" COUNTS=246078 scripts/gpu/walk-lanes.sh
. "$(dirname "$0")/env.sh" walk-lanes-out
o=$out/lanes; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
work=$(mktemp -d)
variants=${VARIANTS:-head 128x1 64x2 64x3 32x4}
ten_s_variants=${TEN_S_VARIANTS:-}
iterations=${ITERATIONS:-30}
for v in $(echo $variants $ten_s_variants | tr ' ' '\n' | sort -u); do
  if [ "$v" = head ]; then
    cp -r "${BASE_GLSL:-scratch/base-glsl}/glsl" "$work/$v" || { echo "no $v shaders"; exit 2; }
    continue
  fi
  x=${v%x*} y=${v#*x}
  cp -r glsl "$work/$v"
  for f in sim/dfsph/accelerate.comp sim/dfsph/correct_pressure.comp; do
    grep -q 'layout(local_size_x = 64, local_size_y = 2) in;' "$work/$v/$f" ||
      { echo "$f has changed; update scripts/gpu/walk-lanes.sh"; exit 2; }
    sed -i "s/layout(local_size_x = 64, local_size_y = 2) in;/layout(local_size_x = $x, local_size_y = $y) in;/" "$work/$v/$f"
  done
done
passes='dfsph\.(density|boundary|divergence|pressure|integrate)|frame \(GPU|^simulation|density solve|divergence solve|fps and|^guard|^ranryu:'
for n in ${COUNTS:-64000 246078 1000000}; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/scene-$n.json" "$n" sph.min_iterations="$iterations" \
       sph.max_iterations="$iterations" sph.shrink_step_above=0)
  frames=${FRAMES:-10} warmup=${WARMUP:-20}
  [ "$n" -ge 500000 ] && frames=${FRAMES:-5} warmup=${WARMUP:-5}
  for v in $variants; do
    f=$o/db-$v-$n
    timeout 200 "$B" profile --scene "$o/scene-$n.json" --spacing "$dx" --shading particles --size 640x360 \
      --frames "$frames" --warmup "$warmup" --shader-dir "$work/$v" > "$f.txt" 2>&1
    echo "== $v $n ($dx): rc $?"
    grep -E "$passes" "$f.txt" | grep -v "^why its settings"
  done
done
if [ -n "$ten_s_variants" ]; then
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/db10-scene.json" 250000)
  for v in $ten_s_variants; do
    f=$o/db10-$v
    timeout 150 "$B" profile --scene "$o/db10-scene.json" --spacing "$dx" --shading particles --size 640x360 \
      --frames 600 --warmup 0 --shader-dir "$work/$v" --records "$f.csv" > "$f.txt" 2>&1
    echo "== 10 s $v $dx: rc $?"
    grep -E "$passes" "$f.txt" | grep -v "^why its settings"
  done
fi
if [ -n "${OUT:-}" ]; then (cd "$out" && tar czf lanes.tgz lanes && rm -rf lanes); fi
