#version 430
// Fills an R32F image with one value (the water mode's clears of the shadow map and the thickness,
// engine/render/renderer.cpp): a compute pass writes at the memory's rate on every SM, where a
// glClear of a render target goes through the raster hardware. Dispatch: one invocation per texel.
#include "shading.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = RANRYU_IMG_TARGET, r32f) writeonly uniform image2D u_target;
layout(location = RANRYU_LOC_FILL_VALUE) uniform vec4 u_value;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_target)))) return;
    imageStore(u_target, p, u_value);
}
