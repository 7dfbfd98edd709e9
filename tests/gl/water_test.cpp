// The water shading's passes (render::Shading::water, docs/RENDERING.md) against CPU evaluations of
// their equations, on a scene whose liquid is a box of known size (12 triangles, outward normals,
// counter-clockwise seen from outside, as marching cubes makes them), at random: tank, sun, camera,
// box and absorption.
//
//   - The opaque scene (RGBA16F, linear): sky (R2), tiled floor and walls (R9) lit by (R11) with the
//     liquid's shadow (R10). The CPU replays the shadow map: for each of the (2r + 1)² texels the GPU
//     reads, the ray through the texel centre along the sunlight meets the box over [t0, t1]: s_near is
//     the sun depth (R8) at t0 and d_sun = t1 − t0. Left out: pixels whose footprint crosses an edge
//     of what they show (floor/wall/sky, a grout line, the tank's footprint) or whose centre lies within
//     a 64th of the footprint of such an edge, a tank edge line (within 2.5 px), or a texel whose
//     centre lies within 0.05 texel of the box's outline seen from the sun.
//     (The sky is compared where it is in view; the camera looks down 25°..55°, so it may not be.)
//     The shadow is taken at the point the GPU's depth holds (R12), where compose.comp takes it (R13).
//     Tolerance: 2e-3 relative + 2e-3 (half float keeps 11 bits; the GPU's floats against doubles).
//   - The thickness along each view ray (R5): the box's chord clipped to the opaque scene's distance,
//     with the box floating and with it sunk into the floor. Tolerance 5e-4 m: the opaque distance
//     comes from a 32-bit depth (R12) — near 1 it resolves 6e-8, i.e. |x|²/near·6e-8 ≈ 4e-5 m at 2.6 m.
//   - The surface pixel (R7): Fresnel (R1) at the angles of every face seen, the sky reflected (R2), the
//     highlight (R4), and the opaque scene read back from the GPU, sampled bilinearly where the
//     refracted point x + d·t projects (R5), times exp(−σ_a·d) (R6); d the CPU's chord. Tolerance
//     3/255 of the 8-bit output: the bilinear weights' precision (8 bits in llvmpipe) on the scene's
//     texel differences, amplified up to 2.5x by the display gamma on dark texels.
//   - Frames with and without the liquid agree exactly outside the liquid's projection ∪ its shadow
//     (the floor and walls whose shadow-map taps reach the box's outline seen from the sun), both grown
//     by 2 px, and differ inside; their opaque scenes agree exactly outside the shadow and differ in it.
//   - The scene cache (R13) against the full redraw (WaterOptions::reference()) after a change of view:
//     the linear scene within 1.6e-3·c + 3e-4·C_lit (two half roundings against one), or, at no more than 4 %
//     of the shadow's texels, one shadow-map tap apart (x from the depth, (R12)); the frame within one
//     8-bit step elsewhere; the opaque scene's passes run only in the frames whose view changed.
//   - The thickness at half size, upsampled: within the full-size thickness's range over the 5x5 pixels
//     around (± 1 mm) wherever the opaque depth is continuous, and within 1 mm of it where the chord is
//     one smooth function over the footprint read.
// The thickness and surface-pixel cases draw the thickness at the frame's size (their CPU d is the
// chord at the pixel's centre); the others use the default options.
#include "support/gl_fixture.h"
#include "support/read_pixels.h"
#include "support/screen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "render/shading.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "shared/bindings.h"

namespace {

namespace render = ranryu::render;
namespace gpu = ranryu::gpu;
using ranryu::gl::Buffer;
using ranryu::profile::GpuTimer;
using ranryu::shader::FileSource;
using ranryu::test::read_texture;

constexpr int kWidth = 160, kHeight = 120;
const glm::dvec3 kHorizon(RANRYU_SKY_HORIZON), kZenith(RANRYU_SKY_ZENITH), kGround(RANRYU_SKY_GROUND);
const glm::dvec3 kTile(RANRYU_TILE_ALBEDO), kGrout(RANRYU_GROUT_ALBEDO), kGroundAlbedo(RANRYU_GROUND_ALBEDO);

struct Box {
    glm::dvec3 lo, hi;
};

// The ray o + t·d inside the box: [t0, t1] with t1 > t0, or nothing. `axis`, `exit_axis`: the entry
// and exit faces' axes.
struct Chord {
    double t0, t1;
    int axis, exit_axis;
};
std::optional<Chord> chord(glm::dvec3 o, glm::dvec3 d, const Box& b) {
    double t0 = -1e30, t1 = 1e30;
    int axis = -1, exit_axis = -1;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return std::nullopt;
            continue;
        }
        double u = (b.lo[a] - o[a]) / d[a], v = (b.hi[a] - o[a]) / d[a];
        if (u > v) std::swap(u, v);
        if (u > t0) t0 = u, axis = a;
        if (v < t1) t1 = v, exit_axis = a;
    }
    if (t1 <= t0) return std::nullopt;
    return Chord{t0, t1, axis, exit_axis};
}

