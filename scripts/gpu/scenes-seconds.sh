#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: every bundled SPH scene with SOLVER (default pbf) at about
# PARTICLES particles (default 1000000) for SECONDS simulated seconds (default 10), the guard watching
# (issue 11's "10 s at about 250k and 1M"). Each scene runs as shipped but with --solver SOLVER and the
# spacing that fills its blocks with about PARTICLES particles (PBF's substeps scaled to that spacing,
# docs/PBF.md "Resolution"); SUBSTEPS_dam_break (e.g. 5) overrides the dam break's PBF substeps at its
# own spacing; SCENES (default all four) picks scenes; KEYS adds scene keys to every scene
# ("sph.max_density_error=1e-3", dotted, as scene-at.py takes them). Particle shading at 640x360 (the simulation is
# what is tested). Prints each scene's verdict and frame rate; reports under $OUT.
#     SOLVER=wcsph PARTICLES=250000 scripts/gpu/scenes-seconds.sh 10
# A run longer than a device call: CHECKPOINTS=DIR (an ignored folder a warm machine keeps between calls,
# e.g. build/gpu/checkpoints) makes each run stopped by RUN_TIMEOUT write DIR/NAME.ckpt (profile
# --checkpoint), and the next call with the same settings, issued while the machine is still warm, go on
# from it (profile --resume) to the last frame; its records then start at the checkpoint's frame
# (docs/perf/2026-11-30-h200-tank-1m-ten-seconds/ ran the tank so, by hand). A checkpoint whose scene,
# spacing or solver is not this call's (other SOLVER, PARTICLES or KEYS) is refused, naming the file.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-scenes-seconds-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
seconds=${1:-10}
frames=$(python3 -c "print(max(1, round($seconds * 60)))")
solver=${SOLVER:-pbf}
for name in ${SCENES:-dam-break drop turbulent-jet hydrostatic}; do
  file="$out/$name.json"
  dam=()
  [ "$name" = dam-break ] && [ -n "${SUBSTEPS_dam_break:-}" ] && dam=(sph.pbf.substeps="$SUBSTEPS_dam_break")
  dx=$(python3 scripts/gpu/scene-at.py "$name" "$file" "${PARTICLES:-1000000}" "${dam[@]}" ${KEYS:-})
  start=(--scene "$file" --solver "$solver" --spacing "$dx")
  left=$frames
  keep=()
  if [ -n "${CHECKPOINTS:-}" ]; then
    mkdir -p "$CHECKPOINTS"
    ckpt="$CHECKPOINTS/$name.ckpt"
    keep=(--checkpoint "$ckpt")
    if [ -f "$ckpt" ]; then   # the frame it goes on from, from the file's JSON header (engine/frame/checkpoint.h)
      at=$(python3 -c "
import json, struct, sys
f = open(sys.argv[1], 'rb'); f.read(12); n = struct.unpack('<Q', f.read(8))[0]
h = json.loads(f.read(n)); sc = h['scene']
if (json.loads(sc['source']) != json.load(open(sys.argv[2])) or sc['solver'] != sys.argv[3]
        or abs(float(sc['spacing']) - float(sys.argv[4])) > 1e-6 * float(sys.argv[4])):
    sys.exit(f'{sys.argv[1]}: a checkpoint of another scene, spacing or solver than this call\'s; remove it to start afresh')
print(h['frame'])" "$ckpt" "$file" "$solver" "$dx") || continue
      left=$((frames - at))
      [ "$left" -le 0 ] && { echo "$name: its checkpoint is at frame $at of $frames already"; continue; }
      start=(--resume "$ckpt")
      echo "$name: going on from its checkpoint at frame $at"
    fi
  fi
  timeout "${RUN_TIMEOUT:-150}" $B profile "${start[@]}" "${keep[@]}" --shading particles --size 640x360 \
    --frames "$left" --warmup 0 --records "$out/$name.csv" > "$out/$name.txt" 2>&1
  rc=$?
  verdict=$(grep -m1 "^ranryu: simulation" "$out/$name.txt" || grep -m1 "fps and real-time" "$out/$name.txt" ||
            grep -m1 "^ranryu: interrupted" "$out/$name.txt" || echo "rc $rc")
  particles=$(grep -m1 -oE '[0-9]+ particles' "$out/$name.txt")
  echo "$name at $dx${particles:+ ($particles)}, $(grep -m1 -oE '[0-9.]+ substeps/frame' "$out/$name.txt"), $left of $frames frames: $verdict"
  grep -h "^guard:" "$out/$name.txt"
done
