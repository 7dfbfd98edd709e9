#version 430
// "subparticles.classify", step 1 of 3: the raw level of every particle (docs/METHOD.md §6;
// engine/turbulence/subparticles.h gives the rule and its reasoning).
//   in   energy[i].w = ê_i (m²/s²), the wavelet energy of the fluid's cell order; sub.level_energy
//   out  level[i] = L_i = the number of k in [0, levels) with ê_i >= level_energy[k]
//            (= min(L_max, 1 + floor(log2(ê_i/e_th) / 2β)) for ê_i >= e_th, else 0)
//        block[workgroup] = (n_1, n_2, n_3, 0): how many of this workgroup's particles have L = 1, 2, 3
// Thresholds instead of log2: comparisons are exact, so the CPU's count from the same ê is the GPU's
// to the particle (a log2 a few ulp off would move particles at a level boundary). A NaN ê is level 0;
// an infinite one L_max (the min: the thresholds past L_max are +inf).
// Example (L_max = 2, e_th = 0.01, β = 1/3: level_energy = (0.01, 0.0159, +inf)): ê = 0.005, 0.01,
// 0.012, 0.02, 7 -> L = 0, 1, 1, 2, 2; block = (2, 2, 0, 0).
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams sub; };
layout(std430) readonly buffer WaveletEnergy { vec4 energy[]; };
layout(std430) writeonly buffer SubparticleLevels { uint level[]; };
layout(std430) writeonly buffer SubparticleBlocks { uvec4 block[]; };

shared uint counts[4];

void main() {
    uint l = gl_LocalInvocationIndex;
    if (l < 4u) counts[l] = 0u;
    memoryBarrierShared();
    barrier();
    uint i = gl_GlobalInvocationID.x;
    if (i < sub.particle_count) {
        float e = energy[i].w;
        uint L = min(uint(e >= sub.level_energy.x) + uint(e >= sub.level_energy.y) + uint(e >= sub.level_energy.z), sub.levels);
        level[i] = L;
        if (L > 0u) atomicAdd(counts[L], 1u);
    }
    memoryBarrierShared();
    barrier();
    if (l == 0u) block[gl_WorkGroupID.x] = uvec4(counts[1], counts[2], counts[3], 0u);
}
