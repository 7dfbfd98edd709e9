#version 430
// "mc.emit": the triangles of every listed active cell, written at the cell's first vertex.
//   in   active_cells[0, mc.emit_dispatch.w), phi, surface_grid
//   out  vertices[first .. first + 3 x triangles): MeshVertex (position, outward unit normal)
// A vertex on edge (a, b), a the edge's lower corner (mc_tables.h), lies where φ is zero on the
// linear interpolant:  t = φa / (φa - φb),  x = origin + h (node_a + t (node_b - node_a)), with t kept
// RANRYU_MC_EDGE_MARGIN from either node (bindings.h: distinct edges, distinct vertices).
// Every cell that shares the edge computes it from the same numbers in the same order ('precise'
// forbids the compiler to fuse differently), so shared vertices are bit-identical: no cracks.
// The normal is -∇φ/|∇φ| (docs/SURFACE.md (S8)), ∇φ by the smoothed difference gradient() at the two
// nodes interpolated with the same t; where ∇φ vanishes, the triangle's own normal.
// Triangles past the vertex capacity are dropped (mc.totals.z says so); mc.draw counts those kept.
// Dispatch: glDispatchComputeIndirect with mc.emit_dispatch.
#include "../shared/bindings.h"

layout(local_size_x = 64) in;
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) readonly buffer Phi { float phi[]; };
layout(std430) readonly buffer Mesh { MeshState mc; };
layout(std430) readonly buffer ActiveCells { uvec2 active_cells[]; };
layout(std430) writeonly buffer MeshVertices { MeshVertex vertices[]; };
layout(location = RANRYU_LOC_SURFACE_CAPACITY) uniform uvec4 capacity;   // x: vertices

#include "mc_common.glsl"

// φ at a node, the grid continued beyond its border by its border values.
float phi_clamped(ivec3 n) { return phi_at(clamp(n, ivec3(0), ivec3(surface_grid.dims.xyz) - 1)); }

// ∇φ at a node, smoothed (docs/SURFACE.md (S8)): component a is
//     Σ_{j,k} c_j c_k [10 (φ(+1) - φ(-1)) + (φ(+2) - φ(-2))] / (24 h),   c = [1, 2, 1]/4,
// φ(±i) at the node + i e_a + j e_b + k e_c (b, c the other axes): the derivative stencil
// [-1, -10, 0, 10, 1]/24 along a (a central difference of φ smoothed by [1, 10, 1]/12) and [1, 2, 1]/4
// across. Every component's stencil has the second moment h²/2 along every axis, so to second order
// in h this is the gradient of φ convolved with one isotropic kernel of variance h²/2. Mirrored as
// surface::polygonise_cpu's gradient.
const float kAcross[3] = float[3](0.25, 0.5, 0.25);
vec3 gradient(ivec3 n) {
    vec3 g;
    for (int a = 0; a < 3; ++a) {
        ivec3 e = ivec3(0), eb = ivec3(0), ec = ivec3(0);
        e[a] = 1;
        eb[(a + 1) % 3] = 1;
        ec[(a + 2) % 3] = 1;
        float sum = 0.0;
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                ivec3 m = n + j * eb + k * ec;
                float near = phi_clamped(m + e) - phi_clamped(m - e), far = phi_clamped(m + 2 * e) - phi_clamped(m - 2 * e);
                sum += kAcross[j + 1] * kAcross[k + 1] * (10.0 * near + far);
            }
        g[a] = sum / (24.0 * surface_grid.origin.w);
    }
    return g;
}

// The corners' ∇φ (gradient() above), computed once a cell for the corners on an edge the surface
// crosses: every vertex of the cell lies on such an edge, and its normal interpolates its corners'.
// A corner shared by several of the cell's triangles is evaluated once (the stencil reads 108 φ).
void corner_gradients(uvec3 cell, uint index, out vec3 g[8]) {
    uint need = 0u;
    for (int e = 0; e < 12; ++e) {
        int a = mc_edge_corners[2 * e], b = mc_edge_corners[2 * e + 1];
        if (((index >> uint(a)) & 1u) != ((index >> uint(b)) & 1u)) need |= (1u << uint(a)) | (1u << uint(b));
    }
    for (int c = 0; c < 8; ++c) g[c] = (need & (1u << uint(c))) != 0u ? gradient(ivec3(cell) + mc_corner(c)) : vec3(0.0);
}

void edge_vertex(uvec3 cell, int edge, float f[8], vec3 corner_grad[8], out vec3 position, out vec3 grad) {
    int a = mc_edge_corners[2 * edge], b = mc_edge_corners[2 * edge + 1];
    ivec3 na = ivec3(cell) + mc_corner(a), nb = ivec3(cell) + mc_corner(b);
    precise float t = clamp(f[a] / (f[a] - f[b]), float(RANRYU_MC_EDGE_MARGIN), 1.0 - float(RANRYU_MC_EDGE_MARGIN));
    precise vec3 local = vec3(na) + t * vec3(nb - na);
    precise vec3 x = surface_grid.origin.xyz + surface_grid.origin.w * local;
    position = x;
    vec3 ga = corner_grad[a], gb = corner_grad[b];
    grad = ga + t * (gb - ga);
}

void main() {
    uint s = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    if (s >= mc.emit_dispatch.w) return;
    uvec2 cell_first = active_cells[s];
    uvec3 cell = cell_coord(cell_first.x);
    float f[8];
    uint index = cube_case(cell, f);
    vec3 corner_grad[8];
    corner_gradients(cell, index, corner_grad);
    uint room = capacity.x - capacity.x % 3u;
    for (uint t = 0u; t < 5u; ++t) {
        uint base = cell_first.y + 3u * t;
        if (mc_triangles[index * 16u + 3u * t] < 0 || base + 3u > room) break;
        vec3 p[3], g[3];
        for (uint v = 0u; v < 3u; ++v) edge_vertex(cell, mc_triangles[index * 16u + 3u * t + v], f, corner_grad, p[v], g[v]);
        vec3 face = cross(p[1] - p[0], p[2] - p[0]);
        vec3 fallback = dot(face, face) > 0.0 ? normalize(face) : vec3(0.0);
        for (uint v = 0u; v < 3u; ++v) {
            vec3 n = dot(g[v], g[v]) > 0.0 ? -normalize(g[v]) : fallback;
            vertices[base + v] = MeshVertex(vec4(p[v], 1.0), vec4(n, 0.0));
        }
    }
}