// A random tank, sun, camera, liquid box and absorption.
struct Rig {
    ranryu::scene::Scene scene;
    render::Camera camera;
    gpu::FrameParams fp;
    Box box;
    glm::dvec3 sigma;
};
Rig random_rig(ranryu::test::Random& rng, bool sunk) {
    Rig r;
    auto& sc = r.scene;
    sc.tank_min = glm::vec3(rng.uniform(-0.2f, 0.2f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.2f, 0.2f));
    sc.tank_max = sc.tank_min + glm::vec3(rng.uniform(0.8f, 1.1f), rng.uniform(0.5f, 0.7f), rng.uniform(0.6f, 0.9f));
    sc.gravity = glm::vec3(0.0f, -9.81f, 0.0f);
    const glm::dvec3 lo(sc.tank_min), hi(sc.tank_max);
    // The box: 0.2..0.35 m wide, inside the tank, 4..10 cm above the floor (or 5 cm into it).
    const glm::dvec3 size(rng.uniform(0.2f, 0.35f), rng.uniform(0.12f, 0.25f), rng.uniform(0.2f, 0.35f));
    const glm::dvec3 mid = 0.5 * (lo + hi);
    r.box.lo = glm::dvec3(mid.x - 0.5 * size.x + rng.uniform(-0.1f, 0.1f), lo.y + (sunk ? -0.05 : rng.uniform(0.04f, 0.1f)),
                          mid.z - 0.5 * size.z + rng.uniform(-0.1f, 0.1f));
    r.box.hi = r.box.lo + size;
    const float az = rng.uniform(0.0f, 6.2831853f), el = glm::radians(rng.uniform(25.0f, 55.0f));
    const glm::vec3 target = glm::vec3(0.5 * (r.box.lo + r.box.hi)) - glm::vec3(0.0f, 0.05f, 0.0f);
    r.camera.target = target;
    r.camera.eye = target + rng.uniform(1.6f, 2.0f) * glm::vec3(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    r.camera.fov_deg = 40.0f;
    // The sun: elevation 40°..70°, within 70° of the camera's azimuth (the shadow falls in view).
    const float la = az + glm::radians(rng.uniform(-70.0f, 70.0f)), le = glm::radians(rng.uniform(40.0f, 70.0f));
    sc.light_dir = glm::vec3(std::cos(le) * std::cos(la), std::sin(le), std::cos(le) * std::sin(la));
    sc.ambient = rng.uniform(0.15f, 0.35f);
    r.fp = render::frame_params(sc, r.camera, kWidth, kHeight);
    r.sigma = glm::dvec3(rng.uniform(1.0f, 5.0f), rng.uniform(0.3f, 1.5f), rng.uniform(0.05f, 0.5f));
    return r;
}

// The box as marching cubes' output: 36 gpu::MeshVertex, counter-clockwise seen from outside.
std::vector<gpu::MeshVertex> box_mesh(const Box& b) {
    std::vector<gpu::MeshVertex> out;
    const glm::dvec3 c = 0.5 * (b.lo + b.hi), half = 0.5 * (b.hi - b.lo);
    for (int a = 0; a < 3; ++a)
        for (const double side : {-1.0, 1.0}) {
            glm::dvec3 n(0.0), u(0.0), v(0.0);
            n[a] = side;
            u[(a + 1) % 3] = half[(a + 1) % 3];   // e_(a+1) x e_(a+2) = e_a
            v[(a + 2) % 3] = half[(a + 2) % 3];
            if (side < 0.0) std::swap(u, v);
            const glm::dvec3 f = c + side * half[a] * glm::abs(n);
            const glm::dvec3 q[4] = {f - u - v, f + u - v, f + u + v, f - u + v};
            for (const int k : {0, 1, 2, 0, 2, 3})
                out.push_back(gpu::MeshVertex{glm::vec4(glm::vec3(q[k]), 1.0f), glm::vec4(glm::vec3(n), 0.0f)});
        }
    return out;
}

struct Frame {
    std::vector<std::uint8_t> rgba;   // the frame, 8-bit display-encoded
    std::vector<float> scene;         // the opaque scene, linear rgba
    std::vector<float> depth;         // its depth buffer
    std::vector<float> thickness;     // the liquid's thickness per pixel (m)
    glm::dvec3 final_color(int i, int j) const {
        const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
        return {rgba[k], rgba[k + 1], rgba[k + 2]};
    }
    glm::dvec3 scene_texel(int i, int j) const {
        i = std::clamp(i, 0, kWidth - 1), j = std::clamp(j, 0, kHeight - 1);
        const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
        return {scene[k], scene[k + 1], scene[k + 2]};
    }
};

// The box as a mesh to draw, and an unused particle buffer.
struct BoxDraw {
    std::vector<gpu::MeshVertex> mesh;
    Buffer vertices, indirect, unused;
    render::SurfaceMesh surface;
    explicit BoxDraw(const Box& b)
        : mesh(box_mesh(b)),
          vertices(Buffer::from(std::span<const gpu::MeshVertex>(mesh), GL_STATIC_DRAW, "water_test.mesh")),
          indirect(indirect_for(mesh.size())),
          unused(16, GL_STATIC_DRAW, nullptr, "water_test.unused"),
          surface{vertices, indirect, 0} {}
    static Buffer indirect_for(std::size_t count) {
        const std::uint32_t draw[4] = {std::uint32_t(count), 1u, 0u, 0u};
        return Buffer(sizeof draw, GL_STATIC_DRAW, draw, "water_test.indirect");
    }
};

// The frame in `target` and the renderer's opaque scene, its depth and the liquid's thickness.
Frame read_frame(const ranryu::gl::RenderTarget& target, const render::Renderer& renderer) {
    Frame f;
    f.rgba.resize(std::size_t(kWidth) * kHeight * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, f.rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    read_texture(renderer.scene_color(), GL_RGBA, f.scene, 4);
    read_texture(renderer.scene_depth(), GL_DEPTH_COMPONENT, f.depth, 1);
    read_texture(renderer.thickness(), GL_RED, f.thickness, 1);
    return f;
}

Frame render_water(const Rig& r, bool with_liquid, render::WaterOptions options = {}) {
    GpuTimer timer;
    render::Renderer renderer(FileSource::embedded(), timer, render::Shading::water, false, false, options);
    renderer.resize(kWidth, kHeight);
    renderer.set_frame(r.fp);
    renderer.set_absorption(glm::vec3(r.sigma));
    ranryu::gl::RenderTarget target(kWidth, kHeight, "water_test");
    const BoxDraw box(r.box);
    timer.begin_frame();
    renderer.draw(target, box.unused, box.unused, 0, with_liquid ? &box.surface : nullptr);
    timer.end_frame();
    Frame f = read_frame(target, renderer);
    timer.drain();
    ranryu::test::require_no_gl_errors();
    return f;
}

// The default scene cache with the thickness at the frame's size, for the tests that compare the
// thickness per pixel with the CPU's chord.
const render::WaterOptions kFullSizeThickness{true, 1};

// ---- the CPU side, in doubles

class Cpu {
public:
    explicit Cpu(const Rig& r)
        : r_(r), f_(r.fp), screen_{glm::dmat4(r.fp.view_proj), kWidth, kHeight}, sun_(render::sun_view(r.fp)),
          sun_inv_(glm::inverse(glm::dmat4(sun_.matrix))) {}

    glm::dvec3 eye() const { return glm::dvec3(f_.eye); }
    glm::dvec3 l() const { return glm::normalize(glm::dvec3(f_.light_dir)); }

    glm::dvec3 ray(double x, double y) const { return screen_.ray(x, y); }
    glm::dvec2 window(glm::dvec3 p) const { return screen_.window(p); }

    // What the opaque scene shows along a ray from the eye: kind 0 sky, 1 floor, 2..5 a wall; the
    // distance, point and normal, and the class of its albedo (for the edge checks).
    struct Opaque {
        int kind = 0;
        double t = 1e30;
        glm::dvec3 p{0.0}, n{0.0};
        int albedo_class = 0;   // 0 tile, 1 grout, 2 ground
    };
    Opaque opaque(glm::dvec3 d) const {
        Opaque o;
        const glm::dvec3 lo(f_.tank_min), hi(f_.tank_max), e = eye();
        const double margin = std::max(hi.x - lo.x, hi.z - lo.z);
        if (d.y < 0.0) {
            const double t = (lo.y - e.y) / d.y;
            const glm::dvec3 p = e + t * d;
            if (t > 0.0 && p.x >= lo.x - margin && p.x <= hi.x + margin && p.z >= lo.z - margin && p.z <= hi.z + margin)
                o = Opaque{1, t, p, {0.0, 1.0, 0.0}, 0};
        }
        // Walls (glsl/render/walls.vert): the planes x = lo.x, hi.x, z = lo.z, hi.z, inward normals,
        // drawn where the eye is on their inner side.
        for (int w = 0; w < 4; ++w) {
            const int a = (w & 1) ? 0 : 2;   // 0: z = lo.z, 1: x = hi.x, 2: z = hi.z, 3: x = lo.x
            const bool high = w == 1 || w == 2;
            const double plane = high ? hi[a] : lo[a];
            glm::dvec3 n(0.0);
            n[a] = high ? -1.0 : 1.0;
            if (n[a] * (e[a] - plane) <= 0.0) continue;   // culled: the eye is outside its inner side
            if (std::abs(d[a]) < 1e-12) continue;
            const double t = (plane - e[a]) / d[a];
            const glm::dvec3 p = e + t * d;
            const int b = 2 - a;   // the wall's horizontal axis (x for z-walls, z for x-walls)
            if (t <= 0.0 || t >= o.t || p.y < lo.y || p.y > hi.y || p[b] < lo[b] || p[b] > hi[b]) continue;
            o = Opaque{2 + w, t, p, n, 0};
        }
        if (o.kind != 0) o.albedo_class = albedo_class(o);
        return o;
    }

    static glm::dvec2 plane_uv(glm::dvec3 p, glm::dvec3 n) {
        return std::abs(n.y) > 0.5 ? glm::dvec2(p.x, p.z) : (std::abs(n.x) > 0.5 ? glm::dvec2(p.z, p.y) : glm::dvec2(p.x, p.y));
    }
    int albedo_class(const Opaque& o) const {
        if (o.kind == 1 && (o.p.x < f_.tank_min.x || o.p.x >= f_.tank_max.x || o.p.z < f_.tank_min.z || o.p.z >= f_.tank_max.z))
            return 2;
        const glm::dvec2 uv = plane_uv(o.p, o.n) / double(RANRYU_TILE_SIZE);
        const glm::dvec2 frac = uv - glm::floor(uv);
        const double g = double(RANRYU_GROUT_WIDTH) / double(RANRYU_TILE_SIZE);
        return frac.x < g || frac.y < g ? 1 : 0;
    }

    // Whether p lies within delta (m) of a grout line's side or of the tank's footprint on the floor.
    bool near_albedo_edge(const Opaque& o, double delta) const {
        const double t = double(RANRYU_TILE_SIZE), g = double(RANRYU_GROUT_WIDTH);
        const glm::dvec2 uv = plane_uv(o.p, o.n);
        for (int a = 0; a < 2; ++a) {
            const double f = (uv[a] / t - std::floor(uv[a] / t)) * t;   // metres into the tile, grout first
            if (f < delta || std::abs(f - g) < delta || t - f < delta) return true;
        }
        if (o.kind != 1) return false;
        return std::abs(o.p.x - f_.tank_min.x) < delta || std::abs(o.p.x - f_.tank_max.x) < delta ||
               std::abs(o.p.z - f_.tank_min.z) < delta || std::abs(o.p.z - f_.tank_max.z) < delta;
    }

    // (R2) The sky with its sun, linear.
    glm::dvec3 sky(glm::dvec3 d) const {
        const glm::dvec3 ground = glm::mix(kGround, kHorizon, std::exp(RANRYU_SKY_HAZE * std::min(d.y, 0.0)));
        const glm::dvec3 base = d.y < 0.0 ? ground : glm::mix(kHorizon, kZenith, std::sqrt(std::clamp(d.y, 0.0, 1.0)));
        return base + 4.0 * glm::dvec3(f_.light_color) * std::pow(std::max(glm::dot(d, glm::dvec3(f_.light_dir)), 0.0), 512.0);
    }

    // (R8) the sun depth; (R10) the sunlight reaching x, replaying the shadow map's taps; nothing
    // where a tap's texel centre is within 0.05 texel of the box's outline from the sun.
    double sun_depth(glm::dvec3 x) const { return glm::dot(x - glm::dvec3(sun_.origin), -l()); }
    std::optional<glm::dvec3> sun_transmittance(glm::dvec3 x) const {
        const glm::dvec4 c = glm::dmat4(sun_.matrix) * glm::dvec4(x, 1.0);
        const double n = RANRYU_SHADOW_MAP_SIZE;
        const glm::dvec2 g = (glm::dvec2(c) * 0.5 + 0.5) * n;
        const glm::dvec2 base = glm::floor(g), frac = g - base;
        if (std::min({frac.x, frac.y, 1.0 - frac.x, 1.0 - frac.y}) < 1e-3) return std::nullopt;
        const double s = sun_depth(x);
        glm::dvec3 sum(0.0);
        constexpr int kR = RANRYU_SHADOW_PCF_RADIUS;
        for (int dy = -kR; dy <= kR; ++dy)
            for (int dx = -kR; dx <= kR; ++dx) {
                const glm::dvec2 centre = base + glm::dvec2(dx, dy) + 0.5;
                std::optional<Chord> hit;
                int hits = 0;
                for (const glm::dvec2 off : {glm::dvec2(0.0), glm::dvec2(0.05, 0.05), glm::dvec2(-0.05, 0.05),
                                             glm::dvec2(0.05, -0.05), glm::dvec2(-0.05, -0.05)}) {
                    const glm::dvec2 ndc = (centre + off) / n * 2.0 - 1.0;
                    const glm::dvec4 a = sun_inv_ * glm::dvec4(ndc, -1.0, 1.0);
                    const auto h = chord(glm::dvec3(a) / a.w, -l(), r_.box);
                    hits += h ? 1 : 0;
                    if (off == glm::dvec2(0.0)) hit = h;
                }
                if (hits != 0 && hits != 5) return std::nullopt;
                if (hit) {
                    const glm::dvec4 a = sun_inv_ * glm::dvec4((centre / n) * 2.0 - 1.0, -1.0, 1.0);
                    const double near = sun_depth(glm::dvec3(a) / a.w - hit->t0 * l());
                    if (s > near + RANRYU_SHADOW_BIAS) {
                        sum += glm::exp(-r_.sigma * (hit->t1 - hit->t0));
                        continue;
                    }
                }
                sum += glm::dvec3(1.0);
            }
        return sum / double((2 * kR + 1) * (2 * kR + 1));
    }
    // Whether any shadow-map tap of x could see the box: x's texel within r + 1 texels of the box's
    // outline from the sun (the convex hull of its corners; tested on their bounding square).
    bool near_shadow(glm::dvec3 x) const {
        glm::dvec2 lo(1e30), hi(-1e30);
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 p(k & 1 ? r_.box.hi.x : r_.box.lo.x, k & 2 ? r_.box.hi.y : r_.box.lo.y, k & 4 ? r_.box.hi.z : r_.box.lo.z);
            const glm::dvec2 q = glm::dvec2(glm::dmat4(sun_.matrix) * glm::dvec4(p, 1.0));
            lo = glm::min(lo, q), hi = glm::max(hi, q);
        }
        const double grow = 2.0 * (RANRYU_SHADOW_PCF_RADIUS + 1.5) / RANRYU_SHADOW_MAP_SIZE;
        const glm::dvec2 q = glm::dvec2(glm::dmat4(sun_.matrix) * glm::dvec4(x, 1.0));
        return glm::all(glm::greaterThan(q, lo - grow)) && glm::all(glm::lessThan(q, hi + grow)) &&
               sun_depth(x) > sun_depth(0.5 * (r_.box.lo + r_.box.hi)) - glm::length(r_.box.hi - r_.box.lo);
    }

    // (R9), (R11): the lit floor or wall, linear; its shadow (R10) taken at `shadow_at` (default: o.p).
    std::optional<glm::dvec3> matte(const Opaque& o, std::optional<glm::dvec3> shadow_at = std::nullopt) const {
        const glm::dvec3 albedo = o.albedo_class == 2 ? kGroundAlbedo : o.albedo_class == 1 ? kGrout : kTile;
        const double ndl = std::max(glm::dot(o.n, glm::dvec3(f_.light_dir)), 0.0);
        glm::dvec3 sun(0.0);
        if (ndl > 0.0) {
            const auto s = sun_transmittance(shadow_at.value_or(o.p));
            if (!s) return std::nullopt;
            sun = *s;
        }
        return glm::dvec3(f_.light_color) * albedo * (double(f_.light_color.a) + double(f_.material.x) * ndl * sun);
    }

    // (R12), (R13): the world point a depth-buffer value holds at pixel (i, j)'s centre, as compose.comp
    // finds the receiver whose shadow it applies.
    glm::dvec3 depth_point(int i, int j, double depth) const {
        const glm::dvec2 ndc((i + 0.5) / kWidth * 2.0 - 1.0, (j + 0.5) / kHeight * 2.0 - 1.0);
        const double view_z = double(f_.proj[3][2]) / ((2.0 * depth - 1.0) + double(f_.proj[2][2]));
        const double t = view_z * glm::length(glm::dvec3(ndc.x / f_.proj[0][0], ndc.y / f_.proj[1][1], -1.0));
        return eye() + t * ray(i + 0.5, j + 0.5);
    }

    // The opaque scene at pixel (i, j), linear, or nothing where ambiguous (see the top). `depth`: the
    // GPU's depth there, whose point (depth_point) takes the shadow, as in the scene cache (R13).
    std::optional<glm::dvec3> opaque_pixel(int i, int j, Opaque* out = nullptr, std::optional<double> depth = std::nullopt) const {
        const glm::dvec3 d = ray(i + 0.5, j + 0.5);
        const Opaque o = opaque(d);
        double footprint = 0.0;
        for (int c = 0; c < 4; ++c) {
            const Opaque k = opaque(ray(i + double(c & 1), j + double(c >> 1)));
            if (k.kind != o.kind || k.albedo_class != o.albedo_class) return std::nullopt;
            if (o.kind != 0) footprint = std::max(footprint, glm::length(k.p - o.p));
        }
        // A grout line narrower than the footprint can pass between the corners: the centre is left out
        // too where the GPU's interpolated position (to a sixty-fourth of the footprint, 1e-5 m) may
        // fall on the other side of a boundary between albedos.
        if (o.kind != 0 && near_albedo_edge(o, footprint / 64.0 + 1e-5)) return std::nullopt;
        if (near_edge_line(i, j)) return std::nullopt;
        if (out) *out = o;
        if (o.kind == 0) return sky(d);
        return matte(o, depth ? std::optional<glm::dvec3>(depth_point(i, j, *depth)) : std::nullopt);
    }

    // Whether a tank edge (a 1-px line) passes within 2.5 px of the pixel centre.
    bool near_edge_line(int i, int j) const {
        const glm::dvec3 lo(f_.tank_min), hi(f_.tank_max);
        auto corner = [&](int k) { return glm::dvec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z); };
        const glm::dvec2 p(i + 0.5, j + 0.5);
        for (int a = 0; a < 8; ++a)
            for (int bit = 1; bit < 8; bit <<= 1) {
                if (a & bit) continue;
                const glm::dvec2 u = window(corner(a)), v = window(corner(a | bit));
                const double t = std::clamp(glm::dot(p - u, v - u) / std::max(glm::dot(v - u, v - u), 1e-12), 0.0, 1.0);
                if (glm::length(p - (u + t * (v - u))) < 2.5) return true;
            }
        return false;
    }

    // (R5) The box's chord along the pixel's ray clipped to the opaque scene, and the entry face's axis.
    std::optional<std::pair<double, int>> thickness(glm::dvec3 d) const {
        const auto h = chord(eye(), d, r_.box);
        if (!h) return std::pair<double, int>{0.0, -1};
        const double t_o = opaque(d).t;
        return std::pair<double, int>{std::max(0.0, std::min(h->t1, t_o) - std::min(std::max(h->t0, 0.0), t_o)), h->axis};
    }

    const gpu::FrameParams& fp() const { return f_; }
    const Rig& rig() const { return r_; }

private:
    const Rig& r_;
    const gpu::FrameParams& f_;
    ranryu::test::Screen screen_;
    render::SunView sun_;
    glm::dmat4 sun_inv_;
};

