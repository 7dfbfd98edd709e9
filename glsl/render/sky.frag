#version 430
// The backdrop of the water mode: the procedural sky with its sun (sky(), common/frame.glsl) in the
// direction of each pixel's view ray, linear, into the opaque scene's target; alpha is the sun share
// q = 0 of (R13): the sky takes no shadow. docs/RENDERING.md (R2).
#include "../common/frame.glsl"

in vec2 v_ndc;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 dir_view = vec3(v_ndc.x / frame.proj[0][0], v_ndc.y / frame.proj[1][1], -1.0);
    vec3 dir = normalize(transpose(mat3(frame.view)) * dir_view);   // the view matrix is rigid
    out_color = vec4(sky(dir), 0.0);
}
