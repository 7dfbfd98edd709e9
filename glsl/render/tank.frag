#version 430
layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(0.85, 0.85, 0.88, 1.0); }
