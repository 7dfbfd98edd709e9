#version 430
// Samples the turbulence field y (docs/METHOD.md §4, glsl/turbulence/curl_noise.glsl) on a regular grid:
// point (i, j, k) at origin + spacing·(i, j, k) goes to field[((i·ny + j)·nz + k)·3 + c], the C order
// of an array of shape (nx, ny, nz, 3). Pass "noise.sample" (engine/turbulence/noise.cpp).
#include "../shared/bindings.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std140, binding = RANRYU_UBO_NOISE) uniform NoiseBlock { NoiseParams noise; };
layout(std430) writeonly buffer NoiseField { float field[]; };

#include "curl_noise.glsl"

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (any(greaterThanEqual(id, noise.dims.xyz))) return;
    vec3 x = noise.origin.xyz + noise.origin.w * vec3(id);
    vec3 y = curl_noise_octaves(x, noise.lmin, noise.lmax, noise.beta, int(noise.tile_size));
    uint base = ((id.x * noise.dims.y + id.y) * noise.dims.z + id.z) * 3u;
    field[base] = y.x;
    field[base + 1u] = y.y;
    field[base + 2u] = y.z;
}
