#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: one bundled scene at one spacing for SECONDS simulated
# seconds, once per variant, the guard watching. A variant is a list of scene keys set on the bundled
# file (dotted paths, JSON values), "-" for none. Usage:
#     scripts/gpu/check-variants.sh SCENE SPACING SECONDS "-" "sph.max_time_step=0.002 sph.cfl=0.3" ...
# RANRYU_BIN picks the binary (build/gpu/app/ranryu); RUN_TIMEOUT bounds each run (300 s). Prints one
# line a variant: exit code (3: the guard fired, with its finding), substeps a frame, iterations a step.
set -uo pipefail
cd "$(dirname "$0")/../.."
B=${RANRYU_BIN:-build/gpu/app/ranryu}
scene=$1 spacing=$2 seconds=$3
shift 3
frames=$(python3 -c "print(max(1, round($seconds * 60)))")
dir=$(mktemp -d)
k=0
for variant in "$@"; do
  k=$((k + 1))
  python3 - "media/scenes/$scene.json" "$dir/v$k.json" $([ "$variant" = - ] || echo "$variant") <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for kv in sys.argv[3:]:
    key, value = kv.split("=", 1)
    *path, last = key.split(".")
    node = s
    for p in path: node = node.setdefault(p, {})
    node[last] = json.loads(value)
json.dump(s, open(sys.argv[2], "w"))
PY
  start=$(date +%s)
  timeout "${RUN_TIMEOUT:-300}" $B profile --scene "$dir/v$k.json" --spacing "$spacing" --shading particles --size 640x360 \
    --frames "$frames" --warmup 0 --json "$dir/v$k.out.json" > "$dir/v$k.txt" 2>&1
  rc=$?
  summary=$(python3 - "$dir/v$k.out.json" <<'PY'
import json, sys, os
if not os.path.exists(sys.argv[1]): sys.exit()
j = json.load(open(sys.argv[1])); s = j.get("simulation", {})
print(f"{j['particles']} particles, {s.get('substeps_per_frame', 0):.1f} substeps/frame, {s.get('iterations_per_step', 0):.2f} iterations/step "
      f"(most {s.get('most_iterations', 0)}, {s.get('unconverged_steps', 0)} steps at the cap), RTF {j['real_time_factor_gpu']:.3f}")
PY
)
  echo "$scene $spacing [$variant]: rc $rc, $(( $(date +%s) - start )) s; $summary $(grep -h '^ranryu:' "$dir/v$k.txt")"
done
