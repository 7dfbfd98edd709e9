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
  timeout "${RUN_TIMEOUT:-150}" $B profile --scene "$file" --solver "$solver" --spacing "$dx" --shading particles --size 640x360 \
    --frames "$frames" --warmup 0 --records "$out/$name.csv" > "$out/$name.txt" 2>&1
  rc=$?
  verdict=$(grep -m1 "^ranryu: simulation" "$out/$name.txt" || grep -m1 "fps and real-time" "$out/$name.txt" || echo "rc $rc")
  echo "$name at $dx ($(grep -m1 -oE '[0-9]+ particles' "$out/$name.txt")), $(grep -m1 -oE '[0-9.]+ substeps/frame' "$out/$name.txt"), $frames frames: $verdict"
  grep -h "^guard:" "$out/$name.txt"
done
