#version 430
// The DFSPH density pass, "dfsph.density" (docs/DFSPH.md "A step"), one neighbour walk for:
//   rho_i (docs/SPH.md (2)), factor_i = 1/D_i (D2), the flags and neighbour masks (density_walk.glsl);
//   the non-pressure accelerations a_i (D7) on the step's start velocities, into Accelerations;
//   with RANRYU_DIVERGENCE_SOLVE, the divergence solve's start: the source s_i of (D5), the warm start
//   kappa_v,i = w·(dt' kappa_v')/dt of the last step's (Warm.y, its impulse), and its pressure
//   accelerations (D3), the first iteration's first half.
// Density[i] = (rho_i, 0, factor_i, flags): the last step's pressure is written again at the step's end.
// Accelerations[i].w = u_i of (D9), for the boundary rows' diagonals.
// Kappa[i] = (x_i, kappa_v,i): the position the step's walks gather with kappa_j (dfsph.glsl), and the warm
// start (0 without RANRYU_DIVERGENCE_SOLVE, whose prediction pass writes the density solve's).
// With RANRYU_BOUNDARY_ROWS, every boundary particle within h of a fluid particle becomes a row of this
// step's solves (docs/DFSPH.md (D9)): listed once in BoundaryList (its mark after the BoundaryRowsState
// takes the step's epoch; the first to mark it appends it), with kFreshRow where it was not a row the
// step before; size_boundary_rows.comp then closes the list.
// With RANRYU_GRADIENT_CORRECTION, the step's kernel-gradient correction L_i of (D11) into
// PressureAccel's tail, from M_i = (1/rho_i)[Σ_j m (x_j − x_i) ⊗ gradW_ij + Σ_b psi_b (x_b − x_i) ⊗ gradW_ib]
// of the same walk; the divergence solve's first pressure accelerations already carry it.
// With RANRYU_ELIMINATED_ROWS, the diagonal of (D13) in place of (D2)'s.
// With RANRYU_WALL_GRADIENT_AT k, the wall's gradient sum Σ_b psi_b gradW_ib into PressureAccel[k N + i]
// (xyz), for the residual pass's boundary term (correct_pressure.comp).
// Guard: the frame's largest rho/rho0 and a particle that has it (extremes.glsl); the time step: the largest |a_i| (D8).
#include "dfsph.glsl"

layout(local_size_x = 128) in;
#include "../fluid/extremes.glsl"
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) writeonly buffer Density { vec4 density[]; };
layout(std430) writeonly buffer Accelerations { vec4 accel[]; };
#ifdef RANRYU_DIVERGENCE_SOLVE
layout(std430) readonly buffer Warm { vec2 warm[]; };
#endif
layout(std430) writeonly buffer Kappa { vec4 kappa4[]; };   // (x_i, kappa_i): dfsph.glsl
#if defined(RANRYU_DIVERGENCE_SOLVE) || defined(RANRYU_GRADIENT_CORRECTION)
layout(std430) buffer PressureAccel { vec4 pressure_accel[]; };
#endif

#ifdef RANRYU_BOUNDARY_ROWS
layout(std430) coherent buffer BoundaryRows { BoundaryRowsState rows; uint boundary_mark[]; };
layout(std430) writeonly buffer BoundaryList { uint boundary_list[]; };
uint epoch_;
#endif

#define RANRYU_VISITS_FROM_HITS   // its visits are heavy (density_walk.glsl)
#include "../fluid/density_walk.glsl"

vec3 xi_, vi_, grad_fluid_, grad_wall_, viscous_, viscous_wall_, pressure_;
float fluid_sum_, wall_sum_, squares_, rate_, kappa_i_, spread_, warm_v_;
vec3 moment_diagonal_, moment_off_;   // (D11): m_k (x_k − x_i) ⊗ gradW_ik summed, (xx, yy, zz), (xy, xz, yz)

// (D11): (x_k − x_i) ⊗ gradW_ik = −d ⊗ g for d = x_i − x_k, g = gradW_ik (symmetric: g ∥ d), weighted w.
void add_moment(float w, vec3 d, vec3 g) {
#ifdef RANRYU_GRADIENT_CORRECTION
    moment_diagonal_ -= w * d * g;
    moment_off_ -= w * vec3(d.x * g.y, d.x * g.z, d.y * g.z);
#endif
}

// (D11): L_i from M_i, the moments over rho_i; I where det M_i <= RANRYU_CORRECTION_NONE (an edge or
// corner of the fluid, a particle alone: its inverse large and meaningless), M_i^-1 from
// RANRYU_CORRECTION_FULL (shared/bindings.h), linear between.
void store_correction(uint i, float rho) {
#ifdef RANRYU_GRADIENT_CORRECTION
    vec3 a = moment_diagonal_ / rho, b = moment_off_ / rho;
    mat3 m = mat3(a.x, b.x, b.y, b.x, a.y, b.z, b.y, b.z, a.z);
    float det = determinant(m);
    const float none = float(RANRYU_CORRECTION_NONE), full = float(RANRYU_CORRECTION_FULL);
    float s = clamp((det - none) / (full - none), 0.0, 1.0);
    mat3 l = s > 0.0 ? s * inverse(m) + (1.0 - s) * mat3(1.0) : mat3(1.0);
    CORRECTION(i, 0u) = vec4(l[0][0], l[1][1], l[2][2], l[0][1]);
    CORRECTION(i, 1u) = vec4(l[0][2], l[1][2], det, s);
#endif
}