std::string describe(glm::dvec3 c) {
    std::ostringstream s;
    s << "(" << c.r << ", " << c.g << ", " << c.b << ")";
    return s.str();
}

// A random rig, its CPU side and its frame (rendered with the liquid). Stays where it was built (cpu
// refers to rig).
struct Case {
    Rig rig;
    Cpu cpu;
    Frame frame;
    explicit Case(ranryu::test::Random& rng, bool sunk = false, render::WaterOptions options = {})
        : rig(random_rig(rng, sunk)), cpu(rig), frame(render_water(rig, true, options)) {}
    Case(const Case&) = delete;
};

}  // namespace

TEST_CASE("water: the opaque scene's sky, tiles and the liquid's coloured shadow match the CPU") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const Case c(rng);
    const auto& [rig, cpu, f] = c;
    int sky = 0, lit = 0, shadowed = 0, walls = 0, failures = 0;
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            Cpu::Opaque o;
            const auto want = cpu.opaque_pixel(i, j, &o, double(f.depth[std::size_t(j) * kWidth + std::size_t(i)]));
            if (!want) continue;
            const glm::dvec3 got = f.scene_texel(i, j);
            const glm::dvec3 err = glm::abs(got - *want) - (2e-3 * glm::abs(*want) + 2e-3);
            if (std::max({err.r, err.g, err.b}) > 0.0 && ++failures <= 8)
                FAIL_CHECK("pixel (" << i << ", " << j << ") kind " << o.kind << ": GPU " << describe(got) << ", CPU " << describe(*want));
            if (o.kind == 0) ++sky;
            else {
                if (o.kind >= 2) ++walls;
                const auto s = glm::dot(o.n, glm::dvec3(rig.fp.light_dir)) > 0.0 ? cpu.sun_transmittance(o.p) : std::nullopt;
                if (s && s->r < 0.999) ++shadowed;
                else if (s) ++lit;
            }
        }
    INFO("compared: " << sky << " sky, " << lit << " lit and " << shadowed << " shadowed floor/wall pixels (" << walls << " on walls)");
    CHECK(failures == 0);
    CHECK(lit > 0);
    CHECK(shadowed > 0);
}

