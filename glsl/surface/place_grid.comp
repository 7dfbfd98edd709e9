#version 430
// "surface.bounds", step 2 of 2 (one invocation): places the φ grid around the box of find_bounds.
//   in   surface_grid.bounds_min/max, surface (SurfaceParams), group = the level-set pass's local size
//   out  surface_grid.origin, .dims, .dispatch (glDispatchComputeIndirect arguments of the level set)
//
// W vanishes at distance >= R, so φ = -iso < 0 outside [lo, hi] = [min - R, max + R]: nodes on or
// beyond that box are outside, and a grid whose first and last nodes lie there closes the surface.
// With sub-particles the box grows by surface.bounds_margin, their reach beyond R (level_set.h).
//     h      = max(node_spacing, max over axes of (hi - lo) / (max_dims - 3))   (coarser only to fit)
//     origin = h * floor(lo / h)          on the lattice of multiples of h: the grid does not shift
//                                          by fractions of a node as the box moves, so neither do
//                                          the surface's facets (no shimmer from frame to frame)
//     dims   = min(ceil((hi - origin) / h) + 1, max_dims)
// Since lo - h < origin <= lo, dims <= (hi - lo) / h + 3 <= max_dims: the clamp only catches rounding.
// With a node budget N = surface.max_nodes > 0 (docs/SURFACE.md (S9)), h grows further to the
// smallest spacing (found by bisection to 2^-20 of h) whose grid has at most N nodes: the cost of the
// level set and marching cubes is bounded whatever the particles' spread. engine/surface/level_set.cpp
// place_grid() is the CPU reference (the same float steps).
// With no particles, or a non-finite bound (an exploded run; the SPH guard reports it), dims = 0 and
// every later pass does nothing.
#include "../shared/bindings.h"

layout(local_size_x = 1) in;
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(location = RANRYU_LOC_SURFACE_GROUP) uniform uvec4 group;   // xyz: compute_level_set's local size

#include "ordered_float.glsl"

// Nodes of the grid of spacing h around [lo, hi] (the rule above), as a float (no overflow).
float grid_nodes(vec3 lo, vec3 hi, float h) {
    vec3 n = min(ceil((hi - h * floor(lo / h)) / h) + 1.0, vec3(surface.max_dims.xyz));
    return n.x * n.y * n.z;
}

void main() {
    float reach = surface.kernel_radius + surface.bounds_margin;   // bounds_margin: 0 without sub-particles
    vec3 lo = from_ordered_bits(surface_grid.bounds_min.xyz) - reach;
    vec3 hi = from_ordered_bits(surface_grid.bounds_max.xyz) + reach;
    bool finite = !any(isnan(lo)) && !any(isinf(lo)) && !any(isnan(hi)) && !any(isinf(hi));
    if (surface.particle_count == 0u || !finite || any(greaterThan(lo, hi))) {
        surface_grid.origin = vec4(0.0, 0.0, 0.0, surface.node_spacing);
        surface_grid.dims = uvec4(0u);
        surface_grid.dispatch = uvec4(0u, 1u, 1u, 0u);
        return;
    }
    vec3 fit = (hi - lo) / (vec3(surface.max_dims.xyz) - 3.0);
    float h = max(surface.node_spacing, max(fit.x, max(fit.y, fit.z)));
    float budget = float(surface.max_nodes);
    if (surface.max_nodes > 0u && grid_nodes(lo, hi, h) > budget) {   // (S9)
        float small = h, big = 2.0 * h;
        for (int k = 0; k < 40 && grid_nodes(lo, hi, big) > budget; ++k) big *= 2.0;
        for (int k = 0; k < 20; ++k) {
            float mid = 0.5 * (small + big);
            if (grid_nodes(lo, hi, mid) > budget) small = mid;
            else big = mid;
        }
        h = big;
    }
    vec3 origin = h * floor(lo / h);
    uvec3 n = min(uvec3(ceil((hi - origin) / h)) + 1u, surface.max_dims.xyz);
    surface_grid.origin = vec4(origin, h);
    surface_grid.dims = uvec4(n, n.x * n.y * n.z);
    surface_grid.dispatch = uvec4((n + group.xyz - 1u) / group.xyz, h > surface.node_spacing ? 1u : 0u);
}
