// The surface's shading modes (glsl/render/surface_*.frag) against CPU evaluations of their formulas.
//
//   - Schlick's approximation against the exact unpolarised dielectric Fresnel reflectance,
//         R = (Rs + Rp) / 2,  Rs = ((n1 cos i − n2 cos t) / (n1 cos i + n2 cos t))²,
//                             Rp = ((n1 cos t − n2 cos i) / (n1 cos t + n2 cos i))²,  n1 sin i = n2 sin t,
//     for air into water (n = 1.333, glsl/render/shading.h): measured (and printed), the deviation is
//     at most 0.0094 for θ ≤ 70°, 0.027 for θ ≤ 75°, and 0.059 over all θ (at θ = 83.8°, where Schlick
//     underestimates the steep rise toward grazing). Checked: < 0.01 up to 70°, < 0.06 everywhere.
//   - The mesh: marching cubes (MarchingCubes::polygonise) of the analytic φ = R − |x − c|,
//     R = 6 node spacings, drawn by render::Renderer (Phong) or with the Fresnel fragment shader's
//     SHOW_FRESNEL variant (its output is R itself, linear), at pixels whose ray meets the analytic
//     sphere with closest approach below 0.95 R (away from the silhouette).
//   - The CPU evaluates the same formula at the analytic hit with the analytic normal. The GPU uses
//     the mesh's interpolated normal instead, which deviates from it by at most
//         ε = ε_v + e/R + d/R + d/D
//     ε_v: the largest angle between a vertex normal (−∇φ by differences) and the analytic normal at
//          that vertex, read back from the mesh;
//     e/R: how far the analytic normal turns across one triangle (e its longest edge);
//     d/R: the hit on the mesh lies d = δ / cos_min from the analytic hit, δ the largest radial
//          distance between mesh and sphere (vertices' |‖x − c‖ − R| plus the sagitta e²/8R), cos_min the
//          smallest cosine between ray and normal at the pixels used (approach < 0.95: 0.312);
//     d/D: the view vector turns by d over the eye distance D (counted as a normal angle: a bound for
//          Phong's r·v, exact for Fresnel's n·v).
//     The test takes the range of the CPU colour over normals within ε of the analytic one (sampled
//     on 8 rings x 48 directions) and allows 3/255 beyond it for Phong (8-bit output, float vs double)
//     and 1.5/255 for R (one rounding to 8 bits). ε is printed; for this mesh (ε_v = 0.31°, e = 1.65 h,
//     δ = 0.0019 m) it is 0.37° + 1.07°/cos θ: 1.4° facing the eye, 3.8° at the outermost pixels.
//   - Phong and Gouraud once more, exactly: against a CPU ray cast of the read-back triangles with
//     the rasteriser's interpolation (see that test); measured within 0.5/255 on llvmpipe.
#include "support/gl_fixture.h"
#include "support/phong.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "render/shading.h"
#include "scene/scene.h"
#include "shader/program.h"
#include "shader/source.h"
#include "shared/bindings.h"
#include "surface/marching_cubes.h"
#include "surface/phi_grid.h"

namespace {

namespace rs = ranryu::surface;
namespace render = ranryu::render;
namespace gpu = ranryu::gpu;
using ranryu::gl::Buffer;

constexpr int kWidth = 160, kHeight = 120;
const glm::dvec3 kCentre(0.5, 0.3, 0.3);
constexpr double kRadius = 0.15, kSpacing = 0.025;   // R = 6 h
constexpr double kMaxApproach = 0.95;
const glm::dvec3 kWaterBase(0.10, 0.35, 0.80);   // glsl/render/surface.vert kWaterBase

double schlick(double cos_i, double n1, double n2) {   // glsl/common/frame.glsl fresnel_schlick
    const double r0 = std::pow((n1 - n2) / (n1 + n2), 2.0);
    return r0 + (1.0 - r0) * std::pow(1.0 - std::clamp(cos_i, 0.0, 1.0), 5.0);
}

double fresnel_exact(double cos_i, double n1, double n2) {
    const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0) return 1.0;   // total internal reflection
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = std::pow((n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t), 2.0);
    const double rp = std::pow((n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i), 2.0);
    return 0.5 * (rs + rp);
}