TEST_CASE("water: the liquid's thickness along each view ray is the box's chord in front of the opaque scene") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (const bool sunk : {false, true}) {
        INFO((sunk ? "box sunk 5 cm into the floor" : "box above the floor"));
        const Case c(rng, sunk, kFullSizeThickness);
        const auto& [rig, cpu, f] = c;
        int inside = 0, clipped = 0, outside = 0, failures = 0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i) {
                const auto want = cpu.thickness(cpu.ray(i + 0.5, j + 0.5));
                // The pixel's footprint meets one face and one opaque surface, and no tank edge line
                // (whose depth clips the thickness too).
                bool clear = !cpu.near_edge_line(i, j);
                for (int c = 0; c < 4 && clear; ++c) {
                    const glm::dvec3 d = cpu.ray(i + double(c & 1), j + double(c >> 1));
                    clear = cpu.thickness(d)->second == want->second && cpu.opaque(d).kind == cpu.opaque(cpu.ray(i + 0.5, j + 0.5)).kind;
                }
                if (!clear) continue;
                const double got = f.thickness[std::size_t(j) * kWidth + std::size_t(i)];
                if (std::abs(got - want->first) > 5e-4 && ++failures <= 8)
                    FAIL_CHECK("pixel (" << i << ", " << j << "): GPU " << got << " m, CPU " << want->first << " m");
                if (want->second < 0) ++outside;
                else {
                    ++inside;
                    const auto h = chord(cpu.eye(), cpu.ray(i + 0.5, j + 0.5), rig.box);
                    if (h->t1 > cpu.opaque(cpu.ray(i + 0.5, j + 0.5)).t) ++clipped;
                }
            }
        INFO("compared " << inside << " pixels through the box (" << clipped << " clipped by the opaque scene), " << outside << " beside it");
        CHECK(failures == 0);
        CHECK(inside > 50);
        CHECK(outside > 50);
        if (sunk) CHECK(clipped > 0);
    }
}

