#version 430
// The tank's edges, one colour. Location 1 is the water mode's scene cache (sun share q = 0, R13: the
// edges take no shadow); targets with one colour attachment drop it.
layout(location = 0) out vec4 out_color;
layout(location = 1) out vec4 out_position;

void main() {
    out_color = vec4(0.85, 0.85, 0.88, 1.0);
    out_position = vec4(0.0);
}
