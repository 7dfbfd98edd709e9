#version 430
// The compute raster's shading (docs/RENDERING.md (R15)), drawn over the whole target (sky.vert's
// triangle) after rasterise_impostors.comp: at each pixel, the sphere found nearest there (u_id,
// its id + 1; 0: none, discarded) is shaded as impostor.frag shades it, with its depth written for the
// depth test against the floor and the tank, and for what is drawn after. Built with BY_LEVEL, an id
// with kChild is a sub-particle's, of radius r/2^E and the level's colour, and a parent has level 0's.
#include "impostor.glsl"

layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
#ifdef BY_LEVEL
layout(std430) readonly buffer SubparticlePositions { vec4 sub_position[]; };
#endif
layout(binding = RANRYU_IMG_IMPOSTOR_ID, r32ui) readonly uniform uimage2D u_id;
layout(location = 0) out vec4 out_color;

const uint kChild = 0x80000000u;

void main() {
    uint id = imageLoad(u_id, ivec2(gl_FragCoord.xy)).x;
    if (id == 0u) discard;
    id -= 1u;
    float r = frame.material.w;
#ifdef BY_LEVEL
    bool child = (id & kChild) != 0u;
    vec4 x = child ? sub_position[id & ~kChild] : position[id];
    uint level = child ? min(uint(x.w), 3u) : 0u;
    r = ldexp(r, -int(level));
    vec3 base = level_base(level);
#else
    vec4 x = position[id];
    vec3 base = speed_base(length(velocity[id].xyz));
#endif
    vec3 c = (frame.view * vec4(x.xyz, 1.0)).xyz;
    vec3 dir = view_ray(gl_FragCoord.xy);
    float t = sphere_front(dir, c, r);
    if (t < 0.0) discard;   // the raster found the ray on the sphere; kept against its rounding
    vec3 p = t * dir;
    gl_FragDepth = window_depth(p);
    out_color = vec4(shade_impostor(base, p, c, r, dir), 1.0);
}