struct Rig {
    bool ready = (ranryu::test::context(), true);
    ranryu::shader::FileSource shaders = ranryu::shader::FileSource::embedded();
    ranryu::profile::GpuTimer timer{4, 64};
    rs::MarchingCubes mc{shaders, timer, rs::MeshCapacity{glm::uvec3(24), 100'000}};
};
Rig& rig() {
    static Rig r;
    return r;
}

// A scene whose tank holds the eye and the sphere, so no tank edge lies between them.
ranryu::scene::Scene view_scene() {
    ranryu::scene::Scene s;
    s.tank_min = glm::vec3(-0.5f, 0.0f, -0.5f);
    s.tank_max = glm::vec3(1.5f, 1.0f, 1.5f);
    s.light_dir = glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f));
    s.ambient = 0.25f;
    return s;
}
render::Camera view_camera() { return render::Camera{glm::vec3(0.5f, 0.6f, 1.15f), glm::vec3(kCentre), 40.0f}; }

// The mesh of φ = R − |x − c| on a grid 2 nodes beyond the sphere, polygonised on the GPU, and its
// vertices read back (test only).
struct SphereMesh {
    Buffer phi, grid;
    gpu::MeshState state{};
    std::vector<gpu::MeshVertex> vertices;
};
SphereMesh sphere_mesh() {
    Rig& r = rig();
    const unsigned n = 17;
    rs::PhiGrid g{glm::vec3(kCentre - 8.0 * kSpacing), float(kSpacing), glm::uvec3(n), {}};
    g.phi.resize(g.nodes());
    for (unsigned k = 0; k < n; ++k)
        for (unsigned j = 0; j < n; ++j)
            for (unsigned i = 0; i < n; ++i) {
                const glm::uvec3 node(i, j, k);
                g.phi[g.index(node)] = float(kRadius - glm::length(glm::dvec3(g.node(node)) - kCentre));
            }
    gpu::SurfaceGrid sg{};
    sg.origin = glm::vec4(g.origin, g.spacing);
    sg.dims = glm::uvec4(g.dims, std::uint32_t(g.nodes()));
    SphereMesh m{Buffer::from<float>(g.phi, GL_STATIC_DRAW, "test.phi"), Buffer(sizeof sg, GL_STATIC_DRAW, &sg, "test.grid"), {}, {}};
    r.timer.begin_frame();
    r.mc.polygonise(m.phi, m.grid);
    r.timer.end_frame();
    m.state = r.mc.state().read<gpu::MeshState>(1)[0];
    m.vertices = r.mc.vertices().read<gpu::MeshVertex>(m.state.draw.x);
    return m;
}

// The parts of ε (see the header) that the read-back mesh gives.
struct NormalError {
    double vertex = 0.0;   // ε_v / cos(e/R) + η·e/R (rad)
    double depth = 0.0;    // δ (m)
    double eye = 1.0;      // D (m)
    // ε at a pixel whose analytic hit has cos(θ) between ray and normal.
    double at(double cos_theta) const { return vertex + depth / std::max(cos_theta, 1e-3) * (1.0 / kRadius + 1.0 / eye); }
};
NormalError normal_error(const std::vector<gpu::MeshVertex>& v, double eye_distance) {
    double eps_v = 0.0, edge = 0.0, radial = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const glm::dvec3 p(v[i].position), n(v[i].normal);
        const glm::dvec3 a = glm::normalize(p - kCentre);
        eps_v = std::max(eps_v, std::acos(std::clamp(glm::dot(glm::normalize(n), a), -1.0, 1.0)));
        radial = std::max(radial, std::abs(glm::length(p - kCentre) - kRadius));
        const glm::dvec3 q(v[i - i % 3 + (i + 1) % 3].position);
        edge = std::max(edge, glm::length(q - p));
    }
    NormalError e;
    e.vertex = eps_v / std::cos(edge / kRadius) + (radial / kRadius) * (edge / kRadius);
    e.depth = radial + edge * edge / (6.0 * kRadius);
    e.eye = eye_distance;
    WARN("normal error: eps_v " << glm::degrees(eps_v) << " deg, longest edge " << edge << " m, radial " << radial
                                << " m: eps = " << glm::degrees(e.vertex) << " deg + " << glm::degrees(e.at(1.0) - e.vertex)
                                << " deg / cos(theta)");
    return e;
}

