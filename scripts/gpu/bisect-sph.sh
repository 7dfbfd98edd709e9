#!/usr/bin/env bash
# Diagnosis on the GPU host: runs `validate hydrostatic` with shader variants made by sed.
# The record of the bisection in docs/PERFORMANCE.md (the looped row merge that read wrong sums on
# NVIDIA 580): its sed patterns match glsl/sim/sph/sph_common.glsl as of commit 56bca8e, so check
# that commit out to repeat it; on later shaders the variants equal the base.
set -uo pipefail
cd "$(dirname "$0")/../.."
B=build/gpu/app/ranryu
variant() {  # name, sed script applied to sph_common.glsl
  rm -rf /tmp/v-$1; cp -r glsl /tmp/v-$1; sed -i "$2" /tmp/v-$1/sim/sph/sph_common.glsl
  echo "== $1: $($B validate hydrostatic --spacing 0.02 --shader-dir /tmp/v-$1 2>&1 | tail -1)"
}
variant base 's/^$//'
variant cells 's/x0_ += (grid.morton != 0u ? 1 : 3)/x0_ += 1/; s/#define ROW_END(x0) (grid.morton != 0u ? (x0) : 1)/#define ROW_END(x0) (x0)/'
variant nofluidcheck 's/if (s < sph.particle_count \&\& sorted_keys\[s\] == key) return/if (s < sph.particle_count) return/'
variant barrier 's/    atomicMax(wg_max_, bits);/    memoryBarrierShared(); atomicMax(wg_max_, bits); memoryBarrierShared();/'
