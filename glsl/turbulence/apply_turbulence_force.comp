#version 430
// The turbulence force (METHOD.md §5; engine/turbulence/force.h states the choices):
//     f_i = A (P_i/dt) ê_i y(x_i),  P_i = m_i  =>  a_i += A ê_i y(x_i) / dt
// A (s) the amplitude, ê_i (m/s²) the wavelet energy of the current cell order (analyse_velocity.comp),
// y(x_i) the curl-noise octave sum (curl_noise.glsl, dimensionless), dt the substep's dt (StepState,
// chosen on the GPU this substep): the substep's velocity kick is A ê_i y(x_i) (m/s).
// Runs after the forces pass, before integrate. Folds the new |a_i| into step.max_accel with one
// atomic per workgroup (the next substep's dt, eq. (7), reads it).
#include "../sim/sph/sph_common.glsl"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_NOISE) uniform NoiseBlock { NoiseParams noise; };
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_ACCEL) buffer Accel { vec4 accel[]; };
layout(std430, binding = RANRYU_SSBO_WAVELET_ENERGY) readonly buffer Energy { vec4 energy[]; };
layout(location = RANRYU_LOC_TURBULENCE_AMPLITUDE) uniform float amplitude;

#include "curl_noise.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float magnitude = 0.0;
    float dt = step.dt;
    if (live) {
        vec3 a = accel[i].xyz;
        float e = energy[i].w;
        // dt = 0 (NaN maxima: no step is taken) or e = 0 (no turbulence here): no force, and no 0/0.
        if (e > 0.0 && dt > 0.0) {
            vec3 y = curl_noise_octaves(position[i].xyz, noise.lmin, noise.lmax, noise.beta, int(noise.tile_size));
            a += (amplitude * e / dt) * y;
            accel[i] = vec4(a, 0.0);
        }
        magnitude = length(a);
    }
    uvec2 m = workgroup_max(live ? max_bits(magnitude) : 0u, i);
    if (gl_LocalInvocationIndex == 0u) atomicMax(step.max_accel, m.x);
}
