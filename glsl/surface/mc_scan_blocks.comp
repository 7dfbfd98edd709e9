#version 430
// "mc.compact", step 1 of 2 (ONE workgroup): exclusive prefix sums of the blocks' (active, vertices),
// and the indirect arguments that follow from the totals.
//   in   blocks[0, B) from mc_classify, B = mc.cell_dispatch.x * mc.cell_dispatch.y (padding blocks hold 0)
//   out  blocks[b] = sums over blocks 0..b-1
//        mc.totals.xyz = (active cells, vertices, 1 if vertices > capacity)
//        mc.emit_dispatch = (dispatch_2d(groups), active cells listed = min(active, capacity.y))
//        mc.draw = (vertices cut to a whole number of triangles within capacity.x, 1, 0, 0)
// The workgroup walks the blocks in chunks of local_size * SCAN_ITEMS and carries the running sum
// from chunk to chunk, so any B works without a third level (16.7M cells = 65536 blocks = 16 chunks).
#include "../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std430) buffer Mesh { MeshState mc; };
layout(std430) buffer McBlocks { uvec2 blocks[]; };
layout(location = RANRYU_LOC_SURFACE_CAPACITY) uniform uvec4 capacity;   // x vertices, y active cells
layout(location = RANRYU_LOC_SURFACE_GROUP) uniform uvec4 group;         // x: mc_emit's local size

#include "workgroup_scan.glsl"
#include "dispatch_2d.glsl"

#define SCAN_ITEMS 16u   // blocks per invocation per chunk

void main() {
    uint count = mc.cell_dispatch.x * mc.cell_dispatch.y;
    uint rank = gl_LocalInvocationIndex;
    uvec2 carry = uvec2(0u);
    for (uint base = 0u; base < count; base += SCAN_SIZE * SCAN_ITEMS) {
        uint first = base + rank * SCAN_ITEMS;
        uvec2 v[SCAN_ITEMS];
        uvec2 sum = uvec2(0u);
        for (uint j = 0u; j < SCAN_ITEMS; ++j) {
            v[j] = first + j < count ? blocks[first + j] : uvec2(0u);
            sum += v[j];
        }
        uvec2 total;
        uvec2 run = carry + workgroup_exclusive_scan(sum, total);
        for (uint j = 0u; j < SCAN_ITEMS; ++j) {
            if (first + j < count) blocks[first + j] = run;
            run += v[j];
        }
        carry += total;
    }
    if (rank == 0u) {
        uint room = capacity.x - capacity.x % 3u;
        uint listed = min(carry.x, capacity.y);
        mc.totals.xyz = uvec3(carry.x, carry.y, carry.y > room ? 1u : 0u);
        mc.emit_dispatch = uvec4(dispatch_2d((listed + group.x - 1u) / group.x), listed);
        mc.draw = uvec4(min(carry.y, room), 1u, 0u, 0u);
    }
}
