#!/usr/bin/env bash
# Call 2 (2026-12-02): DFSPH's wall drag sph.boundary_viscosity (docs/DFSPH.md (D7)) over both
# experiments: `validate impact-pressure` (Lobovsky et al. 2014) at H/dx = 48 and 96 and `validate
# dam-break` (Martin & Moyce 1952) at a/dx = 40 and 80, each with nu_b in {0, 1e-5, 1e-4, 3e-4, 1e-3} m^2/s
# (1e-3 as the dam break ships), the scenes otherwise as shipped.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT/drag; mkdir -p "$o"
for nu in 0 1e-5 1e-4 3e-4 1e-3; do
  python3 - "$nu" "$o" <<'PY'
import json, sys
nu, o = float(sys.argv[1]), sys.argv[2]
for name, path in (("impact", "media/validation/impact-pressure.json"), ("dam", "media/scenes/dam-break.json")):
    s = json.load(open(path))
    s.pop("$schema", None)
    s["sph"]["boundary_viscosity"] = nu
    json.dump(s, open(f"{o}/{name}-{sys.argv[1]}.json", "w"), indent=1)
PY
  for dx in 0.00625 0.003125; do
    timeout 200 "$B" validate impact-pressure --scene "$o/impact-$nu.json" --spacing $dx --quiet --json "$o/impact-$nu-$dx.json" > "$o/impact-$nu-$dx.txt" 2>&1
    echo "== impact nu $nu dx $dx rc $?: $(grep -E '^ +P[134] ' "$o/impact-$nu-$dx.txt" | tr -s ' ' | tr '\n' '|')"
  done
  for dx in 0.005 0.0025; do
    timeout 200 "$B" validate dam-break --scene "$o/dam-$nu.json" --spacing $dx --quiet --json "$o/dam-$nu-$dx.json" > "$o/dam-$nu-$dx.txt" 2>&1
    echo "== dam nu $nu dx $dx rc $?: $(grep -E 'surge front error|steps in' "$o/dam-$nu-$dx.txt" | tr '\n' '|')"
  done
done
(cd "$OUT" && tar czf drag.tgz drag && rm -rf drag)
