#version 430
// "subparticles.spawn": one invocation per sub-particle (glDispatchComputeIndirect with state.dispatch).
// engine/turbulence/subparticles.h states the model; spawn_subparticle() there is its CPU reference.
// Sub-particle g lies in level list L (offsets from choose_level_cap.comp) with effective level
// E = min(L, C); its parent is p = list_L[k] and it is child c of p's 8^E, where g - offset_L = k·8^E + c.
//     o_c = Σ_{l=1..E} (dx/2^l)·(b_l - ½)      b_l = base-8 digit l of c (l = 1 the lowest), bits x, y, z
//                                               o_c: the centre of the c-th of the 8^E sub-cubes of p's cell
//     e_E = ê_p·2^(-2βE)                        the energy of the octaves below the particle, E levels down
//     ŷ_c = y_c(seed_p, o_c, t; octave lmax + E) / σ      unit rms, carried with the fluid (carried_noise.glsl)
//     v_c = v_p + √(2 e_E)·ŷ_c                  so ½|v_c - v_p|² averages e_E
//     x_c = x_p + o_c + ½(dx/2^E)·ŷ_c           sub-scale eddies move a child about half its own spacing
// Out: position[g] = (x_c, E), velocity[g] = (v_c, e_E); child 0 also marks its parent split:
// level[p] = L | E << RANRYU_SUBPARTICLE_SPLIT_SHIFT (the level set skips it, the draw culls it).
// Example: C = 2, offsets (0, 800, 4000), g = 4130 -> L = 3, E = 2, k = 130 / 64 = 2, c = 2:
// p = list_3[2]; c = 2 = digits (2, 0): b_1 = (0, 1, 0), b_2 = (0, 0, 0);
// o_c = dx/2·(-½, ½, -½) + dx/4·(-½, -½, -½) = dx·(-3/8, 1/8, -3/8).
#include "../../shared/bindings.h"

layout(local_size_x = 128) in;
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams sub; };
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer WaveletEnergy { vec4 energy[]; };
layout(std430) readonly buffer NoiseSeeds { NoiseSeed seed[]; };
layout(std430) readonly buffer Step { StepState step; };
layout(std430) readonly buffer Subparticles { SubparticleState state; };
layout(std430) writeonly buffer SubparticleLevels { uint level[]; };
layout(std430) readonly buffer SubparticleLists { uint list[]; };
layout(std430) writeonly buffer SubparticlePositions { vec4 sub_position[]; };
layout(std430) writeonly buffer SubparticleVelocities { vec4 sub_velocity[]; };

#include "../curl_noise.glsl"
#include "../carried_noise.glsl"
#include "../../surface/dispatch_2d.glsl"

// Keep in step with lattice_offset() in engine/turbulence/subparticles.cpp.
vec3 lattice_offset(uint c, uint E, float dx) {
    vec3 o = vec3(0.0);
    for (uint l = 1u; l <= E; ++l) {
        uint digit = (c >> (3u * (l - 1u))) & 7u;
        vec3 b = vec3(float(digit & 1u), float((digit >> 1u) & 1u), float((digit >> 2u) & 1u));
        o += ldexp(dx, -int(l)) * (b - 0.5);
    }
    return o;
}

void main() {
    uint g = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    if (g >= state.dispatch.w) return;
    uvec3 offsets = state.offsets.xyz;
    uint L = g >= offsets.z ? 3u : g >= offsets.y ? 2u : 1u;
    uint E = min(L, state.limits.x);
    uint local = g - offsets[L - 1u];
    uint k = local >> (3u * E), c = local & ((1u << (3u * E)) - 1u);
    uint p = list[(L - 1u) * sub.particle_count + k];

    float dx = sub.spacing;
    vec3 o = lattice_offset(c, E, dx);
    float e = energy[p].w * sub.energy_scale[E - 1u];
    int octave = sub.noise_lmax + int(E);
    vec3 y = carried_noise(seed[p], o, step.time, sub.coherence_time, octave, octave, sub.beta, int(sub.tile_size)) *
             sub.inv_sigma;
    sub_velocity[g] = vec4(velocity[p].xyz + sqrt(2.0 * e) * y, e);
    sub_position[g] = vec4(position[p].xyz + o + (0.5 * ldexp(dx, -int(E))) * y, float(E));
    if (c == 0u) level[p] = L | (E << RANRYU_SUBPARTICLE_SPLIT_SHIFT);
}
