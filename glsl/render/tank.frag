#version 430
// The tank's edges, one colour. Built with SUN_SHARE (the water mode's scene cache) alpha is the sun
// share q = 0 of (R13): the edges take no shadow.
layout(location = 0) out vec4 out_color;

void main() {
#ifdef SUN_SHARE
    out_color = vec4(0.85, 0.85, 0.88, 0.0);
#else
    out_color = vec4(0.85, 0.85, 0.88, 1.0);
#endif
}