TEST_CASE("water: the surface pixel is Fresnel-weighted sky reflection, absorbed refraction of the scene, and the sun's highlight") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const Case c(rng, false, kFullSizeThickness);
    const auto& [rig, cpu, f] = c;
    const auto& fp = rig.fp;
    const glm::dvec3 l(fp.light_dir), light(fp.light_color);
    // (The thickness at the frame's size: the CPU's d is the chord at the pixel's centre.)
    const double n1 = RANRYU_IOR_AIR, n2 = RANRYU_IOR_WATER;
    int compared = 0, failures = 0, refracted_aside = 0;
    std::array<int, 3> per_axis{};
    double cos_min = 1.0, cos_max = 0.0;
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const glm::dvec3 dir = cpu.ray(i + 0.5, j + 0.5);
            const auto h = chord(cpu.eye(), dir, rig.box);
            if (!h) continue;
            bool clear = !cpu.near_edge_line(i, j);
            for (int c = 0; c < 4 && clear; ++c) {
                const auto k = chord(cpu.eye(), cpu.ray(i + double(c & 1), j + double(c >> 1)), rig.box);
                clear = k && k->axis == h->axis;
            }
            if (!clear) continue;
            const glm::dvec3 x = cpu.eye() + h->t0 * dir, v = -dir;
            glm::dvec3 n(0.0);
            n[h->axis] = dir[h->axis] < 0.0 ? 1.0 : -1.0;
            // (R1) Schlick's Fresnel, (R2) the sky reflected, (R4) the highlight.
            const double cos_i = glm::dot(n, v);
            const double r0 = std::pow((n1 - n2) / (n1 + n2), 2.0);
            const double fr = r0 + (1.0 - r0) * std::pow(1.0 - std::clamp(cos_i, 0.0, 1.0), 5.0);
            const glm::dvec3 reflected = cpu.sky(glm::reflect(-v, n));
            const glm::dvec3 hv = glm::normalize(l + v);
            const double highlight = glm::dot(n, l) > 0.0
                                         ? RANRYU_WATER_SPECULAR * std::pow(std::max(glm::dot(n, hv), 0.0), RANRYU_WATER_SHININESS)
                                         : 0.0;
            // (R5) the refracted lookup, (R6) absorption.
            const double d = cpu.thickness(dir)->first;
            const glm::dvec3 t = glm::refract(-v, n, n1 / n2);
            const glm::dvec4 clip = glm::dmat4(fp.view_proj) * glm::dvec4(x + d * t, 1.0);
            glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
            const glm::dvec2 straight((i + 0.5) / kWidth, (j + 0.5) / kHeight);
            if (clip.w <= 0.0 || glm::any(glm::lessThan(uv, glm::dvec2(0.0))) || glm::any(glm::greaterThan(uv, glm::dvec2(1.0)))) {
                uv = straight;
            } else {
                const glm::dvec2 q = uv * glm::dvec2(kWidth, kHeight);
                const int qi = std::min(int(q.x), kWidth - 1), qj = std::min(int(q.y), kHeight - 1);
                // (R12) on the read-back depth: the scene nearer than x is in front of the water.
                const double depth = f.depth[std::size_t(qj) * kWidth + std::size_t(qi)];
                const double view_z = double(fp.proj[3][2]) / ((2.0 * depth - 1.0) + double(fp.proj[2][2]));
                const glm::dvec2 ndc = q / glm::dvec2(kWidth, kHeight) * 2.0 - 1.0;
                const double t_scene = view_z * glm::length(glm::dvec3(ndc.x / fp.proj[0][0], ndc.y / fp.proj[1][1], -1.0));
                if (std::abs(t_scene - h->t0) < 1e-3) continue;   // the check could go either way
                if (t_scene < h->t0) uv = straight;
            }
            if (uv != straight) ++refracted_aside;
            // Bilinear, texel centres at +½, clamped to the edge.
            const glm::dvec2 g = uv * glm::dvec2(kWidth, kHeight) - 0.5, g0 = glm::floor(g), a = g - g0;
            const int x0 = int(g0.x), y0 = int(g0.y);
            const glm::dvec3 behind = glm::mix(glm::mix(f.scene_texel(x0, y0), f.scene_texel(x0 + 1, y0), a.x),
                                               glm::mix(f.scene_texel(x0, y0 + 1), f.scene_texel(x0 + 1, y0 + 1), a.x), a.y);
            const glm::dvec3 c = fr * reflected + (1.0 - fr) * glm::exp(-rig.sigma * d) * behind + highlight * light;
            const glm::dvec3 want = 255.0 * glm::pow(glm::clamp(c, 0.0, 1.0), glm::dvec3(1.0 / 2.2));
            const glm::dvec3 got = f.final_color(i, j);
            const glm::dvec3 err = glm::abs(got - want);
            if (std::max({err.r, err.g, err.b}) > 3.0 && ++failures <= 8)
                FAIL_CHECK("pixel (" << i << ", " << j << ") face axis " << h->axis << ", cos_i " << cos_i << ", d " << d << ": GPU "
                                     << describe(got) << ", CPU " << describe(want));
            ++compared;
            ++per_axis[h->axis];
            cos_min = std::min(cos_min, cos_i), cos_max = std::max(cos_max, cos_i);
        }
    INFO("compared " << compared << " surface pixels (faces along x, y, z: " << per_axis[0] << ", " << per_axis[1] << ", "
                     << per_axis[2] << "), cos θ_i in [" << cos_min << ", " << cos_max << "], " << refracted_aside
                     << " refracted off their own pixel");
    CHECK(failures == 0);
    CHECK(compared > 100);
    // The Fresnel term was checked at the angles of the top and at least one side face.
    CHECK(per_axis[1] > 20);
    CHECK(std::max(per_axis[0], per_axis[2]) > 20);
    CHECK(refracted_aside > 0);
}

