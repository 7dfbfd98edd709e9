#version 430
// The turbulence force (docs/METHOD.md §5; engine/turbulence/force.h states the choices):
//     f_i = A (P_i/dt) ê_i y_c,i,   P_i = m_i·dt   =>   a_i += A ê_i y_c,i
// A (1/m) the amplitude, ê_i (m²/s²) the wavelet energy of the current cell order
// (analyse_velocity.comp), y_c,i the curl-noise octave sum carried with particle i
// (carried_noise.glsl, dimensionless). The pass first re-seeds the particle's noise phases whose
// epoch began since the last substep (s_p = x_i at the substep's time, and the phase's octave sum
// y(q_p), which is fixed for the epoch: the noise is evaluated once a phase and coherence time, not
// every substep), so the seeds follow the fluid's cell order (the reorder moves them) and the
// sub-particles read them after the frame.
// Runs after the forces pass, before integrate. Folds the new |a_i| into step.max_accel with one
// atomic per workgroup (the next substep's dt, eq. (7), reads it).
#include "../sim/fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_NOISE) uniform NoiseBlock { NoiseParams noise; };
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Accelerations { vec4 accel[]; };
layout(std430) readonly buffer WaveletEnergy { vec4 energy[]; };
layout(std430) buffer NoiseSeeds { NoiseSeed seed[]; };
layout(location = RANRYU_LOC_TURBULENCE_AMPLITUDE) uniform float amplitude;
layout(location = RANRYU_LOC_COHERENCE_TIME) uniform float coherence_time;

#include "curl_noise.glsl"
#include "carried_noise.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float magnitude = 0.0;
    if (live) {
        vec3 a = accel[i].xyz;
        float t = step.time;
        NoiseSeed s = seed[i];
        int n = int(noise.tile_size);
        NoiseSeed r = reseed_noise(s, position[i].xyz, t, coherence_time, noise.lmin, noise.lmax, noise.beta, n);
        if (r.phase[0] != s.phase[0] || r.phase[1] != s.phase[1]) seed[i] = r;
        float e = energy[i].w;
        // dt = 0: NaN maxima, no step is taken; e = 0: no turbulence here. Either way, no force.
        if (e > 0.0 && step.dt > 0.0) {
            vec3 y = carried_value(r, t, coherence_time);   // the octave sums were evaluated at re-seeding
            a += (amplitude * e) * y;
            accel[i].xyz = a;   // w is the solver's (docs/DFSPH.md (D9))
        }
        magnitude = length(a);
    }
    uvec2 m = workgroup_max(live ? max_bits(magnitude) : 0u, i);
    if (gl_LocalInvocationIndex == 0u) atomicMax(step.max_accel, m.x);
}
