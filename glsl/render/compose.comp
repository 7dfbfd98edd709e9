#version 430
// "compose" (docs/RENDERING.md (R13)): the cached opaque scene with this frame's shadow of the liquid,
// per pixel p of the frame:
//     c = C_lit·(1 − q·(1 − S(x)))     C_lit, and x, q, from the scene cache; S of (R10), only where q > 0
// into the opaque scene (linear, RGBA16F: what the surface refracts, (R5)) and, display-encoded,
// into the frame (RGBA8, (R7)). The renderer copies the cache's depth into the frame's depth after.
// Dispatch: one invocation per pixel.
#include "water.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = RANRYU_TEX_SCENE_LIT) uniform sampler2D t_scene_lit;
layout(binding = RANRYU_TEX_SCENE_POSITION) uniform sampler2D t_scene_position;
layout(binding = RANRYU_IMG_SCENE, rgba16f) writeonly uniform image2D u_scene;
layout(binding = RANRYU_IMG_FRAME, rgba8) writeonly uniform image2D u_frame;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_frame)))) return;
    vec3 c = texelFetch(t_scene_lit, p, 0).rgb;
    vec4 xq = texelFetch(t_scene_position, p, 0);
    if (xq.w > 0.0) c *= 1.0 - xq.w * (1.0 - sun_transmittance(xq.xyz));
    imageStore(u_scene, p, vec4(c, 1.0));
    imageStore(u_frame, p, vec4(to_display(c), 1.0));
}
