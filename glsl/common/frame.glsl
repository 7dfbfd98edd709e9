// The per-frame view block and the Phong model every raster pass shades with.
#include "../shared/bindings.h"

layout(std140, binding = RANRYU_UBO_FRAME) uniform FrameBlock { FrameParams frame; };

// Phong reflection (Phong 1975) of one directional light, in world space:
//     c = L · (k_a·base + k_d·max(n·l, 0)·base + k_s·max(r·v, 0)^s),   r = reflect(−l, n),
// with k_a = light_color.a, k_d, k_s, s = material.xyz; the specular term is zero where n·l ≤ 0.
// Then gamma 2.2 for display. tests/gl/render_test.cpp evaluates the same formula on the CPU.
vec3 shade_phong(vec3 base, vec3 n, vec3 v) {
    vec3 l = frame.light_dir.xyz;
    float ndl = dot(n, l);
    float diffuse = max(ndl, 0.0);
    float specular = ndl > 0.0 ? pow(max(dot(reflect(-l, n), v), 0.0), frame.material.z) : 0.0;
    vec3 c = frame.light_color.rgb *
             (frame.light_color.a * base + frame.material.x * diffuse * base + frame.material.y * specular);
    return pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2));
}
