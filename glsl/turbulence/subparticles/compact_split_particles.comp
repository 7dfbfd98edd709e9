#version 430
// "subparticles.classify", step 3 of 3: the per-level lists of the particles to split, in cell order.
//   in   level[i] = L_i (classify_particles.comp); block[wg] = the particles of each level in earlier
//        workgroups (scan_level_counts.comp); same local size as classify (C++ checks)
//   out  list[(L - 1)·particles + k] = the index of the k-th particle of level L, ascending
// Within a workgroup a particle's rank among those of its level is an exclusive scan of "is level L";
// adding the earlier workgroups' count gives its place. No atomics: the lists are the same every run,
// and so are the sub-particles' order and the images drawn from them.
// Example (4 invocations a workgroup, block (2,0,1,0)): L = 1, 0, 3, 1 -> list_1[2] = i0, list_1[3] = i3,
// list_3[1] = i2.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams sub; };
layout(std430) readonly buffer SubparticleLevels { uint level[]; };
layout(std430) readonly buffer SubparticleBlocks { uvec4 block[]; };
layout(std430) writeonly buffer SubparticleLists { uint list[]; };

#include "../../surface/workgroup_scan.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint L = i < sub.particle_count ? level[i] : 0u;   // no early return: the scans have barriers
    uvec2 total;
    uvec2 rank12 = workgroup_exclusive_scan(uvec2(L == 1u ? 1u : 0u, L == 2u ? 1u : 0u), total);
    uvec2 rank3 = workgroup_exclusive_scan(uvec2(L == 3u ? 1u : 0u, 0u), total);
    if (L == 0u) return;
    uvec3 rank = uvec3(rank12, rank3.x), before = block[gl_WorkGroupID.x].xyz;
    list[(L - 1u) * sub.particle_count + before[L - 1u] + rank[L - 1u]] = i;
}
