#version 430
// "mc.compact", step 2 of 2: the list of active cells, in cell order, each with its first vertex.
//   in   cell_vertices (mc_classify), blocks = exclusive sums over earlier blocks (mc_scan_blocks)
//   out  active_cells[slot] = (cell, first vertex) for every cell that emits vertices, slot < capacity.y
// Each workgroup scans its block's (active, vertices) pairs again in shared memory and adds the
// block's offset: slot = active cells before this one, first vertex = vertices before this one.
//
// Worked example, blocks of 4 cells (the real block is the local size):
//     cell               0  1  2  3 |  4  5  6  7
//     cell_vertices      0  3  0  6 |  3  0  0  9
//     blocks (classify)  (2, 9)     |  (2, 12)
//     blocks (scanned)   (0, 0)     |  (2, 9)          totals: 4 active, 21 vertices
//     in-block scan      (0,0) (0,0) (1,3) (1,3) | (0,0) (1,3) (1,3) (1,3)
//     slot, vertex       -  (0,0) -  (1,3)       | (2,9) -  -  (3,12)
//     active             [(1,0), (3,3), (4,9), (7,12)]; mc.draw.x = 21
// Order-preserving: the mesh comes out in cell order, the same order a serial CPU loop makes.
// Dispatch: glDispatchComputeIndirect with mc.cell_dispatch; same local size as mc_classify.
#include "../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std430) readonly buffer Mesh { MeshState mc; };
layout(std430) readonly buffer CellVertices { uint cell_vertices[]; };
layout(std430) readonly buffer McBlocks { uvec2 blocks[]; };
layout(std430) writeonly buffer ActiveCells { uvec2 active_cells[]; };
layout(location = RANRYU_LOC_SURFACE_CAPACITY) uniform uvec4 capacity;   // y: active cells

#include "workgroup_scan.glsl"
#include "dispatch_2d.glsl"

void main() {
    uint c = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    uint n = c < mc.cell_dispatch.w ? cell_vertices[c] : 0u;
    uvec2 total;
    uvec2 before = workgroup_exclusive_scan(uvec2(n > 0u ? 1u : 0u, n), total) + blocks[flat_group()];
    if (n > 0u && before.x < capacity.y) active_cells[before.x] = uvec2(c, before.y);
}
