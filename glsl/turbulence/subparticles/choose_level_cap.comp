#version 430
// "subparticles.budget" (one invocation): how finely the budget lets the particles split, and the
// indirect arguments of the spawn pass, the splat pass and the sub-particles' draw.
//   in   state.counts = (n_1, n_2, n_3, sum) (scan_level_counts.comp); sub.levels = L_max, sub.budget = B
//   out  state: the cap C = the largest C <= L_max with need(C) = Σ_{L>=1} n_L·8^min(L, C) <= B, or 0
//        when even need(1) > B (then nothing splits); the effective level of a level-L particle is
//        E = min(L, C). The sub-particles are laid out level list by level list:
//            offsets = (0, n_1·8^E(1), n_1·8^E(1) + n_2·8^E(2)),  total = need(C)
//        dispatch = rows of ceil(total / group.y) workgroups (surface/dispatch_2d.glsl), w = total;
//        draw = (4, total, 0, 0); limits = (C, the raw finest level, need(L_max), B).
// need() saturates at 2^32 - 1 (a million particles at level 3 want 2^29; sixteen million, 2^33).
// Example (L_max = 3, B = 6000): n = (100, 50, 20): need(3) = 14240, need(2) = 800 + 3200 + 1280 = 5280
// -> C = 2, offsets (0, 800, 4000), total 5280; the 20 level-3 particles split to level 2.
#include "../../shared/bindings.h"

layout(local_size_x = 1) in;
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams sub; };
layout(std430) buffer Subparticles { SubparticleState state; };
layout(location = RANRYU_LOC_SUBPARTICLE_GROUP) uniform uvec4 group;   // y: spawn's local size

#include "../../surface/dispatch_2d.glsl"

const uint kMax = 0xFFFFFFFFu;

uint children(uint n, uint E) { return n > (kMax >> (3u * E)) ? kMax : n << (3u * E); }   // n·8^E, saturated
uint add(uint a, uint b) { return a > kMax - b ? kMax : a + b; }
uint need(uvec3 n, uint C) {
    return add(add(children(n.x, min(1u, C)), children(n.y, min(2u, C))), children(n.z, min(3u, C)));
}

void main() {
    uvec3 n = state.counts.xyz;
    uint finest = n.z > 0u ? 3u : n.y > 0u ? 2u : n.x > 0u ? 1u : 0u;
    uint cap = 0u;
    for (uint C = sub.levels; C >= 1u; --C)
        if (need(n, C) <= sub.budget) {
            cap = C;
            break;
        }
    uint total = cap > 0u ? need(n, cap) : 0u;
    uint o2 = cap > 0u ? children(n.x, 1u) : 0u;
    uint o3 = cap > 0u ? o2 + children(n.y, min(2u, cap)) : 0u;
    state.dispatch = uvec4(dispatch_2d((total + group.y - 1u) / group.y), total);
    state.draw = uvec4(4u, total, 0u, 0u);
    state.offsets = uvec4(0u, o2, o3, cap > 0u ? state.counts.w : 0u);
    state.limits = uvec4(cap, finest, need(n, sub.levels), sub.budget);
}
