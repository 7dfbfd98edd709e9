#version 430
// "surface.anisotropy" (docs/SURFACE.md (S1)-(S5); Yu & Turk 2013): per particle i, in cell order,
// the smoothed centre and the principal axes and stretches of its level-set kernel.
//   in   sorted_position[0, surface.particle_count), the neighbour grid's cell ranges (as the level
//        set's gather: particles may have moved by up to search_margin since the sort)
//   out  centres[i] = (x̄_i, s_3), axes[2i] = (a_1, s_1), axes[2i+1] = (a_2, s_2); a_3 = a_1 × a_2
// One neighbour loop gives the three sums both (S2) and (S3) need, relative to x_i (no cancellation
// of large coordinates):
//     w_ij = 1 - (|d|/r)³ for |d| < r, d = x_j - x_i                          (S1)
//     m = Σ w_ij d / Σ w_ij,   x̄_i = x_i + λ m                                   (S2)
//     C_i = Σ w_ij d dᵀ / Σ w_ij - m mᵀ                                          (S3)
// then C_i = A diag(σ_1 ≥ σ_2 ≥ σ_3) Aᵀ by cyclic Jacobi rotations (S4), and the stretches (S5):
//     s_k = min(k_s · max(σ_k, σ_1/k_r), s_max)   if N_i >= N_ε,   s_k = k_n otherwise.
// engine/surface/anisotropy.h is the double-precision CPU reference (tests/gl/surface_test.cpp).
// Dispatch: one invocation per particle along x.
#include "../shared/bindings.h"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) readonly buffer Positions { vec4 sorted_position[]; };
layout(std430) readonly buffer CellRange { uvec2 cell_range[]; };
layout(std430) readonly buffer SortedKeys { uint sorted_keys[]; };
layout(std430) writeonly buffer SurfaceCentres { vec4 centres[]; };
layout(std430) writeonly buffer SurfaceAxes { vec4 axes[]; };

#include "../sim/grid.glsl"
#include "cell_run.glsl"

// Cyclic Jacobi (S4): a becomes diagonal, v's columns the eigenvectors. a[col][row]. Each sweep
// rotates away the three off-diagonal entries in turn; convergence is quadratic, and 6 sweeps take a
// float 3×3 to round-off (the CPU reference runs double to 1e-16).
void jacobi(inout mat3 a, out mat3 v) {
    v = mat3(1.0);
    for (int sweep = 0; sweep < 6; ++sweep)
        for (int pair = 0; pair < 3; ++pair) {
            int p = pair == 2 ? 1 : 0, q = pair == 0 ? 1 : 2;
            float apq = a[q][p];
            if (apq == 0.0) continue;
            float theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            float t = (theta >= 0.0 ? 1.0 : -1.0) / (abs(theta) + sqrt(theta * theta + 1.0));
            float c = inversesqrt(t * t + 1.0), s = t * c;
            mat3 j = mat3(1.0);
            j[p][p] = c;
            j[q][q] = c;
            j[q][p] = s;
            j[p][q] = -s;
            a = transpose(j) * a * j;
            v = v * j;
        }
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= surface.particle_count) return;
    vec3 xi = sorted_position[i].xyz;
    float r = surface.anisotropy.x, reach = r + surface.search_margin;
    ivec3 lo = grid_cell(xi - reach), hi = grid_cell(xi + reach);
    float sw = 0.0;
    vec3 swd = vec3(0.0);
    vec3 sdiag = vec3(0.0), soff = vec3(0.0);   // Σ w d_a², Σ w (d_x d_y, d_x d_z, d_y d_z)
    uint n = 0u;
    for (int cz = lo.z; cz <= hi.z; ++cz)
        for (int cy = lo.y; cy <= hi.y; ++cy)
            for (int cx = lo.x; cx <= hi.x; ++cx) {
                uvec2 run = cell_run(cell_key(ivec3(cx, cy, cz)));
                for (uint j = run.x; j < run.y; ++j) {
                    vec3 d = sorted_position[j].xyz - xi;
                    float q = length(d);
                    if (q >= r) continue;
                    float t = q / r, w = 1.0 - t * t * t;   // (S1)
                    ++n;
                    sw += w;
                    swd += w * d;
                    sdiag += w * d * d;
                    soff += w * vec3(d.x * d.y, d.x * d.z, d.y * d.z);
                }
            }
    vec3 m = swd / sw;   // sw >= 1: the particle itself
    vec3 centre = xi + surface.anisotropy.y * m;   // (S2)
    vec4 limits = surface.anisotropy_limits;
    if (float(n) < limits.y) {   // isolated (S5)
        centres[i] = vec4(centre, limits.x);
        axes[2u * i] = vec4(1.0, 0.0, 0.0, limits.x);
        axes[2u * i + 1u] = vec4(0.0, 1.0, 0.0, limits.x);
        return;
    }
    vec3 dg = sdiag / sw - m * m, of = soff / sw - vec3(m.x * m.y, m.x * m.z, m.y * m.z);   // (S3)
    mat3 c = mat3(dg.x, of.x, of.y, of.x, dg.y, of.z, of.y, of.z, dg.z);
    mat3 v;
    jacobi(c, v);
    // Sort the three (σ, axis) pairs by decreasing σ.
    vec3 sigma = vec3(c[0][0], c[1][1], c[2][2]);
    ivec3 k = ivec3(0, 1, 2);
    if (sigma[k.y] > sigma[k.x]) k.xy = k.yx;
    if (sigma[k.z] > sigma[k.y]) k.yz = k.zy;
    if (sigma[k.y] > sigma[k.x]) k.xy = k.yx;
    float top = sigma[k.x], ks = surface.anisotropy.z, kr = surface.anisotropy.w, smax = limits.z;
    vec3 s = vec3(min(ks * top, smax), min(ks * max(sigma[k.y], top / kr), smax), min(ks * max(sigma[k.z], top / kr), smax));   // (S5)
    centres[i] = vec4(centre, s.z);
    axes[2u * i] = vec4(v[k.x], s.x);
    axes[2u * i + 1u] = vec4(v[k.y], s.y);
}
