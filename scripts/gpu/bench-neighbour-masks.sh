#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh all: the SPH tests on the GPU, then the dam break's
# substep at 100k, 1M and 4M particles with the density pass's neighbour masks for forces
# (sph.neighbour_masks, the default) and at 1M without them (forces walks the grid again).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
build/gpu/tests/ranryu_gl_tests "[sph]" > "$out/sph-tests.txt" 2>&1
grep -E "FAILED|with expansion|with message" -A4 "$out/sph-tests.txt" | head -40; tail -2 "$out/sph-tests.txt"
python3 - "$out" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
v = dict(s); v["sph"] = dict(s["sph"], neighbour_masks=False); v["name"] = "dam-break-walk"
json.dump(v, open(f"{sys.argv[1]}/dam-break-walk.json", "w"))
PY
prof() {  # name, then ranryu profile arguments
  local name=$1; shift
  $B profile --size 640x360 --frames 6 --warmup 2 --json "$out/$name.json" "$@" > "$out/$name.txt" 2>&1
  echo "== $name (rc $?)"; grep -E "particles|^(hash|sort|cell|reorder|density|forces|integrate|choose)" "$out/$name.txt"
}
prof db-1m-walk --scene "$out/dam-break-walk.json" --spacing 0.002
prof db-1m-masks --scene dam-break --spacing 0.002
prof db-100k-masks --scene dam-break --spacing 0.00431
prof db-4m-masks --scene dam-break --spacing 0.00126
for f in db-1m-walk db-1m-masks db-100k-masks db-4m-masks; do
  python3 - "$out/$f.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
passes = r["passes"] if isinstance(r, dict) and "passes" in r else r
sub = ("choose-time-step", "hash", "sort.count", "sort.scan", "sort.scatter", "reorder", "density", "forces", "integrate")
tot = 0.0
for p in passes:
    if p["name"] in sub:
        tot += p["ms_per_call"] * p["calls_per_frame"] / [q for q in passes if q["name"] == "integrate"][0]["calls_per_frame"]
print(sys.argv[1].split("/")[-1], "substep ms", round(tot, 4))
PY
done
# The sub-particle passes at 1M parents, 10/50/100 % energetic (tests/gl/subparticle_test.cpp).
build/gpu/tests/ranryu_gl_tests "[subparticles],[turbulence],[grid]" > "$out/sub-tests.txt" 2>&1
grep -E "FAILED|with expansion" -A4 "$out/sub-tests.txt" | head -30; tail -2 "$out/sub-tests.txt"
build/gpu/tests/ranryu_gl_tests "[subparticle-bench]" > "$out/subparticle-bench.txt" 2>&1
grep -E "^sub-particles,|^(subparticles|level-set|surface)" "$out/subparticle-bench.txt"
