#version 430
// The density solve's end and the step's integration, "dfsph.integrate" (docs/DFSPH.md "A step"):
//     v_i ← v_i + dt a^p_i(kappa),   x_i ← x_i + dt v_i,
// then the last-resort projection of docs/SPH.md (8) and the guard's records (motion.glsl). The new
// positions and velocities go to the fluid's other buffers (NextPositions, NextVelocities: this pass
// reads its neighbours' current positions); the Fluid swaps them after. kappa is kept in Warm.x for
// the next step's warm start. The step's pressure is p_i = (kappa_i + kappa_v,i) rho_i^2; Density.y
// holds the frame's pressure so far (docs/DFSPH.md "The pressure a frame"): the mean of its steps' p_i
// weighted by their dt, sum p dt / sum dt, kept in FramePressure (carried with the particle) and started
// afresh at the frame's first step. After a frame's last step it is the frame's pressure.
#define RANRYU_KAPPA_VEC4 1   // x_j with kappa_j, one load a neighbour (dfsph.glsl)
#include "dfsph.glsl"

layout(local_size_x = 256) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) writeonly buffer NextPositions { vec4 next_position[]; };
layout(std430) writeonly buffer NextVelocities { vec4 next_velocity[]; };
layout(std430) buffer Density { vec4 density[]; };
layout(std430) readonly buffer Kappa { vec4 kappa4[]; };
layout(std430) buffer Warm { vec2 warm[]; };
layout(std430) buffer FramePressure { vec2 frame_pressure[]; };   // (sum p dt, sum dt) over the frame's steps so far
// sum dt is the particle's own, not the frame's elapsed time: a particle the emitter pours in mid-frame
// averages over the steps it ran.
#ifdef RANRYU_GRADIENT_CORRECTION
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };   // (D11)'s L_i, after the accelerations
#endif

#include "../fluid/neighbours.glsl"
#include "../fluid/motion.glsl"

float kappa_i_;
vec3 a_;
void visit_fluid(uint j, vec3 d, float r2) { a_ -= sph.mass * (kappa_i_ + kappa_j_) * kernel_grad(d, sqrt(r2)); }
void visit_boundary(uint b, vec3 d, float r2) { a_ -= (kappa_i_ + KAPPA_B(b, 0u)) * boundary[b].w * kernel_grad(d, sqrt(r2)); }

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    uvec2 bits = uvec2(0u);
    if (live && parked(position[i])) {   // it waits where it is, at rest (fluid.glsl)
        next_position[i] = position[i];
        next_velocity[i] = vec4(0.0);
    } else if (live) {
        vec4 d = density[i];
        vec3 x0 = position[i].xyz;
        kappa_i_ = KAPPA(i);
        a_ = vec3(0.0);
        for_each_neighbour(i, x0, floatBitsToUint(d.w));
        vec3 v = velocity[i].xyz + step.dt * CORRECTED(i, a_);   // (D11)
        vec3 x = x0 + step.dt * v;
        keep_out_of_obstacles(x0, x, v);
        keep_in_tank(x0, x, v);
        next_position[i] = vec4(x, position[i].w);
        next_velocity[i] = vec4(v, velocity[i].w);
        vec2 w = vec2(kappa_i_, warm[i].y);   // (kappa, dt kappa_v): finish_divergence.comp
        warm[i] = w;
        float p = (w.x + (step.dt > 0.0 ? w.y / step.dt : 0.0)) * d.x * d.x;
        vec2 f = (step.frame_substeps <= 1u ? vec2(0.0) : frame_pressure[i]) + vec2(p * step.dt, step.dt);
        frame_pressure[i] = f;
        density[i].y = f.y > 0.0 ? f.x / f.y : p;
        bits = record_particle(i, x, v);
    }
    record_maxima(bits, i);
}
