#version 430
// The liquid's thickness along each view ray, every layer (no depth test, no culling; ADD blending
// into R32F): −t on front faces, +t on back faces, t the eye distance clipped to the opaque scene's,
// min(|x − eye|, t_opaque) (R12). Over a closed mesh the sum is the length of the ray inside the
// liquid in front of the opaque scene. docs/RENDERING.md (R5).
// Drawn at 1/THICKNESS_DIVISOR of the frame's size (defined by the renderer): a fragment's centre
// is the centre of a THICKNESS_DIVISOR² block of the frame's pixels, and t_opaque comes from the mean
// of their depths, the opaque plane's depth there (window depth is affine in x_w, y_w over a plane).
#include "water.glsl"

in vec3 v_world;
layout(location = 0) out float out_thickness;

void main() {
    vec2 frag = gl_FragCoord.xy * float(THICKNESS_DIVISOR);   // in the frame's pixels
    ivec2 first = ivec2(gl_FragCoord.xy) * THICKNESS_DIVISOR, last = textureSize(t_scene_depth, 0) - 1;
    float depth = 0.0;
    for (int j = 0; j < THICKNESS_DIVISOR; ++j)
        for (int i = 0; i < THICKNESS_DIVISOR; ++i) depth += texelFetch(t_scene_depth, min(first + ivec2(i, j), last), 0).r;
    float t_opaque = eye_distance(frag, depth / float(THICKNESS_DIVISOR * THICKNESS_DIVISOR));
    float t = min(length(v_world - frame.eye.xyz), t_opaque);
    out_thickness = gl_FrontFacing ? -t : t;
}
