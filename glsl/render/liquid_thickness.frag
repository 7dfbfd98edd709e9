#version 430
// The liquid's thickness along each view ray, every layer (no depth test, no culling; ADD blending
// into R32F): −t on front faces, +t on back faces, t the eye distance clipped to the opaque scene's,
// min(|x − eye|, t_opaque) (R12). Over a closed mesh the sum is the length of the ray inside the
// liquid in front of the opaque scene. docs/RENDERING.md (R5).
#include "water.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out float out_thickness;

void main() {
    float t_opaque = eye_distance(gl_FragCoord.xy, texelFetch(t_scene_depth, ivec2(gl_FragCoord.xy), 0).r);
    float t = min(length(v_world - frame.eye.xyz), t_opaque);
    out_thickness = gl_FrontFacing ? -t : t;
}
