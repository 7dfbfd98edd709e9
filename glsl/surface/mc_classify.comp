#version 430
// "mc.classify", step 2 of 2: the case of every cell and the vertices it will emit, and per
// workgroup (a block of local_size_x consecutive cells) the sums compaction starts from.
//   in   phi, surface_grid; mc.cell_dispatch.w = cells
//   out  cell_vertices[c] = 3 x triangles of cell c's case (0..15)
//        blocks[b] = (active cells, vertices) of block b (a cell is active when it emits any)
// Dispatch: glDispatchComputeIndirect with mc.cell_dispatch. mc_compact uses the same blocks, so it
// has the same local size (engine/surface/marching_cubes.cpp checks).
#include "../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) readonly buffer Phi { float phi[]; };
layout(std430) readonly buffer Mesh { MeshState mc; };
layout(std430) writeonly buffer CellVertices { uint cell_vertices[]; };
layout(std430) writeonly buffer McBlocks { uvec2 blocks[]; };

#include "mc_common.glsl"
#include "workgroup_scan.glsl"

void main() {
    uint c = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    uint n = 0u;
    if (c < mc.cell_dispatch.w) {
        float f[8];
        n = case_vertices(cube_case(cell_coord(c), f));
        cell_vertices[c] = n;
    }
    uvec2 total;
    workgroup_exclusive_scan(uvec2(n > 0u ? 1u : 0u, n), total);   // only the total is wanted here
    if (gl_LocalInvocationIndex == 0u) blocks[flat_group()] = total;
}
