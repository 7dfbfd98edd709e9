#version 430
// The compute raster's shading (docs/RENDERING.md (R15)), drawn over the whole target (sky.vert's
// triangle) after rasterise_impostors.comp: at each pixel, the particle found nearest there (u_id,
// index + 1; 0: none, discarded) is shaded as impostor.frag shades it, with its depth written for the
// depth test against the floor and the tank, and for what is drawn after.
#include "impostor.glsl"

layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(binding = RANRYU_IMG_IMPOSTOR_ID, r32ui) readonly uniform uimage2D u_id;
layout(location = 0) out vec4 out_color;

void main() {
    uint id = imageLoad(u_id, ivec2(gl_FragCoord.xy)).x;
    if (id == 0u) discard;
    vec3 c = (frame.view * vec4(position[id - 1u].xyz, 1.0)).xyz;
    float r = frame.material.w;
    vec3 dir = view_ray(gl_FragCoord.xy);
    float t = sphere_front(dir, c, r);
    if (t < 0.0) discard;   // the raster found the ray on the sphere; kept against its rounding
    vec3 p = t * dir;
    gl_FragDepth = window_depth(p);
    out_color = vec4(shade_impostor(speed_base(length(velocity[id - 1u].xyz)), p, c, r, dir), 1.0);
}
