#version 430
// "compose" (docs/RENDERING.md (R13)): the cached opaque scene with this frame's shadow of the liquid,
// per pixel p of the frame:
//     c = C_lit·(1 − q·(1 − S(x)))    C_lit and q from the scene cache, x the world point its depth
//                                     holds (R12); S of (R10), evaluated only where q > 0
// into the opaque scene (linear, RGBA16F: what the surface refracts, (R5)) and, display-encoded,
// into the frame (RGBA8, (R7)). The renderer copies the cache's depth into the frame's after.
// Dispatch: one invocation per pixel.
#include "water.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = RANRYU_TEX_SCENE_LIT) uniform sampler2D t_scene_lit;
layout(binding = RANRYU_IMG_SCENE, rgba16f) writeonly uniform image2D u_scene;
layout(binding = RANRYU_IMG_FRAME, rgba8) writeonly uniform image2D u_frame;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(u_frame)))) return;
    vec4 lit = texelFetch(t_scene_lit, p, 0);
    vec3 c = lit.rgb;
    if (lit.a > 0.0) {
        vec3 x = world_position(vec2(p) + 0.5, texelFetch(t_scene_depth, p, 0).r);
        c *= 1.0 - lit.a * (1.0 - sun_transmittance(x));
    }
    imageStore(u_scene, p, vec4(c, 1.0));
    imageStore(u_frame, p, vec4(to_display(c), 1.0));
}
