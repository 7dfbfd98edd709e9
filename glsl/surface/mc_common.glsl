// Marching cubes (Lorensen & Cline 1987) on the φ grid of shared/bindings.h: the tables, and the
// cells, nodes and cases every MC pass uses. The including pass declares, before including this:
//     surface_grid (SurfaceGrid, readonly)   phi[] (float, readonly)
#ifndef RANRYU_SURFACE_MC_COMMON_GLSL
#define RANRYU_SURFACE_MC_COMMON_GLSL

#include "mc_tables.h"

// The triangle table lives in a buffer filled once from the same header: NVIDIA's compiler rejects
// a 4096-element array constructor ("C1068: too much data in type constructor").
layout(std430) readonly buffer McTriangles { int mc_triangles[]; };
const int mc_corner_offsets[24] = int[24](RANRYU_MC_CORNERS);
const int mc_edge_corners[24] = int[24](RANRYU_MC_EDGES);

ivec3 mc_corner(int c) { return ivec3(mc_corner_offsets[3 * c], mc_corner_offsets[3 * c + 1], mc_corner_offsets[3 * c + 2]); }

#include "dispatch_2d.glsl"

// Cells per axis: nodes - 1 (none when there are no nodes).
uvec3 cell_dims() { return uvec3(max(ivec3(surface_grid.dims.xyz) - 1, ivec3(0))); }

uvec3 cell_coord(uint c) {
    uvec3 d = cell_dims();
    return uvec3(c % d.x, (c / d.x) % d.y, c / (d.x * d.y));
}

float phi_at(ivec3 n) {
    uvec3 d = surface_grid.dims.xyz;
    return phi[uint(n.x) + d.x * (uint(n.y) + d.y * uint(n.z))];
}

// φ at the cell's corners and the case index: bit c set when corner c is outside (φ < 0).
uint cube_case(uvec3 cell, out float f[8]) {
    uint index = 0u;
    for (int c = 0; c < 8; ++c) {
        f[c] = phi_at(ivec3(cell) + mc_corner(c));
        if (f[c] < 0.0) index |= 1u << uint(c);
    }
    return index;
}

// Vertices the case emits: 3 per triangle of the table, 0 to 15.
uint case_vertices(uint index) {
    uint n = 0u;
    while (n < 15u && mc_triangles[index * 16u + n] >= 0) n += 3u;
    return n;
}

#endif
