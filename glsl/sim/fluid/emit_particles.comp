#version 430
// "emit" (engine/sim/fluid.h Fluid::emit): the emitter pours one sheet of particles. Each parked
// particle (fluid.glsl) claims a slot k with an atomic counter (Emitter, cleared by the caller); the
// first side² of them take slot k of the nozzle's side x side lattice, spacing dx, in its x-z plane,
//     x = nozzle + dx ((k mod side) - (side - 1)/2, 0, (k div side) - (side - 1)/2),   v = v_emit,
// and are no longer parked (w = 0); StepState.live_count counts them. The rest stay parked: a sheet has
// at most side² particles, and once every parked particle is poured the budget is spent. Which
// parked particle takes which slot depends on the order the invocations run in; the sheet does not.
#include "fluid.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) buffer Velocities { vec4 velocity[]; };
layout(std430) buffer Emitter { uint claimed; };
layout(location = RANRYU_LOC_EMIT_NOZZLE) uniform vec4 nozzle;       // xyz (m), w: side
layout(location = RANRYU_LOC_EMIT_VELOCITY) uniform vec4 emit_velocity;   // xyz (m/s), w: dx (m)

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count || !parked(position[i])) return;   // no barriers in this pass
    uint side = uint(nozzle.w);
    uint k = atomicAdd(claimed, 1u);
    if (k >= side * side) return;
    vec2 at = (vec2(float(k % side), float(k / side)) - 0.5 * float(side - 1u)) * emit_velocity.w;
    position[i] = vec4(nozzle.xyz + vec3(at.x, 0.0, at.y), 0.0);
    velocity[i] = vec4(emit_velocity.xyz, 0.0);
    atomicAdd(step.live_count, 1u);
}
