#version 430
// "level-set.splat" (docs/SURFACE.md (S6)-(S8)): each particle adds its anisotropic kernel to the
// nodes of the φ grid it covers,
//     V · det(G_i) · W(|G_i (x - x̄_i)|, R),    G_i = Σ_k a_k a_kᵀ / s'_k,  s'_k = max(s_k, 2h/R)   (S6, S7)
// as a fixed-point integer (RANRYU_SUBPARTICLE_SPLAT_SCALE units, rounded to nearest) with atomicAdd:
// integer sums commute, so φ is the same every run. compute_level_set.comp (built with
// RANRYU_SPLATTED) turns the sum into φ and resets it.
//   - W is the cubic spline of glsl/sim/kernel.glsl with support R; G is dimensionless (1 in the
//     bulk, where this is the isotropic kernel), det(G) = 1/(s'_1 s'_2 s'_3) keeps each kernel's volume.
//   - s'_k >= 2h/R: no kernel is narrower than 2 node spacings along any axis, the floor below which
//     the grid samples a kernel too coarsely to keep its volume as it moves (engine/surface/level_set.h
//     has the numbers; RANRYU_SUBPARTICLE_KERNEL_FLOOR). On a coarse grid (a node budget) the floor
//     widens the kernels with the grid instead of leaving gaps between the nodes (S8).
//   - The node box: the ellipsoid |G d| < R reaches R·sqrt(Σ_k s'_k² a_k,c²) along world axis c.
//   - The grid's outermost nodes are never written: φ = -iso there, so the surface always closes,
//     even where a kernel widened by the floor reaches past the grid's margin.
// Built with RANRYU_SUBPARTICLES, particles split into sub-particles are skipped (their children
// splat instead, splat_subparticles.comp).
// Dispatch: one invocation per particle along x (cell order, as centres[] and axes_of[] are).
#include "../shared/bindings.h"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) readonly buffer SurfaceCentres { vec4 centres[]; };
layout(std430) readonly buffer SurfaceAxes { vec4 axes_of[]; };
layout(std430) buffer SplatGrid { uint splat[]; };
#ifdef RANRYU_SUBPARTICLES
layout(std430) readonly buffer SubparticleLevels { uint sub_level[]; };
#endif

#include "../sim/kernel.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    uvec3 dims = surface_grid.dims.xyz;
    if (i >= surface.particle_count || any(lessThan(dims, uvec3(3u)))) return;
#ifdef RANRYU_SUBPARTICLES
    if ((sub_level[i] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) != 0u) return;
#endif
    vec4 c = centres[i], p = axes_of[2u * i], q = axes_of[2u * i + 1u];
    vec3 origin = surface_grid.origin.xyz;
    float h = surface_grid.origin.w, R = surface.kernel_radius;
    float floor_s = float(RANRYU_SUBPARTICLE_KERNEL_FLOOR) * h / R;
    vec3 s = max(vec3(p.w, q.w, c.w), vec3(floor_s));
    mat3 axes = mat3(p.xyz, q.xyz, cross(p.xyz, q.xyz));
    mat3 g = axes * mat3(1.0 / s.x, 0.0, 0.0, 0.0, 1.0 / s.y, 0.0, 0.0, 0.0, 1.0 / s.z) * transpose(axes);   // (S6)
    float weight = surface.volume / (s.x * s.y * s.z) * float(RANRYU_SUBPARTICLE_SPLAT_SCALE);   // V det(G), fixed point
    vec3 extent = R * sqrt((axes[0] * axes[0]) * (s.x * s.x) + (axes[1] * axes[1]) * (s.y * s.y) + (axes[2] * axes[2]) * (s.z * s.z));
    ivec3 lo = max(ivec3(ceil((c.xyz - extent - origin) / h)), ivec3(1));
    ivec3 hi = min(ivec3(floor((c.xyz + extent - origin) / h)), ivec3(dims) - 2);
    for (int k = lo.z; k <= hi.z; ++k)
        for (int j = lo.y; j <= hi.y; ++j)
            for (int n = lo.x; n <= hi.x; ++n) {
                vec3 x = origin + h * vec3(uvec3(n, j, k));   // as the gather computes its node
                float r = length(g * (x - c.xyz));
                if (r < R) atomicAdd(splat[uint(n) + dims.x * (uint(j) + dims.y * uint(k))], uint(weight * kernel_w(r, R) + 0.5));   // (S7)
            }
}
