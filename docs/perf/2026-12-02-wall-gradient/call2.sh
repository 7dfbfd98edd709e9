#!/usr/bin/env bash
# Call 2 (2026-12-02): call 1's drop and jet at about 1M with --solver dfsph passed single-frame density
# spikes with the patch (1.54 and 1.80 rho0) where the tree had reached 1.34 and 1.47 on 2026-12-01. The
# patch changes the residual's boundary term by rounding only (a_i . sum_b psi_b gradW_ib summed once
# instead of per neighbour), so the question is whether the margin was already that thin: both scenes at
# about 900k particles (another spacing, so another trajectory), the shaders of git's HEAD against the
# patched ones, one binary (the patch applied; git's HEAD shaders ignore RANRYU_WALL_GRADIENT_AT).
#     mkdir -p scratch/base-glsl && git archive HEAD glsl | tar x -C scratch/base-glsl
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
for v in head current; do
  dir=$root/$v; mkdir -p "$dir"
  glsl=glsl; [ "$v" = head ] && glsl=scratch/base-glsl/glsl
  for name in drop turbulent-jet; do
    dx=$(python3 scripts/gpu/scene-at.py "$name" "$dir/$name.json" 900000)
    timeout 110 "$B" profile --scene "$dir/$name.json" --solver dfsph --spacing "$dx" --shading particles --size 640x360 \
      --frames 600 --warmup 0 --shader-dir "$glsl" --records "$dir/$name.csv" > "$dir/$name.txt" 2>&1
    echo "== $v $name $dx rc $?: $(grep -m1 -oE '[0-9]+ particles' "$dir/$name.txt"), $(grep -m1 'fps and real-time' "$dir/$name.txt")"
    grep -h "^guard:\|^ranryu: simulation" "$dir/$name.txt"
  done
  (cd "$root" && tar czf "$v.tgz" "$v" && rm -rf "$v")
done