TEST_CASE("water: frames with and without the liquid differ only where the liquid and its shadow are") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const Case c(rng);
    const auto& [rig, cpu, with] = c;
    const Frame without = render_water(rig, false);
    // The masks, per pixel centre and corners, grown by 2 px.
    std::vector<char> liquid(std::size_t(kWidth) * kHeight, 0), shadow(liquid.size(), 0);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            for (int c = 0; c < 5; ++c) {
                const glm::dvec3 d = c == 4 ? cpu.ray(i + 0.5, j + 0.5) : cpu.ray(i + double(c & 1), j + double(c >> 1));
                const auto h = chord(cpu.eye(), d, rig.box);
                const Cpu::Opaque o = cpu.opaque(d);
                for (int dj = -2; dj <= 2; ++dj)
                    for (int di = -2; di <= 2; ++di) {
                        const int a = i + di, b = j + dj;
                        if (a < 0 || b < 0 || a >= kWidth || b >= kHeight) continue;
                        if (h && h->t0 < o.t) liquid[std::size_t(b) * kWidth + std::size_t(a)] = 1;
                        if (o.kind != 0 && cpu.near_shadow(o.p)) shadow[std::size_t(b) * kWidth + std::size_t(a)] = 1;
                    }
            }
    int outside = 0, differ_outside = 0, in_liquid = 0, differ_liquid = 0, in_shadow = 0, differ_shadow = 0;
    int scene_differ_shadow = 0, scene_differ_outside = 0;
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const std::size_t k = std::size_t(j) * kWidth + std::size_t(i);
            const bool differ = with.final_color(i, j) != without.final_color(i, j);
            // The opaque scene (under the liquid too) changes only in the shadow.
            if (with.scene_texel(i, j) != without.scene_texel(i, j)) {
                if (shadow[k]) ++scene_differ_shadow;
                else if (++scene_differ_outside <= 8)
                    FAIL_CHECK("scene texel (" << i << ", " << j << ") outside the shadow: with " << describe(with.scene_texel(i, j))
                                               << ", without " << describe(without.scene_texel(i, j)));
            }
            if (liquid[k]) ++in_liquid, differ_liquid += differ;
            else if (shadow[k]) ++in_shadow, differ_shadow += differ;
            else {
                ++outside;
                if (differ && ++differ_outside <= 8)
                    FAIL_CHECK("pixel (" << i << ", " << j << ") outside the liquid and its shadow: with " << describe(with.final_color(i, j))
                                         << ", without " << describe(without.final_color(i, j)));
            }
        }
    INFO(outside << " pixels outside both masks, " << in_liquid << " in the liquid's (" << differ_liquid << " differ), " << in_shadow
                 << " in its shadow's (" << differ_shadow << " differ; the opaque scene differs at " << scene_differ_shadow
                 << " texels of the shadow's mask)");
    CHECK(differ_outside == 0);
    CHECK(scene_differ_outside == 0);
    CHECK(outside > kWidth * kHeight / 4);
    CHECK(differ_liquid > in_liquid / 2);
    // The shadow is there (seen in the frame, or under the liquid in the opaque scene).
    CHECK(scene_differ_shadow > 0);
}

namespace {
// The pass's ms over the frames read back, or how many frames ran it.
std::size_t frames_with(const GpuTimer& timer, const std::string& pass) {
    for (const auto& p : timer.passes())
        if (p.name == pass) return p.ms.size();
    return 0;
}
}  // namespace

