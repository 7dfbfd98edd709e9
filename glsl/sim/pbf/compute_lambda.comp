#version 430
// The constraint's Lagrange multiplier, "pbf.lambda" (docs/PBF.md (P2)-(P4), (P9)), one neighbour walk:
//     rho_i = m W(0) + Σ_j m W_ij + Σ_b psi_b W_ib                                   (P2)
//     C_i = max(rho_i/rho0 − 1, 0)                                                   (P3)
//     S_i = (|Σ_j m ∇W_ij + Σ_b psi_b ∇W_ib|² + Σ_j m² |∇W_ij|²) / rho0²
//     lambda_i = −C_i / (S_i + epsilon)                                              (P4)
//     p_i = −(rho0/dt²) Σ over this step's iterations of lambda_i                    (P9)
// Density[i] = (rho_i, p_i, lambda_i, flags), Lambda[i] = lambda_i.
// With RANRYU_PBF_WALK (the step's first iteration, on the positions the grid was built on) the
// walk tests every candidate and records the flags and neighbour masks (density_walk.glsl), and the
// non-pressure accelerations of (P1) restart as gravity in this cell order. Without it (the later
// iterations) the fluid neighbours are those the walk found (neighbours.glsl), at the moved positions,
// and the boundary particles are those within h around the particle's sorted cell (walk_flags,
// pbf.glsl): from the first pass's boundary masks while it stays within their skin (neighbours.glsl).
// Guard: the frame's largest rho/rho0, in the step's last iteration only (`last`): the densities the
// last correction starts from, not those of the prediction (P1), which a fast flow compresses far more
// before the iterations undo it. The walk also counts the step's iterations into StepState
// (iterations.x summed over the frame, .z the most in one step), as an iterative solver's record.
#include "pbf.glsl"

layout(local_size_x = 128) in;
#include "../fluid/extremes.glsl"
layout(location = RANRYU_LOC_AUX) uniform uint last;   // 1 in the step's last iteration
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) writeonly buffer Lambda { float lambda[]; };
#ifdef RANRYU_PBF_WALK
layout(std430) writeonly buffer Density { vec4 density[]; };
layout(std430) writeonly buffer Accelerations { vec4 accel[]; };
#ifdef RANRYU_BOUNDARY_SKIN
layout(std430) writeonly buffer MaskOrigins { vec4 mask_origin[]; };   // where the boundary masks were recorded (pbf.glsl)
#endif
#define RANRYU_VISITS_FROM_HITS   // its visits are heavy (density_walk.glsl)
#include "../fluid/density_walk.glsl"
#else
layout(std430) buffer Density { vec4 density[]; };
#include "../fluid/neighbours.glsl"
#endif

float sum_w_, squares_;
vec3 grad_;

// j == i (the walk's) adds W(0) and a zero gradient.
void visit_fluid(uint j, vec3 d, float r2) {
    float r = sqrt(r2);
    sum_w_ += sph.mass * kernel_w(r);
    vec3 g = sph.mass * kernel_grad(d, r);
    grad_ += g;
    squares_ += dot(g, g);
}

void visit_boundary(uint b, vec3 d, float r2) {
    float r = sqrt(r2), psi = boundary[b].w;
    sum_w_ += psi * kernel_w(r);
    grad_ += psi * kernel_grad(d, r);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float ratio = 0.0;
    if (live) {
        vec3 xi = position[i].xyz;
        grad_ = vec3(0.0);
        squares_ = 0.0;
#ifdef RANRYU_PBF_WALK
        sum_w_ = 0.0;
        uint count;
        uint flags = walk_neighbours(i, xi, count);
#ifdef RANRYU_BOUNDARY_SKIN
        mask_origin[i] = vec4(xi, 0.0);
#endif
        float p = 0.0;
        accel[i] = vec4(sph.gravity.xyz, 0.0);
        if (i == 0u) {   // one invocation: nothing else writes these this pass
            step.iterations.x += pbf.iterations;
            step.iterations.z = max(step.iterations.z, pbf.iterations);
        }
#else
        vec4 last = density[i];
        uint flags = floatBitsToUint(last.w);
        sum_w_ = sph.mass * kernel_w(0.0);
        for_each_neighbour_around(i, xi, sorted_cell(i), walk_flags(i, flags));
        float p = last.y;
#endif
        float rho = sum_w_;
        ratio = rho / sph.rest_density;
        float c = max(ratio - 1.0, 0.0);
        float s = (dot(grad_, grad_) + squares_) / (sph.rest_density * sph.rest_density);
        float l = c > 0.0 ? -c / (s + pbf.epsilon) : 0.0;   // C = 0 with no neighbours (S = 0) and epsilon = 0: 0, not 0/0
        p -= sph.rest_density * l / (step.dt * step.dt);
        density[i] = vec4(rho, p, l, uintBitsToFloat(flags));
        lambda[i] = l;
    }
    if (last != 0u) {   // dynamically uniform: workgroup_max()'s barriers are met by every invocation
        uvec2 m = workgroup_max(live ? max_bits(ratio) : 0u, i);
        if (gl_LocalInvocationIndex == 0u && m.x != 0u) keep_extreme(RANRYU_EXTREME_DENSITY, m, position[m.y].xyz);
    }
}
