#!/usr/bin/env bash
# The residual pass's excess over the accelerate pass: variants of correct_pressure.comp with one part
# left out each (the rows' code, (D10)'s step and its KappaPrevious, the workgroup reduction; `lean` all
# three), the dam break with every density solve fixed at 30 iterations, --detail; then the NVIDIA shader
# cache's machine code, for the passes' register counts.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b1.txt 2>&1 || { tail -30 /tmp/b1.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $o/device.txt; date -u | tee -a $o/device.txt
export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/glcache __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1
mkdir -p /tmp/glcache
for n in 1000000 246078; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s-$n.json $n sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
  fr=5; wu=5; [ $n -lt 500000 ] && { fr=10; wu=20; }
  for v in current norowsc nocheb noreduce lean current; do
    d=glsl; [ $v != current ] && d=scratch/$v/glsl
    f=/tmp/r-$v-$n.txt
    timeout 120 $B profile --scene /tmp/s-$n.json --spacing $dx --shading particles --size 640x360 --frames $fr --warmup $wu --detail --shader-dir $d > $f 2>&1
    echo "== $v $n rc $?"; grep -E "dfsph.pressure.(solve|correct|accelerate)|density solve:" $f
    cat $f >> $o/runs.txt
  done
done
echo "== cache"; find /tmp/glcache -type f | head; du -sh /tmp/glcache
python3 - <<'PY' > $o/cache.txt 2>&1
import os,glob,subprocess
n=0
for p in glob.glob('/tmp/glcache/**/*',recursive=True):
    if not os.path.isfile(p): continue
    b=open(p,'rb').read()
    print(p,len(b),'NVcp' ,b.count(b'!!NVcp'),'ELF',b.count(b'\x7fELF'))
    i=b.find(b'\x7fELF')
    while i>=0:
        fn=f'/tmp/elf{n}.cubin'; import struct
        shoff=struct.unpack_from('<Q',b,i+0x28)[0]; shes,shn=struct.unpack_from('<HH',b,i+0x3A)
        open(fn,'wb').write(b[i:i+shoff+shes*shn]); n+=1
        r=subprocess.run(['cuobjdump','-res-usage',fn],capture_output=True,text=True)
        print(fn, r.stdout[-3000:], r.stderr[-500:])
        i=b.find(b'\x7fELF',i+4)
    j=b.find(b'!!NVcp')
    if j>=0: print(b[j:j+400].decode('latin1'))
PY
head -c 20000 $o/cache.txt
