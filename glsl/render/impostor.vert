#version 430
// Sphere impostors drawn: one camera-facing quad per particle (instanced, 4-vertex strip), sized to
// cover the sphere's silhouette exactly (silhouette_corner, impostor.glsl).
// Built with RANRYU_BY_LEVEL (sub-particles, render/renderer.h): a sphere of level E has radius
// r/2^E and the level's colour. Parents (children == 0) carry their levels word: one the spawn pass
// split (E > 0) is not drawn, its sub-particles are. Sub-particles (children == 1) carry E in position.w.
// Built with RANRYU_RADIUS_IN_W (the paddle, render/renderer.h draw_sphere): the radius is position.w.
// A fluid particle with position.w = -1 is parked (the emitter's budget, engine/sim/fluid.h): not drawn.
#include "impostor.glsl"

layout(location = RANRYU_ATTR_POSITION) in vec4 in_position;
layout(location = RANRYU_ATTR_VELOCITY) in vec4 in_velocity;
#ifdef RANRYU_BY_LEVEL
layout(location = RANRYU_ATTR_LEVEL) in uint in_level;
layout(location = RANRYU_LOC_IMPOSTOR_CHILDREN) uniform uint children;
flat out vec3 v_base;
#endif

out vec3 v_view_pos;          // this corner, view space
flat out vec3 v_center;       // sphere centre, view space
flat out float v_speed;
flat out float v_radius;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    vec3 c = (frame.view * vec4(in_position.xyz, 1.0)).xyz;
    float r = frame.material.w;
#ifdef RANRYU_RADIUS_IN_W
    r = in_position.w;
#endif
#ifdef RANRYU_BY_LEVEL
    uint level = children != 0u ? min(uint(in_position.w), 3u) : 0u;
    r = ldexp(r, -int(level));
    v_base = level_base(level);
    bool split = children == 0u && (in_level >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) != 0u;
#else
    bool split = false;
#endif
#if defined(RANRYU_BY_LEVEL)
    split = split || (children == 0u && in_position.w < -0.5);   // a parked parent (engine/sim/fluid.h): not drawn
#elif !defined(RANRYU_RADIUS_IN_W)
    split = in_position.w < -0.5;   // parked (engine/sim/fluid.h): not drawn
#endif
    float d = length(c);
    v_center = c;
    v_speed = length(in_velocity.xyz);
    v_radius = r;
    if (split || d <= r * 1.001) {   // split into sub-particles, or the eye inside the sphere: draw nothing
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_view_pos = c;
        return;
    }
    vec3 p = silhouette_corner(c, r, corner);
    v_view_pos = p;
    gl_Position = frame.proj * vec4(p, 1.0);
}
