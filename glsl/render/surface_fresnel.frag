#version 430
// Water: Fresnel-weighted reflection and refraction of the environment (common/frame.glsl), per pixel.
//   n = normalize(interpolated normal), v = unit vector to the eye, cos_i = n·v
//   R = fresnel_schlick(cos_i, n_air, n_water)                          (Schlick 1994)
//   reflected = sky(reflect(−v, n))
//   refracted: t = refract(−v, n, n_air / n_water) (Snell); the floor plane y = tank_min.y is met at
//     q = x + s·t, s = (tank_min.y − x.y) / t.y when t.y < 0, and shaded there with Phong
//     (floor_albedo(q.xz), normal +y, view −t); otherwise sky(t) with s = 0. The light is attenuated
//     over the path s in the water by Beer-Lambert, exp(−σ·s), σ = u_absorption.rgb (1/m).
//   colour = to_display(R·reflected + (1 − R)·refracted)
// Approximations: one interface (the ray leaves the water only at the floor), no shadows, and the
// floor is seen wherever the refracted ray meets its plane (inside or outside the tank).
// With SHOW_FRESNEL defined (tests only) the output is R itself, linear, in every channel.
#include "../common/frame.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = RANRYU_LOC_ABSORPTION) uniform vec4 u_absorption;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 v = normalize(frame.eye.xyz - v_world);
    // A back face is seen only through a gap in the front ones (the mesh is closed): shade it as
    // the interface seen from its other side.
    if (dot(n, v) < 0.0) n = -n;
    float cos_i = dot(n, v);
    float r = fresnel_schlick(cos_i, RANRYU_IOR_AIR, RANRYU_IOR_WATER);
#ifdef SHOW_FRESNEL
    out_color = vec4(vec3(r), 1.0);
#else
    vec3 reflected = sky(reflect(-v, n));
    vec3 t = refract(-v, n, RANRYU_IOR_AIR / RANRYU_IOR_WATER);
    vec3 refracted;
    float path = 0.0;
    if (t.y < 0.0) {
        path = (frame.tank_min.y - v_world.y) / t.y;
        vec3 q = v_world + max(path, 0.0) * t;
        refracted = phong_linear(floor_albedo(q.xz), vec3(0.0, 1.0, 0.0), -t);
    } else {
        refracted = sky(t);
    }
    refracted *= exp(-u_absorption.rgb * max(path, 0.0));
    out_color = vec4(to_display(r * reflected + (1.0 - r) * refracted), 1.0);
#endif
}