TEST_CASE("water: the scene cache gives the frame the full redraw gives, and is drawn again only when the view changes") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const Rig first = random_rig(rng, false);
    // The second view: the eye turned 20°..40° about the vertical through the target.
    Rig second = first;
    const float turn = glm::radians(rng.uniform(20.0f, 40.0f));
    const glm::vec3 arm = first.camera.eye - first.camera.target;
    second.camera.eye = first.camera.target + glm::vec3(std::cos(turn) * arm.x - std::sin(turn) * arm.z, arm.y,
                                                        std::sin(turn) * arm.x + std::cos(turn) * arm.z);
    second.fp = render::frame_params(second.scene, second.camera, kWidth, kHeight);
    const BoxDraw box(first.box);
    ranryu::gl::RenderTarget target(kWidth, kHeight, "water_test");

    // The cache: a frame at the first view, then three at the second (set each frame, as a window
    // does); the second view's last frame against a renderer that draws everything every frame.
    GpuTimer timer;
    render::Renderer cached(FileSource::embedded(), timer, render::Shading::water, false, false, kFullSizeThickness);
    cached.resize(kWidth, kHeight);
    cached.set_absorption(glm::vec3(first.sigma));
    for (int frame = 0; frame < 4; ++frame) {
        cached.set_frame(frame == 0 ? first.fp : second.fp);
        timer.begin_frame();
        cached.draw(target, box.unused, box.unused, 0, &box.surface);
        timer.end_frame();
    }
    const Frame got = read_frame(target, cached);
    timer.drain();
    GpuTimer reference_timer;
    render::Renderer reference(FileSource::embedded(), reference_timer, render::Shading::water, false, false,
                               render::WaterOptions::reference());
    reference.resize(kWidth, kHeight);
    reference.set_absorption(glm::vec3(first.sigma));
    for (int frame = 0; frame < 2; ++frame) {
        reference.set_frame(second.fp);
        reference_timer.begin_frame();
        reference.draw(target, box.unused, box.unused, 0, &box.surface);
        reference_timer.end_frame();
    }
    const Frame want = read_frame(target, reference);
    reference_timer.drain();
    ranryu::test::require_no_gl_errors();

    // The opaque scene drawn in the first two frames only (the view changed), composed in all four;
    // the reference draws it every frame.
    for (const char* pass : {"clear", "draw-sky", "draw-floor", "draw-walls", "draw-tank"}) {
        INFO(pass);
        CHECK(frames_with(timer, pass) == 2);
        CHECK(frames_with(reference_timer, pass) == 2);
    }
    CHECK(frames_with(timer, "compose") == 4);
    CHECK(frames_with(timer, "shadow-map") == 4);

    // The linear scene: the cache rounds C_lit to half (2^-11 relative) and q (by up to 2^-12), and
    // compose rounds C_lit·(1 − q·(1 − S)) to half again; the reference rounds (R11) once, c. So
    // |cached − redrawn| <= 3·2^-11·c + 2^-12·C_lit: tolerance 1.6e-3·c + 3e-4·C_lit.
    // compose finds x from the depth (R12), within ~2e-5 m of the raster's interpolated x at these
    // distances: where that moves x across a shadow-map texel's edge, one of the 9 taps may change, by at
    // most C_lit/9 (C_lit: the scene without the liquid), at a few texels along the shadow's edges, on
    // either side of it (the cached texel shadowed and the redrawn one not, or the reverse).
    // The frame: display-encoded to 8 bits from those, a difference of at most one step elsewhere.
    const Frame bare = render_water(second, false, kFullSizeThickness);
    int scene_failures = 0, frame_failures = 0, equal_frame = 0, one_tap = 0, in_shadow = 0;
    double worst = 0.0, largest_scene_difference = 0.0;
    std::vector<glm::ivec2> refracted;   // frame pixels past one step whose own scene texel is not a tap apart
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const glm::dvec3 g = got.scene_texel(i, j), w = want.scene_texel(i, j), lit = bare.scene_texel(i, j);
            in_shadow += lit != w;
            const glm::dvec3 err = glm::abs(g - w), tol = 1.6e-3 * glm::abs(w) + 3e-4 * lit;
            largest_scene_difference = std::max({largest_scene_difference, err.r, err.g, err.b});
            const glm::dvec3 rel = err / glm::max(glm::abs(w), glm::dvec3(1e-3));
            bool tap = false;
            if (std::max({err.r - tol.r, err.g - tol.g, err.b - tol.b}) > 0.0) {
                const glm::dvec3 over = err - (tol + lit / 9.0);
                // Either side may be the shadowed one: the cached x can move into a shadowed tap where
                // the redrawn texel is in full light (lit == w), as well as out of one.
                tap = std::max({over.r, over.g, over.b}) <= 0.0 && (lit != w || lit != g);
                one_tap += tap;
                if (!tap && ++scene_failures <= 8)
                    FAIL_CHECK("scene texel (" << i << ", " << j << "): cached " << describe(g) << ", redrawn " << describe(w));
            } else {
                worst = std::max({worst, rel.r, rel.g, rel.b});
            }
            const glm::dvec3 d = glm::abs(got.final_color(i, j) - want.final_color(i, j));
            if (!tap && std::max({d.r, d.g, d.b}) > 1.0) {
                refracted.emplace_back(i, j);
                if (++frame_failures <= 8)
                    WARN("pixel (" << i << ", " << j << "): cached " << describe(got.final_color(i, j)) << ", redrawn "
                                   << describe(want.final_color(i, j)));
            }
            equal_frame += got.final_color(i, j) == want.final_color(i, j);
        }
    INFO("largest relative difference of the scene " << worst << " (" << one_tap << " texels a shadow-map tap apart); " << equal_frame
                                                     << " of " << kWidth * kHeight << " frame pixels equal; " << in_shadow
                                                     << " scene texels in the liquid's shadow");
    CHECK(scene_failures == 0);
    // The surface refracts the scene (docs/RENDERING.md (R5)): a scene texel a tap apart shows, looked up
    // through the liquid, in a few frame pixels elsewhere too (seed 679104364: one such pixel two
    // steps apart, its own scene texel within the tolerance). None without a tap-apart texel.
    CHECK(frame_failures <= 4 * one_tap);
    // And by no more than a scene difference can make: such a pixel is (R5)'s blend of the scene looked
    // up through the same surface in both frames, R·reflected + (1 − R)·T·scene + highlight, the same
    // but for the scene, with weight (1 − R)·T <= 1 on a bilinear mix of texels; so its linear values
    // differ by at most the largest linear difference of any scene texel (a tap's C_lit/9 and the
    // tolerance). Back from 8 bits through to_display's x^(1/2.2) (glsl/common/frame.glsl): each
    // linear value is known to within 2.2·y^1.2 times a step (the conversion to 8 bits rounds to within
    // one), y the display value a step up.
    int beyond = 0;
    for (const glm::ivec2 p : refracted) {
        const glm::dvec3 a = got.final_color(p.x, p.y) / 255.0, b = want.final_color(p.x, p.y) / 255.0;
        for (int c = 0; c < 3; ++c) {
            auto slack = [](double y) { return 2.2 * std::pow(std::min(1.0, y + 1.0 / 255.0), 1.2) / 255.0; };
            const double diff = std::abs(std::pow(a[c], 2.2) - std::pow(b[c], 2.2));
            if (diff > largest_scene_difference + slack(a[c]) + slack(b[c]) && ++beyond <= 8)
                FAIL_CHECK("pixel (" << p.x << ", " << p.y << ") channel " << c << ": linear " << std::pow(a[c], 2.2) << " against "
                                     << std::pow(b[c], 2.2) << ", more apart than any scene texel (" << largest_scene_difference << ")");
        }
    }
    CHECK(beyond == 0);
    // The liquid's shadow is in the compared scene, and the texels a tap apart are a few of it.
    CHECK(in_shadow > 20);
    CHECK(one_tap <= std::max(4, in_shadow / 25));
}

