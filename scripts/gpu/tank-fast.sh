#!/usr/bin/env bash
# Where the tank at rest's fastest particles are in its first frames, at about N particles each
# (PARTICLES, default "1000000 250000"), with DFSPH (the scene itself ships PBF), for each VARIANT
# ("name:key=value,key=value", "base:" the scene's other settings as shipped): `ranryu record
# --export-particles ply` over FRAMES frames (default 6), then
# scripts/gpu/fast-particles.py on frames 0, 1, 2 and the last. Output: $OUT/tank-fast/*.txt, *.csv.
#     VARIANTS="base: rows:sph.boundary_rows=true" scripts/gpu/tank-fast.sh
# DIVIDING=1 takes the spacing nearest N's that divides the block (scene-at.py --dividing), so that
# the lattice stands half a spacing from every wall.
. "$(dirname "$0")/env.sh" tank-fast-out
o="$out/tank-fast"; mkdir -p "$o"
FRAMES=${FRAMES:-6}
for n in ${PARTICLES:-1000000 250000}; do
  for v in ${VARIANTS:-base:}; do
    name=${v%%:*}; keys=${v#*:}
    scene="/tmp/tank-$name.json"
    dx=$(scripts/gpu/scene-at.py ${DIVIDING:+--dividing} hydrostatic "$scene" "$n" ${keys//,/ })
    tank=$(python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["tank"]; print(",".join(map(str, t["min"] + t["max"])))' "$scene")
    tag="$name-$n"; dir="/tmp/tank-$tag"; rm -rf "$dir"
    timeout ${RUN_TIMEOUT:-200} "$B" record --scene "$scene" --solver dfsph --spacing "$dx" --frames "$FRAMES" \
      --shading particles --size 64x36 --no-png --export-particles ply --out "$dir" --force \
      --records "$o/$tag.csv" --quiet > "$o/$tag.txt" 2>&1
    echo "exit $? (spacing $dx)" >> "$o/$tag.txt"
    last=$(printf 'particles_%05d.ply' $((FRAMES - 1)))
    (cd "$dir" && python3 "$OLDPWD/scripts/gpu/fast-particles.py" --spacing "$dx" --tank "$tank" --top 10 \
       --speed 1.0 particles_00000.ply particles_00001.ply particles_00002.ply "$last") >> "$o/$tag.txt" 2>&1
    rm -rf "$dir"
  done
done
