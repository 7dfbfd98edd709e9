#version 430
// Copies the opaque scene (linear) into the frame's target, display-encoded, with its depth, so that
// the liquid's surface pass depth-tests against it. docs/RENDERING.md (R7).
#include "water.glsl"

layout(location = 0) out vec4 out_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    out_color = vec4(to_display(texelFetch(t_scene_color, p, 0).rgb), 1.0);
    gl_FragDepth = texelFetch(t_scene_depth, p, 0).r;
}
