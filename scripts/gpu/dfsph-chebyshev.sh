#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: DFSPH's density solve with and without the Chebyshev
# acceleration of docs/DFSPH.md (D10), over SECONDS_RUN simulated seconds (default 10) of each of SCENES
# (default the dam break) at about PARTICLES particles (default 250000), for each rho of RHOS (default
# "0 0.95"; 0 is the plain relaxed Jacobi, the default). Particle shading at 640x360. Prints each run's
# verdict, substeps, iterations and real-time factor; reports and per-frame records under $OUT.
#     SCENES="dam-break hydrostatic" RHOS="0 0.95" scripts/gpu/dfsph-chebyshev.sh
. "$(dirname "$0")/env.sh" dfsph-chebyshev-out
frames=$(python3 -c "print(max(1, round(${SECONDS_RUN:-10} * 60)))")
for name in ${SCENES:-dam-break}; do
  for rho in ${RHOS:-0 0.95}; do
    file="$out/$name-c$rho.json"
    dx=$(python3 scripts/gpu/scene-at.py "$name" "$file" "${PARTICLES:-250000}" sph.chebyshev="$rho")
    timeout "${RUN_TIMEOUT:-200}" $B profile --scene "$file" --solver dfsph --spacing "$dx" --shading particles --size 640x360 \
      --frames "$frames" --warmup 0 --records "$out/$name-c$rho.csv" > "$out/$name-c$rho.txt" 2>&1
    echo "== $name, rho_c $rho, spacing $dx (rc $?) $(grep -m1 '^ranryu: simulation' "$out/$name-c$rho.txt")"
    grep -hE "substeps/frame \(|density solve|fps and real-time|^guard" "$out/$name-c$rho.txt" | sed 's/^/   /'
  done
done
