#version 430
// "draw-spray": a white disc of the vertex shader's opacity (spray.vert has the formula).
in vec2 v_corner;
flat in float v_alpha;
layout(location = 0) out vec4 out_color;

void main() {
    if (dot(v_corner, v_corner) > 1.0) discard;
    out_color = vec4(1.0, 1.0, 1.0, v_alpha);
}
