#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: where the dam break's fastest particles are at 1M
# particles (DFSPH as shipped), for each VARIANT "NAME:ETA[:KEY=VALUE,...]" (default "base:5e-4"):
# `ranryu record --export-particles ply` over FRAMES frames (default 130) with sph.max_density_error =
# ETA and the scene keys given (dotted, as scene-at.py takes them), then
# scripts/gpu/fast-particles.py on the frames of PICK (default "90 110 129"), and each frame's fastest
# particle and substeps from the records. NAME "nodrop" and "drop5" run a copy of glsl/ whose
# warm-start drop (glsl/sim/dfsph/dfsph.glsl warm_start_drop()) is off or at 5 % of rho0 instead of
# 1 %; any other NAME the shaders built in. Output: $OUT/dbfast.tgz (a report and the records per
# variant).
#     VARIANTS="base:5e-4 nodrop:5e-4 rows:5e-4:sph.boundary_rows=true" FRAMES=13 PICK="3 6 12" scripts/gpu/db-fast.sh
. "$(dirname "$0")/env.sh" dbfast-out
o=$out/dbfast; mkdir -p "$o"
variant() {
  rm -rf "/tmp/glsl-$1"; cp -r glsl "/tmp/glsl-$1"
  python3 - "/tmp/glsl-$1/sim/dfsph/dfsph.glsl" "$2" <<'PY'
import sys
path, value = sys.argv[1], sys.argv[2]
text = open(path).read()
old = "float warm_start_drop() { return 0.01 * sph.rest_density; }"
assert old in text, "warm_start_drop() has changed: update scripts/gpu/db-fast.sh"
open(path, "w").write(text.replace(old, "float warm_start_drop() { return " + value + "; }"))
PY
}
variant nodrop 1e30
variant drop5 "0.05 * sph.rest_density"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for v in ${VARIANTS:-base:5e-4}; do
  IFS=: read -r name eta keys <<< "$v"
  shaders=(); [ -d "/tmp/glsl-$name" ] && shaders=(--shader-dir "/tmp/glsl-$name")
  scene=/tmp/db-$eta.json tag=$name-$eta
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$scene" 1000000 sph.max_density_error="$eta" ${keys//,/ })
  dir=/tmp/dbfast-$tag; rm -rf "$dir"
  start=$(date +%s)
  timeout "${RUN_TIMEOUT:-200}" $B record --scene "$scene" --solver dfsph --spacing "$dx" --frames "${FRAMES:-130}" \
    --shading particles --size 64x36 --no-png --export-particles ply --out "$dir" --force "${shaders[@]}" \
    --records "$o/$tag.csv" --quiet > "$o/$tag.txt" 2>&1
  echo "== $tag: rc $?, $(( $(date +%s) - start )) s" | tee -a "$o/$tag.txt"
  files=(); for f in ${PICK:-90 110 129}; do files+=("$(printf 'particles_%05d.ply' "$f")"); done
  (cd "$dir" && python3 "$OLDPWD/scripts/gpu/fast-particles.py" --spacing "$dx" --tank 0,0,0,1,0.5,0.1 --top 6 \
     --speed 4.0 "${files[@]}") >> "$o/$tag.txt" 2>&1
  rm -rf "$dir"
  python3 - "$o/$tag.csv" <<'PY' | tee -a "$o/$tag.txt"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("  fastest particle by frame (m/s):", " ".join(f"{float(r['max_speed']):.1f}" for r in rows))
print("  substeps by frame:", " ".join(r["substeps"] for r in rows))
PY
  grep -A8 "^particles_" "$o/$tag.txt" | cut -c1-140
done
if [ -n "${OUT:-}" ]; then tar czf "$OUT/dbfast.tgz" -C "$out" dbfast && rm -rf "$o"; fi
