#version 430
// "draw-spray": the sub-particles (turbulence/subparticles.h) as white spray, one camera-facing disc
// per sub-particle (instanced 4-vertex strip, glDrawArraysIndirect with the sub-particle count the
// GPU wrote). A level-E sub-particle (position.w = E) with energy e = e_E (velocity.w) is a disc of
// radius r/2^E (r the particles' drawn radius) in the plane through its centre facing the camera,
// of opacity
//     α = RANRYU_SPRAY_ALPHA · clamp(e / e_min − 1, 0, 1)
// e_min = e_th·2^(−2β), the least energy a sub-particle is spawned with (docs/SUBPARTICLES.md "Levels":
// a parent at its level's threshold): a sprite fades in as its eddy's energy rises past twice that
// and out as it decays, so sub-particles appear and merge back without popping. Blended over the
// frame (src alpha, one minus src alpha), depth-tested against the surface, not depth-written.
// tests/gl/spray_test.cpp compares its pixels with this formula.
#include "../common/frame.glsl"
#include "spray.h"

layout(location = RANRYU_ATTR_POSITION) in vec4 in_position;   // xyz (m), w: level E
layout(location = RANRYU_ATTR_VELOCITY) in vec4 in_velocity;   // xyz (m/s), w: e_E (m²/s²)
layout(location = RANRYU_LOC_SPRAY) uniform vec4 spray;

out vec2 v_corner;        // the disc's own coordinates: |v_corner| <= 1 inside
flat out float v_alpha;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    int level = clamp(int(in_position.w), 1, RANRYU_SUBPARTICLE_MAX_LEVEL);
    float r = ldexp(frame.material.w, -level);
    float alpha = RANRYU_SPRAY_ALPHA * clamp(in_velocity.w / spray.x - 1.0, 0.0, 1.0);
    vec3 c = (frame.view * vec4(in_position.xyz, 1.0)).xyz;
    v_corner = corner;
    v_alpha = alpha;
    // No disc at zero opacity, or behind the eye.
    gl_Position = alpha > 0.0 && c.z < -r ? frame.proj * vec4(c + r * vec3(corner, 0.0), 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