// The ray through pixel (i, j)'s centre, as the raster stage samples it.
glm::dvec3 pixel_ray(const gpu::FrameParams& f, int i, int j) {
    const glm::dmat4 inv = glm::inverse(glm::dmat4(f.view_proj));
    const glm::dvec2 ndc(2.0 * (i + 0.5) / kWidth - 1.0, 2.0 * (j + 0.5) / kHeight - 1.0);
    const glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 1.0, 1.0);
    return glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
}

struct Hit {
    glm::dvec3 point, normal, view;
};
// The analytic sphere's front hit, if the ray's closest approach is below kMaxApproach · R.
std::optional<Hit> sphere_hit(const gpu::FrameParams& f, int i, int j) {
    const glm::dvec3 eye(f.eye), dir = pixel_ray(f, i, j), oc = kCentre - eye;
    const double b = glm::dot(dir, oc), d2 = glm::dot(oc, oc) - b * b;
    if (std::sqrt(std::max(d2, 0.0)) >= kMaxApproach * kRadius) return std::nullopt;
    const glm::dvec3 p = eye + (b - std::sqrt(kRadius * kRadius - d2)) * dir;
    return Hit{p, (p - kCentre) / kRadius, -dir};
}

// Normals within `eps` of n: n itself and 8 rings of 48.
std::vector<glm::dvec3> cone(glm::dvec3 n, double eps) {
    const glm::dvec3 side = glm::normalize(glm::cross(n, std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
    const glm::dvec3 up = glm::cross(n, side);
    std::vector<glm::dvec3> out{n};
    for (int ring = 1; ring <= 8; ++ring) {
        const double a = eps * ring / 8.0;
        for (int k = 0; k < 48; ++k) {
            const double phi = 2.0 * std::numbers::pi * k / 48.0;
            out.push_back(std::cos(a) * n + std::sin(a) * (std::cos(phi) * side + std::sin(phi) * up));
        }
    }
    return out;
}

// Phong of glsl/common/frame.glsl, display-encoded, in 0..255 (support/phong.h).
using ranryu::test::phong;

std::vector<std::uint8_t> read_colour(const ranryu::gl::RenderTarget& t) {
    std::vector<std::uint8_t> rgba(std::size_t(kWidth) * kHeight * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.framebuffer());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return rgba;
}

}  // namespace

TEST_CASE("surface shading: Schlick's approximation against the exact Fresnel reflectance of water", "[surface][shading]") {
    const double n1 = RANRYU_IOR_AIR, n2 = RANRYU_IOR_WATER;
    double worst = 0.0, at = 0.0, worst70 = 0.0;
    for (int k = 0; k <= 9000; ++k) {
        const double theta = glm::radians(k * 0.01), c = std::cos(theta);
        const double dev = std::abs(schlick(c, n1, n2) - fresnel_exact(c, n1, n2));
        if (dev > worst) worst = dev, at = k * 0.01;
        if (k <= 7000) worst70 = std::max(worst70, dev);
    }
    INFO("max |Schlick - exact| = " << worst << " at " << at << " deg; up to 70 deg: " << worst70);
    WARN("air->water: max |Schlick - exact| = " << worst << " at theta = " << at << " deg; " << worst70 << " up to 70 deg");
    CHECK(worst70 < 0.01);
    CHECK(worst < 0.06);
    // Both agree at normal incidence (R0 = 0.0204) and grazing incidence (1).
    CHECK(std::abs(schlick(1.0, n1, n2) - 0.020373) < 1e-5);
    CHECK(std::abs(fresnel_exact(1.0, n1, n2) - schlick(1.0, n1, n2)) < 1e-12);
    CHECK(std::abs(fresnel_exact(1e-9, n1, n2) - 1.0) < 1e-6);
}

TEST_CASE("surface shading: per-pixel Phong and the shader's Fresnel on a marching-cubes sphere match the CPU", "[surface][shading]") {
    Rig& r = rig();
    const SphereMesh mesh = sphere_mesh();
    REQUIRE(mesh.state.draw.x > 0);
    REQUIRE(mesh.state.totals.z == 0);
    const ranryu::scene::Scene scene = view_scene();
    const gpu::FrameParams f = render::frame_params(scene, view_camera(), kWidth, kHeight);
    const NormalError error = normal_error(mesh.vertices, glm::length(glm::dvec3(f.eye) - kCentre) - kRadius);
    REQUIRE(error.at(1.0) < glm::radians(3.0));
    const render::SurfaceMesh drawn{r.mc.vertices(), r.mc.state(), rs::MarchingCubes::draw_offset};
    const Buffer none(sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "test.none");

    SECTION("phong") {
        render::Renderer renderer(r.shaders, r.timer, render::Shading::phong);
        renderer.set_frame(f);
        ranryu::gl::RenderTarget target(kWidth, kHeight, "shading_test");
        r.timer.begin_frame();
        renderer.draw(target, none, none, 0, &drawn);
        r.timer.end_frame();
        const auto rgba = read_colour(target);
        int checked = 0;
        double worst = 0.0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i) {
                const auto hit = sphere_hit(f, i, j);
                if (!hit) continue;
                const double eps = error.at(glm::dot(hit->normal, hit->view));
                glm::dvec3 lo(1e9), hi(-1e9);
                for (const glm::dvec3& n : cone(hit->normal, eps)) {
                    const glm::dvec3 c = phong(f, kWaterBase, n, hit->view);
                    lo = glm::min(lo, c);
                    hi = glm::max(hi, c);
                }
                const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
                const glm::dvec3 got(rgba[k], rgba[k + 1], rgba[k + 2]);
                const glm::dvec3 want = phong(f, kWaterBase, hit->normal, hit->view);
                worst = std::max(worst, glm::length(got - want) / std::sqrt(3.0));
                INFO("pixel (" << i << ", " << j << ") got " << got.x << " " << got.y << " " << got.z << ", CPU range ["
                               << lo.x << " " << lo.y << " " << lo.z << "] - [" << hi.x << " " << hi.y << " " << hi.z << "]");
                REQUIRE(glm::all(glm::greaterThanEqual(got, lo - 3.0)));
                REQUIRE(glm::all(glm::lessThanEqual(got, hi + 3.0)));
                ++checked;
            }
        WARN("phong: " << checked << " pixels within the eps-cone range; rms-per-channel deviation from the analytic "
                                     "normal's colour at most " << worst << "/255");
        CHECK(checked > 500);
    }

    SECTION("fresnel") {
        // The Fresnel mode's own fragment shader, in its SHOW_FRESNEL variant (output: R, linear).
        const auto program = ranryu::shader::Program::graphics(r.shaders, "render/surface.vert", "render/surface_fresnel.frag",
                                                               "#define SHOW_FRESNEL\n");
        Buffer frame_ubo(sizeof f, GL_STATIC_DRAW, &f, "test.frame");
        ranryu::gl::VertexArray vao;
        ranryu::gl::RenderTarget target(kWidth, kHeight, "fresnel_test");
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
        glViewport(0, 0, kWidth, kHeight);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        frame_ubo.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
        glBindVertexArray(vao.id());
        glEnableVertexAttribArray(RANRYU_ATTR_MESH_POSITION);
        glEnableVertexAttribArray(RANRYU_ATTR_MESH_NORMAL);
        glVertexAttribFormat(RANRYU_ATTR_MESH_POSITION, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexAttribFormat(RANRYU_ATTR_MESH_NORMAL, 4, GL_FLOAT, GL_FALSE, 16);
        glVertexAttribBinding(RANRYU_ATTR_MESH_POSITION, 0);
        glVertexAttribBinding(RANRYU_ATTR_MESH_NORMAL, 0);
        glBindVertexBuffer(0, r.mc.vertices().id(), 0, sizeof(gpu::MeshVertex));
        program.use();
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, r.mc.state().id());
        glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(rs::MarchingCubes::draw_offset));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
        glBindVertexArray(0);
        glDisable(GL_DEPTH_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        const auto rgba = read_colour(target);

        int checked = 0;
        double r_min = 1.0, r_max = 0.0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i) {
                const auto hit = sphere_hit(f, i, j);
                if (!hit) continue;
                // R depends on n·v alone and falls as it grows: its extremes over the cone are at
                // cos(θ ∓ ε), θ the analytic angle of incidence.
                const double theta = std::acos(std::clamp(glm::dot(hit->normal, hit->view), -1.0, 1.0));
                const double eps = error.at(std::cos(theta));
                const double n1 = RANRYU_IOR_AIR, n2 = RANRYU_IOR_WATER;
                const double lo = schlick(std::cos(std::max(theta - eps, 0.0)), n1, n2);
                const double hi = schlick(std::cos(std::min(theta + eps, std::numbers::pi / 2)), n1, n2);
                const double got = rgba[4 * (std::size_t(j) * kWidth + std::size_t(i))] / 255.0;
                INFO("pixel (" << i << ", " << j << ") theta " << glm::degrees(theta) << " deg: GPU R " << got
                               << ", CPU R " << schlick(std::cos(theta), n1, n2) << " in [" << lo << ", " << hi << "]");
                REQUIRE(got >= lo - 1.5 / 255.0);
                REQUIRE(got <= hi + 1.5 / 255.0);
                r_min = std::min(r_min, got);
                r_max = std::max(r_max, got);
                ++checked;
            }
        WARN("fresnel: " << checked << " pixels, R from " << r_min << " to " << r_max);
        CHECK(checked > 500);
        CHECK(r_max > 0.1);   // grazing pixels were among them
    }
    ranryu::test::require_no_gl_errors();
}

