#version 430
// "subparticles.classify", step 2 of 3 (one workgroup): exclusive prefix sums of the per-workgroup
// level counts, in workgroup order, and the totals.
//   in   block[b] = (n_1, n_2, n_3, 0) of classify workgroup b, b < ceil(particles / group.x)
//   out  block[b] = (particles of level 1, 2, 3 in workgroups before b, 0); state.counts = (n_1, n_2, n_3, sum)
// The blocks are scanned in chunks of this workgroup's size with a running carry (uniform control
// flow: the chunk count is the same for every invocation). Example: blocks (1,0,2,0) (0,0,0,0)
// (3,1,0,0) -> (0,0,0,0) (1,0,2,0) (1,0,2,0); counts (4,1,2,7).
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams sub; };
layout(std430) buffer SubparticleBlocks { uvec4 block[]; };
layout(std430) buffer Subparticles { SubparticleState state; };
layout(location = RANRYU_LOC_SUBPARTICLE_GROUP) uniform uvec4 group;   // x: classify's local size

#include "../../surface/workgroup_scan.glsl"

void main() {
    uint blocks = (sub.particle_count + group.x - 1u) / group.x;
    uvec3 carry = uvec3(0u);
    for (uint base = 0u; base < blocks; base += SCAN_SIZE) {
        uint b = base + gl_LocalInvocationIndex;
        uvec4 v = b < blocks ? block[b] : uvec4(0u);
        uvec2 total12, total3;
        uvec2 before12 = workgroup_exclusive_scan(v.xy, total12);
        uvec2 before3 = workgroup_exclusive_scan(uvec2(v.z, 0u), total3);
        if (b < blocks) block[b] = uvec4(carry + uvec3(before12, before3.x), 0u);
        carry += uvec3(total12, total3.x);
    }
    if (gl_LocalInvocationIndex == 0u) state.counts = uvec4(carry, carry.x + carry.y + carry.z);
}
