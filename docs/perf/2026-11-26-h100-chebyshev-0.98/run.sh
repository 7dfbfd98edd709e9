#!/usr/bin/env bash
# Call B: the dam break's Chebyshev radius (sph.chebyshev) over 10 s at 246k: 0.95 (shipped), 0.98, 0.99.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh b-out
o=$out/b; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
start=$(date +%s)
for rho in 0.95 0.98 0.99; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/db-$rho.json" 250000 sph.chebyshev=$rho)
  f=$o/db10-$rho
  timeout 150 "$B" profile --scene "$o/db-$rho.json" --spacing "$dx" --shading particles --size 640x360 \
    --frames 600 --warmup 0 --records "$f.csv" > "$f.txt" 2>&1
  echo "== 10 s rho $rho $dx: rc $? at $(( $(date +%s) - start )) s"
  grep -E "dfsph.pressure.solve|frame \(GPU|^simulation|density solve|fps and|spike|^ranryu:" "$f.txt"
done
(cd "$out" && tar czf b.tgz b && rm -rf b)
#!/usr/bin/env bash
# Call C: sph.chebyshev 0.98 in the dam break: 10 s at its own spacing (0.95 and 0.98) and at 1M (0.98).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh c-out
o=$out/c; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
start=$(date +%s)
for rho in 0.95 0.98; do
  python3 - "$rho" "$o/own-$rho.json" <<'PY'
import json, sys, re
s = json.load(open("media/scenes/dam-break.json")); s["sph"]["chebyshev"] = float(sys.argv[1])
json.dump(s, open(sys.argv[2], "w"))
PY
  f=$o/own-$rho
  timeout 60 "$B" profile --scene "$o/own-$rho.json" --frames 600 --warmup 0 --records "$f.csv" > "$f.txt" 2>&1
  echo "== own spacing rho $rho: rc $?"; grep -E "^scene|^simulation|density solve|fps and|spike|^ranryu:" "$f.txt"
done
dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/db1m.json" 1000000 sph.chebyshev=0.98)
timeout 420 "$B" profile --scene "$o/db1m.json" --spacing "$dx" --shading particles --size 640x360 \
  --frames 600 --warmup 0 --records "$o/db1m-0.98.csv" > "$o/db1m-0.98.txt" 2>&1
echo "== 1M rho 0.98 $dx: rc $? at $(( $(date +%s) - start )) s"
grep -E "^scene|dfsph.pressure.solve|^simulation|density solve|fps and|spike|^ranryu:" "$o/db1m-0.98.txt"
(cd "$out" && tar czf c.tgz c && rm -rf c)
#!/usr/bin/env bash
# Call D: the dam break's surge (frames 20-40, whole pipeline at 1920x1080) with sph.chebyshev 0.95 and 0.98.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh d-out
o=$out/d; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
for dx in 0.00317 0.002; do
  for rho in 0.95 0.98; do
    python3 - "$rho" "$o/db-$rho.json" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json")); s["sph"]["chebyshev"] = float(sys.argv[1])
json.dump(s, open(sys.argv[2], "w"))
PY
    f=$o/surge-$rho-$dx
    timeout 120 "$B" profile --scene "$o/db-$rho.json" --spacing "$dx" --size 1920x1080 --frames 20 --warmup 20 > "$f.txt" 2>&1
    echo "== $dx rho $rho: rc $?"; grep -E "dfsph.pressure.solve|frame \(GPU|^simulation|density solve|fps and|^ranryu:" "$f.txt"
  done
done
(cd "$out" && tar czf d.tgz d && rm -rf d)
