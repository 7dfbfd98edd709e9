#version 430
// One triangle covering the screen (3 vertices from gl_VertexID); passes the NDC position on.
out vec2 v_ndc;

void main() {
    v_ndc = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID >> 1) * 4 - 1));
    gl_Position = vec4(v_ndc, 0.0, 1.0);
}
