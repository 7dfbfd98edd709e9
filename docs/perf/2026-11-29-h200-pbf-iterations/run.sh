#!/usr/bin/env bash
# PBF's iterations against its substeps on the dam break (docs/PBF.md "Resolution"): the scene with
# sph.pbf = S x I at its own spacing for (4,4) (the defaults), (6,2), (8,1), each a build (the scenes
# are embedded), swept for 10 s at its own spacing, 246k and 1M particles.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $out/pi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/pi/device.txt; date -u >> $out/pi/device.txt
cp media/scenes/dam-break.json /tmp/db.json
t0=$(date +%s)
for v in 4x4 6x2 8x1; do
  s=${v%x*} i=${v#*x}
  python3 - $s $i <<'PY'
import json, sys
p = "media/scenes/dam-break.json"
d = json.load(open("/tmp/db.json"))
d["sph"]["pbf"] = {"substeps": int(sys.argv[1]), "iterations": int(sys.argv[2])}
json.dump(d, open(p, "w"), indent=1)
PY
  cmake --build build/gpu --target ranryu >/dev/null 2>&1 || { echo "build $v failed"; exit 1; }
  for dx in 0.0125 0.00317 0.002; do
    timeout 150 $B sweep --cases scene:dam-break --solvers pbf --factors 1 --spacings $dx --seconds 10 --quiet --out $out/pi/$v >> $out/pi/$v.log 2>&1
    echo "rc $? at $(( $(date +%s) - t0 )) s: $v $dx"
  done
done
python3 - $out/pi <<'PY'
import json, sys, glob
for f in sorted(glob.glob(sys.argv[1] + "/*/sweep.json")):
    for r in json.load(open(f))["rows"]:
        print(f.split("/")[-2], r["key"], r["status"], r.get("pbf_substeps"), r.get("pbf_iterations"),
              "peak %.3f %%" % (100 * (r.get("mean_density_deviation_peak") or 0)), "max %.3f" % (r.get("max_density_deviation") or 0),
              "%.0f GPU ms/sim s" % (r.get("gpu_ms_per_simulated_second") or 0), "wall %.1f" % (r.get("wall_seconds") or 0),
              r.get("failure_message", ""))
PY
cp /tmp/db.json media/scenes/dam-break.json
tar czf $out/pi.tgz -C $out pi && rm -rf $out/pi
