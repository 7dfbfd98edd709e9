#!/usr/bin/env bash
# Call 8: PBF's correction with s_corr's n = 4 as two multiplies (sq) against pow (head), the dam break
# with PBF at 1M, frames 20-30, particle shading; and PBF's programs' machine code (the driver's cache).
set -u
# scratch/base-glsl: `git archive HEAD glsl`; scratch/sq: the same with variants/sq.patch of this folder.
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -20 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
for v in head sq head sq; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  timeout 60 $B profile --scene dam-break --solver pbf --spacing 0.002 --shading particles --size 640x360 --frames 10 --warmup 20 --shader-dir $d > /tmp/p-$v.txt 2>&1
  echo "== $v rc $?"; grep -E "^pbf\.(lambda|correct)|fps and" /tmp/p-$v.txt
done
mkdir -p /tmp/cache-pbf
__GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-pbf timeout 60 $B profile --scene dam-break --solver pbf --spacing 0.002 --shading particles --size 640x360 --frames 2 --warmup 0 --shader-dir scratch/base-glsl/glsl > /dev/null 2>&1
cp /tmp/p-*.txt $OUT/ ; tar czf $OUT/cache-pbf.tgz -C /tmp cache-pbf
