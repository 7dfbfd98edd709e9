#version 430
// The substep's dt (docs/SPH.md eq. (7), docs/DFSPH.md (D8)), one invocation, before the substep's passes:
//     dt = min(cfl dx / (c + v_max), f sqrt(dx / a_max), dt_max, dt_it, frame_left / substeps_left)
// with c = 0 for DFSPH, dt_it the step DFSPH's density solves allow ((D8), set by its residual pass;
// dt_max for the other solvers). cfl = f = 0 (PBF, docs/PBF.md (P1)): the fixed step min(dt_max, frame_left / substeps_left). v_max and a_max are the previous substep's maxima (the integration's and the
// accelerations' workgroup atomics).
// Spreading the frame's remaining time evenly over the substeps left ends the frame on time when
// the stable dt allows; when it does not, the stable dt wins and the remainder carries into the next
// frame (the CPU issues more substeps once it sees that, frames later).
#include "fluid.glsl"

layout(local_size_x = 1) in;

void main() {
    float v_max = uintBitsToFloat(step.max_speed);
    float a_max = uintBitsToFloat(step.max_accel);
    float dx = sph.spacing;
    float speed = sph.sound_speed + v_max;
    float dt = speed > 0.0 && sph.cfl > 0.0 ? min(sph.cfl * dx / speed, sph.dt_max) : sph.dt_max;
    if (a_max > 0.0 && sph.force_factor > 0.0) dt = min(dt, sph.force_factor * sqrt(dx / a_max));
    dt = min(dt, step.iteration_dt);   // DFSPH's (D8): the step its density solves' iterations allow
    if (!(dt >= 0.0)) dt = 0.0;   // NaN maxima: the guard reports them; take no step
    step.stable_dt = dt;
    step.frame_min_dt = min(step.frame_min_dt, dt);   // the stable dt: the guard's and the CPU's measure
    if (step.substeps_left > 0u) dt = min(dt, max(step.frame_left, 0.0) / float(step.substeps_left));
    step.dt = dt;
    step.time += dt;
    step.frame_left -= dt;
    step.substeps_left = step.substeps_left > 0u ? step.substeps_left - 1u : 0u;
    step.frame_substeps += 1u;
    step.steps += 1u;
    step.max_speed = 0u;
    step.max_accel = 0u;
}
