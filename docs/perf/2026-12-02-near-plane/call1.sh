#!/usr/bin/env bash
# Call 1 (2026-12-02, night): the compute raster's spheres cut by the near plane drawn as the draw draws
# them (glsl/render/rasterise_impostors.comp: the quad clipped at the near plane, the quad's point tested
# a pixel). 1. the whole GL suite on the H200 (the new render case among it), and the render cases five
# times more with fresh seeds; 2. what the change costs the compute raster where no sphere is cut: the
# dam break at 1M with particle shading, 30 frames after 10, at 640x360 and 1920x1080, the tree's shaders
# against the shader before it (change.patch reversed, --shader-dir), one binary, each twice in turn.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
start=$(date +%s)
build/gpu/tests/ranryu_gl_tests > "$root/gl-tests.txt" 2>&1
echo "== gl suite rc $?: $(tail -2 "$root/gl-tests.txt" | head -1), $(( $(date +%s) - start )) s"
for k in 1 2 3 4 5; do
  build/gpu/tests/ranryu_gl_tests "render:*" > /tmp/r.txt 2>&1; echo "== render cases rc $?: $(tail -2 /tmp/r.txt | head -1)"
  grep -E "seed|FAILED" /tmp/r.txt | head -4
done
base=/tmp/base-glsl; rm -rf $base; cp -r glsl $base
(cd $base/.. && patch -s -R -p1 < "$OLDPWD/docs/perf/2026-12-02-near-plane/change.patch") || { echo "patch failed"; exit 1; }
mkdir -p "$root/raster"
f="$root/raster/db-1m.json"
dx=$(python3 scripts/gpu/scene-at.py dam-break "$f" 1000000)
for size in 640x360 1920x1080; do
  for turn in 1 2; do
    for v in base tree; do
      dir=glsl; [ $v = base ] && dir=$base
      timeout 60 "$B" profile --scene "$f" --spacing "$dx" --shading particles --size $size --frames 30 --warmup 10 \
        --shader-dir "$dir" > "$root/raster/$v-$size-$turn.txt" 2>&1
      echo "== $v $size $turn rc $?: $(grep -E '^draw-particles|^frame \(GPU' "$root/raster/$v-$size-$turn.txt" | tr -s ' ' | tr '\n' '|')"
    done
  done
done
