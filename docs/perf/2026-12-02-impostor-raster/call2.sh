#!/usr/bin/env bash
# Call 2 (2026-12-02): the sub-particles by the impostors' compute raster (BY_LEVEL) against the draw:
# the turbulent jet as shipped at about 1M particles (PBF, the turbulence force and its sub-particles),
# particle shading, 20 frames after 150 (the jet pours, and its sub-particles appear once its energy builds,
# not in its first frames), at 640x360 and 1920x1080, each raster, the passes within timed apart on the compute raster.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
mkdir -p "$root/jet"
f="$root/jet/jet-1m.json"
dx=$(python3 scripts/gpu/scene-at.py turbulent-jet "$f" 1000000)
for size in 640x360 1920x1080; do
  for raster in draw compute; do
    detail=()
    [ $raster = compute ] && detail=(--detail)
    RANRYU_PARTICLE_RASTER=$raster timeout 90 "$B" profile --scene "$f" --spacing "$dx" --shading particles --size $size \
      --frames 20 --warmup 150 "${detail[@]}" > "$root/jet/$raster-$size.txt" 2>&1
    echo "== $raster $size rc $?: $(grep -E '^draw-particles|^frame \(GPU|^subparticles.spawn' "$root/jet/$raster-$size.txt" | tr -s ' ' | tr '\n' '|')"
    grep -E "^  draw-particles|^sub-particles \(last" "$root/jet/$raster-$size.txt"
  done
done
(cd "$root" && tar czf jet.tgz jet && rm -rf jet)