void visit_fluid(uint j, vec3 d, float r2) {
    float r = sqrt(r2);
    fluid_sum_ += kernel_w(r);
    vec3 g = kernel_grad(d, r);   // 0 for j = i
    vec3 vj = velocity[j].xyz;
    grad_fluid_ += sph.mass * g;
    squares_ += sph.mass * sph.mass * dot(g, g);
    spread_ += sph.mass * length(g);
    rate_ += sph.mass * dot(vi_ - vj, g);
    viscous_ += (sph.mass / sph.rest_density) * dot(vi_ - vj, d) / (r2 + 0.01 * sph.h * sph.h) * g;
    add_moment(sph.mass, d, g);
#ifdef RANRYU_DIVERGENCE_SOLVE
    pressure_ -= sph.mass * (kappa_i_ + warm_v_ * warm[j].y) * g;
#endif
}

void visit_boundary(uint b, vec3 d, float r2) {
    float r = sqrt(r2), psi = boundary[b].w;
    wall_sum_ += psi * kernel_w(r);
    vec3 g = kernel_grad(d, r);
    grad_wall_ += psi * g;
    rate_ += psi * dot(vi_, g);
    viscous_wall_ += (psi / sph.rest_density) * dot(vi_, d) / (r2 + 0.01 * sph.h * sph.h) * g;
    spread_ += sph.mass * length(g);
    add_moment(psi, d, g);
#ifdef RANRYU_DIVERGENCE_SOLVE
    pressure_ -= kappa_i_ * psi * g;   // (D9): the boundary rows' divergence solve starts from kappa_v,b = 0
#endif
#ifdef RANRYU_BOUNDARY_ROWS
    uint last = atomicExchange(boundary_mark[b], epoch_);
    if (last != epoch_) boundary_list[atomicAdd(rows.count, 1u)] = b | (last + 1u == epoch_ ? 0u : kFreshRow);
#endif
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float ratio = 0.0, magnitude = 0.0;
    if (live) {
        xi_ = position[i].xyz;
        vi_ = velocity[i].xyz;
        grad_fluid_ = grad_wall_ = viscous_ = viscous_wall_ = pressure_ = vec3(0.0);
        fluid_sum_ = wall_sum_ = squares_ = rate_ = spread_ = 0.0;
        moment_diagonal_ = moment_off_ = vec3(0.0);
        kappa_i_ = 0.0;
#ifdef RANRYU_BOUNDARY_ROWS
        epoch_ = rows.epoch;
#endif
#ifdef RANRYU_DIVERGENCE_SOLVE
        warm_v_ = step.dt > 0.0 ? dfsph.warm_start_divergence / step.dt : 0.0;   // (D5): Warm.y is dt' kappa_v'
        kappa_i_ = warm_v_ * warm[i].y;
#endif
        uint count;
        uint flags = walk_neighbours(i, xi_, count);
        if (count < dfsph.deficient_neighbours) flags |= kDeficient;
        float rho = sph.mass * fluid_sum_ + wall_sum_;
        vec3 sum = grad_fluid_ + grad_wall_;
#ifdef RANRYU_ELIMINATED_ROWS
        // (D13): the rows take the fluid's pressure (a particle alone at a wall gives kappa_b = kappa_i), so
        // |A + B|² becomes |A + B|·|A + 2B|, the diagonal both solves read
        float diagonal = length(sum) * length(sum + grad_wall_) + squares_;
#else
        float diagonal = dot(sum, sum) + squares_;   // (D2)
#endif
        density[i] = vec4(rho, 0.0, diagonal > 0.0 ? 1.0 / diagonal : 0.0, uintBitsToFloat(flags));
        store_correction(i, rho);
        vec3 a = sph.gravity.xyz + kViscosityFactor * (sph.viscosity * viscous_ + dfsph.boundary_viscosity * viscous_wall_);
        accel[i] = vec4(a, length(sum) + spread_);   // w: u_i of (D9)
        kappa4[i] = vec4(xi_, kappa_i_);   // the position the step's walks gather with kappa_j (dfsph.glsl)
#ifdef RANRYU_DIVERGENCE_SOLVE
        // (D5): s_i (a deficient particle: rho0, so no correction); a positive w drops the warm start.
        pressure_accel[i] = vec4(CORRECTED(i, pressure_), (flags & kDeficient) != 0u ? sph.rest_density : -step.dt * rate_);
#endif
#ifdef RANRYU_WALL_GRADIENT_AT
        pressure_accel[RANRYU_WALL_GRADIENT_AT * sph.particle_count + i] = vec4(grad_wall_, 0.0);
#endif
        ratio = rho / sph.rest_density;
        magnitude = length(a);
    }
    uvec2 m = workgroup_max(live ? max_bits(ratio) : 0u, i);
    if (gl_LocalInvocationIndex == 0u && m.x != 0u) keep_extreme(RANRYU_EXTREME_DENSITY, m, position[m.y].xyz);
    m = workgroup_max(live ? max_bits(magnitude) : 0u, i);
    if (gl_LocalInvocationIndex == 0u) atomicMax(step.max_accel, m.x);
}
