#version 430
// Density and pressure of every fluid particle (docs/SPH.md eqs. (2), (3)):
//     rho_i = sum_j m W(x_i - x_j) + sum_b psi_b W(x_i - x_b),   p_i = max(0, B((rho_i/rho0)^7 - 1)).
// Input: sorted positions and keys, cell ranges of this substep.
// Output: density[i] = (rho_i, p_i, p_i / rho_i^2, 0); forces reads the third to save a division a pair.
// Guard: the frame's largest rho/rho0 and a particle that has it.
#include "sph_common.glsl"

layout(local_size_x = 128) in;
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_DENSITY) writeonly buffer Density { vec4 density[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float ratio = 0.0;
    if (live) {
        vec3 xi = position[i].xyz;
        ivec3 c = grid_cell(xi);
        float h = sph.h, h2 = h * h;
        float fluid = 0.0, wall = 0.0;
        FOR_EACH_RUN {
            uvec2 run = NEIGHBOUR_RUN(c, true);
            for (uint j = run.x; j < run.y; ++j) {   // |d|^2 first: most candidates lie outside h
                vec3 d = xi - position[j].xyz;
                float r2 = dot(d, d);
                if (r2 < h2) fluid += kernel_w(sqrt(r2), h);
            }
            run = NEIGHBOUR_RUN(c, false);
            for (uint b = run.x; b < run.y; ++b) {
                vec3 d = xi - boundary[b].xyz;
                float r2 = dot(d, d);
                if (r2 < h2) wall += boundary[b].w * kernel_w(sqrt(r2), h);
            }
        }
        float rho = sph.mass * fluid + wall;
        ratio = rho / sph.rest_density;
        float p = max(0.0, sph.stiffness * (pow(ratio, 7.0) - 1.0));
        density[i] = vec4(rho, p, p / (rho * rho), 0.0);
    }
    uvec2 m = workgroup_max(live ? max_bits(ratio) : 0u, i);
    if (gl_LocalInvocationIndex == 0u && m.x > atomicMax(step.frame_max_density, m.x)) step.density_index = m.y;
}
