#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: what a DFSPH iteration costs, the shaders of git's HEAD
# against this tree's (docs/PERFORMANCE.md "The boundary rows' neighbour masks"). Variants, each
# run with --shader-dir:
#     head     glsl/ of git's HEAD (BASE_GLSL, default scratch/base-glsl: the development machine
#              fills it before the call, `git archive HEAD glsl | tar x -C scratch/base-glsl`)
#     current  this tree's glsl/
#     NAME     any other name: scratch/NAME/glsl, a variant the development machine wrote there
# Runs, with every variant of VARIANTS: the dam break with every density solve fixed at ITERATIONS
# iterations (sph.min_iterations = sph.max_iterations; the step rule (D8) off), so that the solve's
# time over its iterations is an iteration's cost, at about each particle count of COUNTS (default
# "246078 1000000"), FRAMES frames after WARMUP, particle shading at 640x360. Then the variants of
# TEN_S_VARIANTS (default none) run the dam break as shipped for ten simulated seconds at about 250k
# particles, with their records, and the variants of WCSPH_VARIANTS (default none) run it with WCSPH at
# about WCSPH_COUNT particles (default 246078), FRAMES frames after WARMUP (default 10 after 20), its
# passes timed a substep. Prints the passes; reports under $OUT/bench (tarred as $OUT/bench.tgz).
#     VARIANTS="head current" TEN_S_VARIANTS="head current" scripts/gpu/iteration-bench.sh
. "$(dirname "$0")/env.sh" iteration-bench-out
o=$out/bench; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
work=$(mktemp -d)
# The clocks, power and load through the run, to tell a slow pass from a slow chip.
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,pstate,power.draw,utilization.gpu --format=csv -lms 1000 \
  > "$o/clocks.csv" 2>&1 &
clocks=$!
variants=${VARIANTS:-head current}
ten_s_variants=${TEN_S_VARIANTS:-}
wcsph_variants=${WCSPH_VARIANTS:-}
iterations=${ITERATIONS:-30}
for v in $(echo $variants $ten_s_variants $wcsph_variants | tr ' ' '\n' | sort -u); do
  case $v in
    head) cp -r "${BASE_GLSL:-scratch/base-glsl}/glsl" "$work/$v" || { echo "no $v shaders"; exit 2; } ;;
    current) cp -r glsl "$work/$v" ;;
    *) cp -r "scratch/$v/glsl" "$work/$v" || { echo "unknown variant $v (no scratch/$v/glsl)"; exit 2; } ;;
  esac
done
passes='dfsph\.(density|boundary|divergence|pressure|integrate)|^(density|forces|integrate) |frame \(GPU|^simulation|density solve|divergence solve|fps and|^guard|^ranryu:'
for n in ${COUNTS:-246078 1000000}; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/scene-$n.json" "$n" sph.min_iterations="$iterations" \
       sph.max_iterations="$iterations" sph.shrink_step_above=0)
  frames=${FRAMES:-10} warmup=${WARMUP:-20}
  [ "$n" -ge 500000 ] && frames=${FRAMES:-5} warmup=${WARMUP:-5}
  for v in $variants; do
    f=$o/db-$v-$n
    timeout 200 "$B" profile --scene "$o/scene-$n.json" --spacing "$dx" --shading particles --size 640x360 \
      --frames "$frames" --warmup "$warmup" --shader-dir "$work/$v" > "$f.txt" 2>&1
    rc=$?   # N is the count asked for; the spacing's lattice holds the count the profile names
    echo "== $v $n ($dx, $(grep -m1 -oE '[0-9]+ particles' "$f.txt")): rc $rc"
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
if [ -n "$wcsph_variants" ]; then
  n=${WCSPH_COUNT:-246078}
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/wcsph-scene.json" "$n")
  for v in $wcsph_variants; do
    f=$o/wcsph-$v-$n
    timeout 200 "$B" profile --scene "$o/wcsph-scene.json" --solver wcsph --spacing "$dx" --shading particles --size 640x360 \
      --frames "${FRAMES:-10}" --warmup "${WARMUP:-20}" --shader-dir "$work/$v" --records "$f.csv" > "$f.txt" 2>&1
    echo "== wcsph $v $n ($dx): rc $?"
    grep -E "$passes" "$f.txt" | grep -v "^why its settings"
  done
fi
kill "$clocks" 2>/dev/null
if [ -n "${OUT:-}" ]; then (cd "$out" && tar czf bench.tgz bench && rm -rf bench); fi