// Phong and Gouraud on the same mesh, against a CPU ray cast of the read-back triangles: the ray
// through a pixel centre meets triangle (x0, x1, x2) at barycentrics (b0, b1, b2) (Möller-Trumbore,
// double), which equal the rasteriser's perspective-correct ones, so
//   Phong:   n = normalize(Σ b_i n_i),  v = normalize(eye − x),  colour = shade_phong(base, n, v)
//   Gouraud: colour = to_display(Σ b_i phong_linear(base, normalize(n_i), normalize(eye − x_i)))
// Both are continuous across shared edges (their vertices and normals are bit-identical), so a pixel
// whose ray lands on the neighbouring triangle of the GPU's choice still agrees. Tolerance 3/255 per
// channel (8-bit output, float vs double), at the pixels of the tests above (approach < 0.95 R).
TEST_CASE("surface shading: Phong and Gouraud on the mesh equal a CPU ray cast of its triangles", "[surface][shading]") {
    Rig& r = rig();
    const SphereMesh mesh = sphere_mesh();
    REQUIRE(mesh.state.draw.x > 0);
    const gpu::FrameParams f = render::frame_params(view_scene(), view_camera(), kWidth, kHeight);
    const render::SurfaceMesh drawn{r.mc.vertices(), r.mc.state(), rs::MarchingCubes::draw_offset};
    const Buffer none(sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "test.none");
    const glm::dvec3 eye(f.eye);

    auto linear = [&](glm::dvec3 n, glm::dvec3 v) {   // phong_linear of common/frame.glsl
        const glm::dvec3 l(f.light_dir);
        const double ndl = glm::dot(n, l);
        const double spec = ndl > 0.0 ? std::pow(std::max(glm::dot(glm::reflect(-l, n), v), 0.0), double(f.material.z)) : 0.0;
        return glm::dvec3(f.light_color) * (double(f.light_color.a) * kWaterBase + double(f.material.x) * std::max(ndl, 0.0) * kWaterBase +
                                            double(f.material.y) * spec);
    };
    auto display = [](glm::dvec3 c) { return 255.0 * glm::pow(glm::clamp(c, 0.0, 1.0), glm::dvec3(1.0 / 2.2)); };

    for (const render::Shading mode : {render::Shading::phong, render::Shading::gouraud}) {
        INFO(render::shading_name(mode));
        render::Renderer renderer(r.shaders, r.timer, mode);
        renderer.set_frame(f);
        ranryu::gl::RenderTarget target(kWidth, kHeight, "shading_test");
        r.timer.begin_frame();
        renderer.draw(target, none, none, 0, &drawn);
        r.timer.end_frame();
        const auto rgba = read_colour(target);
        int checked = 0;
        double worst = 0.0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i) {
                if (!sphere_hit(f, i, j)) continue;
                const glm::dvec3 dir = pixel_ray(f, i, j);
                double best = 1e30;
                glm::dvec3 want(0.0);
                for (std::size_t t = 0; t + 2 < mesh.vertices.size(); t += 3) {
                    const glm::dvec3 x0(mesh.vertices[t].position), x1(mesh.vertices[t + 1].position), x2(mesh.vertices[t + 2].position);
                    const glm::dvec3 e1 = x1 - x0, e2 = x2 - x0, p = glm::cross(dir, e2);
                    const double det = glm::dot(e1, p);
                    if (std::abs(det) < 1e-14) continue;
                    const glm::dvec3 s = eye - x0;
                    const double b1 = glm::dot(s, p) / det;
                    const glm::dvec3 q = glm::cross(s, e1);
                    const double b2 = glm::dot(dir, q) / det, dist = glm::dot(e2, q) / det;
                    if (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0 || dist <= 0.0 || dist >= best) continue;
                    best = dist;
                    const double b[3] = {1.0 - b1 - b2, b1, b2};
                    if (mode == render::Shading::phong) {
                        glm::dvec3 n(0.0);
                        for (int k = 0; k < 3; ++k) n += b[k] * glm::dvec3(mesh.vertices[t + std::size_t(k)].normal);
                        want = display(linear(glm::normalize(n), -dir));
                    } else {
                        glm::dvec3 c(0.0);
                        for (int k = 0; k < 3; ++k) {
                            const glm::dvec3 xk(mesh.vertices[t + std::size_t(k)].position);
                            c += b[k] * linear(glm::normalize(glm::dvec3(mesh.vertices[t + std::size_t(k)].normal)), glm::normalize(eye - xk));
                        }
                        want = display(c);
                    }
                }
                REQUIRE(best < 1e30);
                const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
                const glm::dvec3 got(rgba[k], rgba[k + 1], rgba[k + 2]);
                const glm::dvec3 diff = glm::abs(got - want);
                const double dev = std::max({diff.x, diff.y, diff.z});
                INFO("pixel (" << i << ", " << j << ") got " << got.x << " " << got.y << " " << got.z << ", CPU " << want.x << " "
                               << want.y << " " << want.z);
                REQUIRE(dev <= 3.0);
                worst = std::max(worst, dev);
                ++checked;
            }
        WARN(render::shading_name(mode) << ": " << checked << " pixels; largest deviation from the CPU ray cast " << worst << "/255");
        CHECK(checked > 500);
    }
    ranryu::test::require_no_gl_errors();
}
