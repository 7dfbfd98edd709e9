#version 430
// "subparticles.splat" (docs/METHOD.md §7; engine/surface/level_set.h): the sub-particles' share of φ.
// One invocation per sub-particle (glDispatchComputeIndirect with SubparticleState.dispatch, the
// spawn pass's arguments: the same local size, C++ checks). A level-E sub-particle at x_c adds
//     (V/8^E) · W(|x - x_c|, R_E),   R_E = max(R·2^-E, RANRYU_SUBPARTICLE_KERNEL_FLOOR · h)
// to every node x of the φ grid (spacing h) within R_E, as a fixed-point integer (2^-24 units, rounded
// to nearest) with atomicAdd: integer sums commute, so the grid is the same whatever order the
// invocations run in. compute_level_set.comp (built with RANRYU_SUBPARTICLES) adds the grid to the
// parents' gather and sets it back to 0, so it is all zero between frames.
//   - V/8^E: 8^E children share their parent's volume; W is normalised, so each keeps it, at any R_E.
//   - R_E = R/2^E keeps a lone child's surface a sphere of radius r/2^E (the level set's iso is a lone
//     particle's radius r = dx/2 with R = 1.5 dx: the kernel and the volume scale together). Below
//     2 node spacings a kernel is sampled by too few nodes to keep its volume (h³·Σ W over the nodes
//     strays from 1 by up to 9 % at 1.5 h, 0.2 % at 2 h, as the child moves), so R_E stops there
//     (level_set.h has the numbers; at the default h = dx/2 the floor is dx).
// Sub-particles farther than the grid's margin (level_set.h) from it add only to the nodes it has.
#include "../shared/bindings.h"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) readonly buffer Subparticles { SubparticleState state; };
layout(std430) readonly buffer SubparticlePositions { vec4 sub_position[]; };
layout(std430) buffer SplatGrid { uint splat[]; };

#include "../sim/kernel.glsl"
#include "dispatch_2d.glsl"

void main() {
    uint g = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    uvec3 dims = surface_grid.dims.xyz;
    if (g >= state.dispatch.w || dims.x == 0u) return;
    vec4 p = sub_position[g];
    int E = int(p.w);
    vec3 origin = surface_grid.origin.xyz;
    float h = surface_grid.origin.w;
    float R = max(ldexp(surface.kernel_radius, -E), float(RANRYU_SUBPARTICLE_KERNEL_FLOOR) * h);
    float scale = ldexp(surface.volume, -3 * E) * float(RANRYU_SUBPARTICLE_SPLAT_SCALE);
    ivec3 lo = max(ivec3(ceil((p.xyz - R - origin) / h)), ivec3(0));
    ivec3 hi = min(ivec3(floor((p.xyz + R - origin) / h)), ivec3(dims) - 1);
    for (int k = lo.z; k <= hi.z; ++k)
        for (int j = lo.y; j <= hi.y; ++j)
            for (int i = lo.x; i <= hi.x; ++i) {
                vec3 x = origin + h * vec3(uvec3(i, j, k));   // as the gather computes its node
                float r = length(x - p.xyz);
                if (r < R) atomicAdd(splat[uint(i) + dims.x * (uint(j) + dims.y * uint(k))], uint(scale * kernel_w(r, R) + 0.5));
            }
}