TEST_CASE("water: the thickness drawn at half size and upsampled stays within the full-size thickness around each pixel") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    int smooth_total = 0;
    for (const bool sunk : {false, true}) {
        INFO((sunk ? "box sunk 5 cm into the floor" : "box above the floor"));
        const Case c(rng, sunk, kFullSizeThickness);
        const auto& [rig, cpu, full] = c;
        const Frame half = render_water(rig, true, render::WaterOptions{true, 2});
        const int hw = (kWidth + 1) / 2, hh = (kHeight + 1) / 2;
        REQUIRE(half.thickness.size() == std::size_t(hw) * std::size_t(hh));
        auto texel = [&](int i, int j) {
            return double(half.thickness[std::size_t(std::clamp(j, 0, hh - 1)) * hw + std::size_t(std::clamp(i, 0, hw - 1))]);
        };
        auto at = [&](int i, int j) {
            const std::size_t k = std::size_t(std::clamp(j, 0, kHeight - 1)) * kWidth + std::size_t(std::clamp(i, 0, kWidth - 1));
            return std::max(0.0, double(full.thickness[k]));
        };
        // What the thickness reads of a ray: the entry and exit faces, whether the opaque scene clips
        // it (not, in part, or wholly), and what the scene is there.
        auto kind = [&](double x, double y) {
            const glm::dvec3 d = cpu.ray(x, y);
            const auto h = chord(cpu.eye(), d, rig.box);
            const Cpu::Opaque o = cpu.opaque(d);
            if (!h) return o.kind - 16;
            const int clip = h->t0 >= o.t ? 2 : h->t1 > o.t ? 1 : 0;
            return ((h->axis * 4 + h->exit_axis) * 3 + clip) * 8 + o.kind;
        };
        int compared = 0, failures = 0, smooth = 0, smooth_failures = 0, off_1cm = 0, liquid = 0, seen_differ = 0;
        double worst_smooth = -1.0, most_curvature = 0.0, sum_sq = 0.0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i) {
                // The upsampling (surface_water.frag): bilinear at (x_w / 2) in the half-size texels.
                const glm::dvec2 g = glm::dvec2((i + 0.5) / 2.0, (j + 0.5) / 2.0) - 0.5, g0 = glm::floor(g), a = g - g0;
                const int x0 = int(g0.x), y0 = int(g0.y);
                const double up = std::max(0.0, glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), a.x),
                                                         glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), a.x), a.y));
                const double want = at(i, j);
                if (up == 0.0 && want == 0.0) continue;
                // The four texels read sample the thickness within 1.5 px of the pixel's centre, each
                // clipped by the mean depth of a 2x2 block within 2 px: away from a jump of the opaque
                // depth (another surface, a tank edge line within 3.9 px) the samples are the chord's
                // values there, and their bilinear mix lies within the range of the full-size thickness
                // over the 5x5 pixels around (a 1 mm margin for the chord's curvature between centres).
                const int o = cpu.opaque(cpu.ray(i + 0.5, j + 0.5)).kind;
                bool continuous = true, same = true;
                const int k = kind(i + 0.5, j + 0.5);
                for (int c = 0; c < 5 && continuous; ++c)
                    continuous = !cpu.near_edge_line(i + (c == 4 ? 0 : (c & 1) * 2 - 1), j + (c == 4 ? 0 : (c >> 1) * 2 - 1));
                double lo = 1e30, hi = -1e30;
                for (int dj = -3; dj <= 4 && continuous; ++dj)
                    for (int di = -3; di <= 4 && continuous; ++di) {
                        const double x = i + di, y = j + dj;
                        continuous = cpu.opaque(cpu.ray(x, y)).kind == o;
                        if (std::abs(di - 0.5) < 3.0 && std::abs(dj - 0.5) < 3.0) same = same && kind(x, y) == k;
                        if (std::abs(di) > 2 || std::abs(dj) > 2) continue;
                        lo = std::min(lo, at(i + di, j + dj)), hi = std::max(hi, at(i + di, j + dj));
                    }
                const glm::dvec3 step = glm::abs(half.final_color(i, j) - full.final_color(i, j));
                liquid += 1, seen_differ += std::max({step.r, step.g, step.b}) > 3.0;
                if (!continuous) continue;
                ++compared;
                sum_sq += (up - want) * (up - want);
                off_1cm += std::abs(up - want) > 0.01;
                if ((up < lo - 1e-3 || up > hi + 1e-3) && ++failures <= 8)
                    FAIL_CHECK("pixel (" << i << ", " << j << "): upsampled " << up << " m, the full size's range around it [" << lo
                                         << ", " << hi << "] m");
                // Where the entry and exit faces and the clipping agree over the whole window the chord is
                // one smooth function of the position, and the two agree to its curvature: bilinear
                // interpolation between samples 2 px apart errs by at most (2 px)²/8 (|t_xx| + |t_yy|),
                // the second derivatives taken as the full size's second differences around the pixel
                // (the largest over its 3x3), plus 1 mm for the rasterisers' own rounding.
                if (same) {
                    ++smooth;
                    double txx = 0.0, tyy = 0.0;
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            const int x = i + di, y = j + dj;
                            txx = std::max(txx, std::abs(at(x + 1, y) - 2.0 * at(x, y) + at(x - 1, y)));
                            tyy = std::max(tyy, std::abs(at(x, y + 1) - 2.0 * at(x, y) + at(x, y - 1)));
                        }
                    const double curvature = 0.5 * (txx + tyy);
                    most_curvature = std::max(most_curvature, curvature);
                    worst_smooth = std::max(worst_smooth, std::abs(up - want) - curvature);
                    if (std::abs(up - want) > 1e-3 + curvature && ++smooth_failures <= 8)
                        FAIL_CHECK("pixel (" << i << ", " << j << ") where the chord is smooth: upsampled " << up << " m, full size "
                                             << want << " m, curvature's allowance " << curvature << " m");
                }
            }
        INFO(compared << " liquid pixels compared, rms difference " << std::sqrt(sum_sq / std::max(compared, 1)) << " m, " << off_1cm
                      << " off by more than 1 cm; " << smooth << " of them where the chord is smooth (largest difference "
                      << worst_smooth << " m beyond the curvature's allowance, which is " << most_curvature << " m at most). In the frame, " << seen_differ << " of " << liquid
                      << " liquid pixels differ by more than 3/255");
        CHECK(failures == 0);
        CHECK(smooth_failures == 0);
        CHECK(compared > 100);
        smooth_total += smooth;
    }
    CHECK(smooth_total > 0);
}
