#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh all: is the turbulent jet stable with the force at a few
# amplitudes at ~1M particles (spacing 0.003 m, 963k)? Records 45 frames of each (the guard stops an
# unstable run with exit code 3) and keeps frames 20 and 44 for the README's side-by-side still.
# Usage: check-turbulence.sh "0 5 15 50" [spacing] [frames]
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
amps=${1:-"0 5 15 50"}
dx=${2:-0.003}
frames=${3:-45}
for A in $amps; do
  python3 - "$out" "$A" <<'PY'
import json, sys
s = json.load(open("media/scenes/turbulent-jet.json"))
s["turbulence"]["amplitude"] = float(sys.argv[2]); s["name"] = f"turbulent-jet-A{sys.argv[2]}"
if float(sys.argv[2]) == 0.0: del s["turbulence"]["subparticles"]   # they split by the force's ê
s["camera"] = {"eye": [1.25, 0.42, 0.62], "target": [0.78, 0.12, 0.1], "fov_deg": 40}   # closer to the jet's impact
json.dump(s, open(f"{sys.argv[1]}/jet-A{sys.argv[2]}.json", "w"))
PY
  rm -rf /tmp/jet-A$A
  start=$(date +%s.%N)
  $B record --scene "$out/jet-A$A.json" --spacing "$dx" --frames "$frames" --size 960x540 --shading ${SHADING:-fresnel} \
     --out /tmp/jet-A$A > "$out/jet-A$A.txt" 2>&1
  rc=$?
  end=$(date +%s.%N)
  echo "== A=$A rc=$rc wall $(python3 -c "print(round($end-$start,1))") s: $(tail -2 "$out/jet-A$A.txt" | tr '\n' ' ')"
  for f in ${KEEP:-20 30 44}; do
    p=$(printf "/tmp/jet-A%s/frame_%05d.png" "$A" "$f")
    [ -f "$p" ] && cp "$p" "$out/jet-A$A-${SHADING:-fresnel}-frame$f.png"
  done
done
# Per-pass timings of the bundled jet (force, carried noise, sub-particles) at the same resolution.
[ -n "${NOPROFILE:-}" ] && exit 0
$B profile --scene turbulent-jet --spacing "$dx" --size 960x540 --frames 6 --warmup 14 \
   --json "$out/jet-profile.json" > "$out/jet-profile.txt" 2>&1
echo "== profile jet (rc $?)"
grep -E "particles,|^(density|wavelet|forces|turbulence|integrate|subparticles|level-set|mc\.|draw)|sub-particles" "$out/jet-profile.txt"
