#!/usr/bin/env bash
# The 1M tank with DFSPH at a spacing that divides the block exactly (0.002 m: 150 x 125 x 50).
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
o=$OUT/exact; mkdir -p $o
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $o/device.txt; date -u >> $o/device.txt
python3 scripts/gpu/scene-at.py hydrostatic /tmp/t.json 1000000 > /dev/null
dir=/tmp/ply; rm -rf $dir
timeout 300 $B record --scene /tmp/t.json --solver dfsph --spacing 0.002 --frames 24 --shading particles --size 64x36 --no-png \
  --export-particles ply --out $dir --force --records $o/base-0.002.csv --quiet > $o/base-0.002.txt 2>&1
echo "exit $?" >> $o/base-0.002.txt
(cd $dir && python3 $OLDPWD/scripts/gpu/fast-particles.py --spacing 0.002 --tank 0,0,0,0.3,0.4,0.1 --top 10 --speed 1.0 \
  particles_00000.ply particles_00001.ply particles_00002.ply particles_00023.ply) >> $o/base-0.002.txt 2>&1
cd $OUT && tar czf e.tgz exact && rm -rf exact
