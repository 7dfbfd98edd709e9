#version 430
// "surface.bounds", step 1 of 2: the box around the particles' centres.
//   in   sorted_position[0, surface.particle_count), less the parked ones (w = -1: the emitter's
//        budget not poured in yet, engine/sim/fluid.h)
//   out  surface_grid.bounds_min/max = ordered_bits of the smallest/largest x, y, z
// The caller clears bounds_min to 0xFFFFFFFF and bounds_max to 0 first. Each workgroup reduces its
// particles in shared memory (a tree: the local size is a power of two) and makes one atomicMin and
// one atomicMax per axis. Integer min/max is exact and commutes, so the box does not depend on the
// order in which workgroups finish.
#include "../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) readonly buffer Positions { vec4 sorted_position[]; };
layout(std430) buffer SurfaceGridState { SurfaceGrid surface_grid; };

#include "ordered_float.glsl"

shared uvec3 lowest[gl_WorkGroupSize.x];
shared uvec3 highest[gl_WorkGroupSize.x];

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint l = gl_LocalInvocationIndex;
    uvec3 lo = uvec3(0xFFFFFFFFu), hi = uvec3(0u);   // identities of min and max
    if (i < surface.particle_count && sorted_position[i].w > -0.5) {
        lo = ordered_bits(sorted_position[i].xyz);
        hi = lo;
    }
    lowest[l] = lo;
    highest[l] = hi;
    memoryBarrierShared();
    barrier();
    for (uint s = gl_WorkGroupSize.x / 2u; s > 0u; s >>= 1u) {
        if (l < s) {
            lowest[l] = min(lowest[l], lowest[l + s]);
            highest[l] = max(highest[l], highest[l + s]);
        }
        memoryBarrierShared();
        barrier();
    }
    if (l == 0u) {
        atomicMin(surface_grid.bounds_min.x, lowest[0].x);
        atomicMin(surface_grid.bounds_min.y, lowest[0].y);
        atomicMin(surface_grid.bounds_min.z, lowest[0].z);
        atomicMax(surface_grid.bounds_max.x, highest[0].x);
        atomicMax(surface_grid.bounds_max.y, highest[0].y);
        atomicMax(surface_grid.bounds_max.z, highest[0].z);
    }
}
