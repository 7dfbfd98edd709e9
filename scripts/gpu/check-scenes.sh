#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: every bundled scene for SECONDS simulated seconds with each
# solver at a resolution, the guard watching (issue 11: no guard fires). Usage:
#     scripts/gpu/check-scenes.sh "dfsph wcsph" own|250k|1M [seconds]
# own: each scene's own spacing; 250k and 1M: the spacing that gives about that many particles,
# (fluid volume / N)^(1/3) with the volumes below. Particles drawn as points (the surface passes do
# not touch the simulation). RUN_TIMEOUT bounds each run (580 s). Each run's output goes to $OUT (or ./bench-out); a table is printed last:
# scene, solver, particles, frames, exit code (3: the guard fired, with its finding), substeps a frame.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
solvers=${1:-"dfsph wcsph"}
scale=${2:-own}
seconds=${3:-10}
frames=$(python3 -c "print(max(1, round($seconds * 60)))")
# Fluid volumes (m^3) of media/scenes/*.json: the blocks' sizes.
declare -A volume=([dam-break]=0.008 [drop]=0.023328 [turbulent-jet]=0.026 [hydrostatic]=0.0075 [falling-block]=0.048)
for scene in dam-break drop turbulent-jet hydrostatic falling-block; do
  case $scale in
    own) spacing=() ;;
    250k) spacing=(--spacing "$(python3 -c "print(f'{(${volume[$scene]} / 250e3) ** (1 / 3):.5f}')")") ;;
    1M) spacing=(--spacing "$(python3 -c "print(f'{(${volume[$scene]} / 1e6) ** (1 / 3):.5f}')")") ;;
    *) echo "check-scenes.sh: scale must be own, 250k or 1M, not \"$scale\"" >&2; exit 2 ;;
  esac
  for s in $solvers; do
    # falling-block has no SPH: one run, without --solver.
    solver=(--solver "$s")
    if [ "$scene" = falling-block ]; then [ "$s" != "${solvers%% *}" ] && continue; solver=(); fi
    name="scene-$scene-$s-$scale"
    start=$(date +%s.%N)
    timeout "${RUN_TIMEOUT:-580}" $B profile --scene "$scene" "${solver[@]}" "${spacing[@]}" --shading particles --size 640x360 \
      --frames "$frames" --warmup 0 --json "$out/$name.json" > "$out/$name.txt" 2>&1
    rc=$?
    wall=$(python3 -c "import time; print(f'{time.time() - $start:.0f}')")
    echo "== $name: rc $rc, ${wall} s"
    grep -E "^(ranryu:|simulation)" "$out/$name.txt"
  done
done
python3 - "$out" "$scale" <<'PY'
import json, sys, glob, os, re
print(f"{'scene':14} {'solver':6} {'particles':>9} {'frames':>6} {'substeps':>8} {'outcome'}")
for txt in sorted(glob.glob(os.path.join(sys.argv[1], f"scene-*-{sys.argv[2]}.txt"))):
    name = os.path.basename(txt)[6:-4 - len(sys.argv[2]) - 1]
    scene, solver = name.rsplit("-", 1)
    js = txt[:-4] + ".json"
    text = open(txt).read()
    bad = [l for l in text.splitlines() if l.startswith("ranryu:")]
    if os.path.exists(js) and not bad:
        j = json.load(open(js)); s = j.get("simulation", {})
        print(f"{scene:14} {solver:6} {j['particles']:9d} {j['frames']:6d} {s.get('substeps_per_frame', 0):8.1f} stable")
    else:
        m = re.search(r"(\d+) particles", text)
        print(f"{scene:14} {solver:6} {m.group(1) if m else '?':>9} {'':>6} {'':>8} {bad[0] if bad else 'no result (timeout?)'}")
PY
