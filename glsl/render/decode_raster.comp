#version 430
// The compute raster's targets (docs/RENDERING.md (R14)) turned in place into what the GL draws leave
// in the same R32F textures, so that every reader reads one quantity whichever path drew it:
//   u_sum:  Σ round(±v·2^20) (r32i)  ->  its float, Σ/2^20 (m): the thickness (R5) or d_sun (R10)
//   u_near (SUN_VIEW): min ordered_bits(s) (r32ui)  ->  s_near, from_ordered_bits (R8); the fill's
//          ordered_bits(1e30) gives 1e30 where no liquid is, as the draw's cleared map holds.
// Dispatch: one invocation per texel.
#include "shading.h"
#include "../surface/ordered_float.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = RANRYU_IMG_RASTER_SUM, r32i) uniform iimage2D u_sum;
#ifdef SUN_VIEW
layout(binding = RANRYU_IMG_RASTER_NEAR, r32ui) uniform uimage2D u_near;
#endif

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_sum)))) return;
    float sum = float(imageLoad(u_sum, p).r) / RANRYU_RASTER_FIXED_SCALE;
    imageStore(u_sum, p, ivec4(floatBitsToInt(sum)));
#ifdef SUN_VIEW
    imageStore(u_near, p, uvec4(floatBitsToUint(from_ordered_bits(imageLoad(u_near, p).r))));
#endif
}
