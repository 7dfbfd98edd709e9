// The per-frame view block, the Phong model every raster pass shades with, and the environment
// (floor checker, procedural sky) that the surface's Fresnel mode reflects and refracts
// (docs/METHOD.md §8).
#include "../shared/bindings.h"
#include "../render/shading.h"

layout(std140, binding = RANRYU_UBO_FRAME) uniform FrameBlock { FrameParams frame; };

// Phong reflection (Phong 1975) of one directional light, in world space, linear (before gamma):
//     c = L · (k_a·base + k_d·max(n·l, 0)·base + k_s·max(r·v, 0)^s),   r = reflect(−l, n),
// with k_a = light_color.a, k_d, k_s, s = material.xyz; the specular term is zero where n·l ≤ 0.
vec3 phong_linear(vec3 base, vec3 n, vec3 v) {
    vec3 l = frame.light_dir.xyz;
    float ndl = dot(n, l);
    float diffuse = max(ndl, 0.0);
    float specular = ndl > 0.0 ? pow(max(dot(reflect(-l, n), v), 0.0), frame.material.z) : 0.0;
    return frame.light_color.rgb *
           (frame.light_color.a * base + frame.material.x * diffuse * base + frame.material.y * specular);
}

// Display encoding: clamp to [0, 1], then gamma 2.2.
vec3 to_display(vec3 c) { return pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)); }

// Phong, display-encoded. tests/gl/render_test.cpp evaluates the same formula on the CPU.
vec3 shade_phong(vec3 base, vec3 n, vec3 v) { return to_display(phong_linear(base, n, v)); }

// The floor's 0.1 m checker (floor.frag draws it; the Fresnel mode sees it through the water).
vec3 floor_albedo(vec2 xz) {
    ivec2 cell = ivec2(floor(xz / 0.1));
    return ((cell.x + cell.y) & 1) == 0 ? vec3(0.62) : vec3(0.42);
}

// A procedural environment seen in direction d (unit, world space), linear (docs/RENDERING.md (R2)):
// a sky gradient from the horizon to the zenith with sqrt of the elevation, below the horizon the
// ground fading into the horizon's haze as exp(k·d_y), and a sun in the light's direction, a lobe
// 4·L·max(d·l, 0)^512. Colours and k: render/shading.h. No texture file.
vec3 sky(vec3 d) {
    vec3 gradient = mix(vec3(RANRYU_SKY_HORIZON), vec3(RANRYU_SKY_ZENITH), sqrt(clamp(d.y, 0.0, 1.0)));
    vec3 ground = mix(vec3(RANRYU_SKY_GROUND), vec3(RANRYU_SKY_HORIZON), exp(RANRYU_SKY_HAZE * min(d.y, 0.0)));
    vec3 base = d.y < 0.0 ? ground : gradient;
    return base + 4.0 * frame.light_color.rgb * pow(max(dot(d, frame.light_dir.xyz), 0.0), 512.0);
}

// Schlick's approximation (Schlick 1994) of the unpolarised Fresnel reflectance at an interface from
// index n1 into n2, for the cosine of the angle of incidence cos_i (measured on the n1 side):
//     R = R0 + (1 − R0)(1 − cos_i)^5,   R0 = ((n1 − n2) / (n1 + n2))^2.
// For air to water R0 = 0.0204; tests/gl/surface_shading_test.cpp bounds its error against the exact
// dielectric formula.
float fresnel_schlick(float cos_i, float n1, float n2) {
    float r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    float m = 1.0 - clamp(cos_i, 0.0, 1.0);
    return r0 + (1.0 - r0) * m * m * m * m * m;
}
