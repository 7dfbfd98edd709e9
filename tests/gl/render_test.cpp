// The raster stage (render::Renderer) against a CPU ray caster. Every pixel's ray is cast through
// the pixel centre with the same view and projection (render::frame_params); what it meets first
// is shaded with the formula of glsl/common/frame.glsl:
//     c = L·(k_a·base + k_d·max(n·l, 0)·base + k_s·max(r·v, 0)^s),  r = reflect(−l, n),
//     specular 0 where n·l ≤ 0;  out = clamp(c, 0, 1)^(1/2.2)
// with base = mix((0.10, 0.35, 0.80), (0.85, 0.95, 1.00), clamp(|u| / speed_scale, 0, 1)) for a
// particle (glsl/render/impostor.frag) and the 0.1 m checker 0.62 / 0.42 for the floor
// (glsl/render/floor.frag); a ray that meets nothing keeps the clear colour (0.16, 0.18, 0.22).
// Tolerance: 3/255 per channel (8-bit output; the GPU's interpolated ray differs from the CPU's
// in the last bits; llvmpipe stays within 0.51/255). Sphere pixels also compare the depth buffer.
// Left out, because there the GPU's answer may differ from the CPU's by a whole colour without
// either being wrong: pixels on a silhouette, a checker edge or a light terminator, where two
// spheres are nearly equally near, and where a tank edge (a 1-px line) passes within 3 px and is
// not clearly behind the surface.
#include "support/gl_fixture.h"
#include "support/screen.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/particles.h"

using ranryu::profile::GpuTimer;
using ranryu::shader::FileSource;
namespace gpu = ranryu::gpu;
namespace render = ranryu::render;

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr double kTolerance = 3.0;   // in 1/255
const glm::dvec3 kSlowBase(0.10, 0.35, 0.80), kFastBase(0.85, 0.95, 1.00);
const glm::dvec3 kClear(0.16, 0.18, 0.22);

// The impostors' rasters (render::ImpostorOptions): the draw, the compute raster, and the compute
// raster with room for one large particle in its list (the others done by their own invocations); and
// how far from a pixel's centre each one's eye ray may pass (compare()).
render::ImpostorOptions impostors(render::ImpostorOptions::Raster raster, unsigned capacity = RANRYU_IMPOSTOR_LARGE_CAPACITY) {
    render::ImpostorOptions o;
    o.raster = raster;
    o.large_capacity = capacity;
    return o;
}
const std::pair<render::ImpostorOptions, const char*> kRasters[] = {
    {impostors(render::ImpostorOptions::Raster::draw), "draw"},
    {impostors(render::ImpostorOptions::Raster::compute), "compute"},
    {impostors(render::ImpostorOptions::Raster::compute, 1), "compute, a list of one"}};
double ray_offset(const render::ImpostorOptions& o) { return o.raster == render::ImpostorOptions::Raster::draw ? 0.02 : 0.0; }

struct Image {
    std::vector<std::uint8_t> rgba;
    std::vector<float> depth;
    glm::dvec3 color(int i, int j) const {
        const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
        return {rgba[k], rgba[k + 1], rgba[k + 2]};
    }
    double depth_at(int i, int j) const { return depth[std::size_t(j) * kWidth + std::size_t(i)]; }
};

// A random scene: tank, light, camera looking at a point near the tank's middle from above.
struct Setup {
    ranryu::scene::Scene scene;
    render::Camera camera;
};
Setup random_setup(ranryu::test::Random& rng, float radius) {
    Setup s;
    auto& sc = s.scene;
    sc.tank_min = glm::vec3(rng.uniform(-0.3f, 0.3f), rng.uniform(-0.2f, 0.2f), rng.uniform(-0.3f, 0.3f));
    sc.tank_max = sc.tank_min + glm::vec3(rng.uniform(0.8f, 1.2f), rng.uniform(0.6f, 1.0f), rng.uniform(0.5f, 0.9f));
    sc.gravity = glm::vec3(0.0f, -rng.uniform(5.0f, 15.0f), 0.0f);
    sc.particle_radius = radius;
    const glm::vec3 mid = 0.5f * (sc.tank_min + sc.tank_max);
    s.camera.target = glm::vec3(mid.x, sc.tank_min.y + 0.3f, mid.z) + glm::vec3(rng.uniform(-0.1f, 0.1f), 0.0f, rng.uniform(-0.1f, 0.1f));
    const float az = rng.uniform(0.0f, 6.2831853f), el = glm::radians(rng.uniform(12.0f, 35.0f));
    const float dist = rng.uniform(1.8f, 2.4f);
    s.camera.eye = s.camera.target + dist * glm::vec3(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    // Light from above (the floor is lit), elevation 35°..80°, within 60° of the camera's azimuth:
    // n·l ≥ 0.19 where a sphere faces the camera, so its centre pixel is never on the terminator.
    const float la = az + glm::radians(rng.uniform(-60.0f, 60.0f)), le = glm::radians(rng.uniform(35.0f, 80.0f));
    sc.light_dir = glm::vec3(std::cos(le) * std::cos(la), std::sin(le), std::cos(le) * std::sin(la));
    sc.ambient = rng.uniform(0.1f, 0.35f);
    s.camera.fov_deg = 40.0f;
    return s;
}

// Renders `positions` (with `velocities`) into a fresh target with the impostors' raster `raster`
// and reads colour and depth back.
Image render_particles(const Setup& s, const gpu::FrameParams& fp, const std::vector<glm::vec4>& positions,
                       const std::vector<glm::vec4>& velocities, render::ImpostorOptions raster) {
    GpuTimer timer;
    ranryu::sim::Particles particles(FileSource::embedded(), timer);
    render::Renderer renderer(FileSource::embedded(), timer, render::Shading::particles, false, false, {}, raster);
    particles.reset(positions, velocities);
    particles.set_params(ranryu::sim::sim_params(s.scene, positions.size()));
    renderer.set_frame(fp);
    renderer.resize(kWidth, kHeight);
    ranryu::gl::RenderTarget target(kWidth, kHeight, "render_test");
    timer.begin_frame();
    renderer.draw(target, particles.positions(), particles.velocities(), particles.count());
    timer.end_frame();

    Image img;
    img.rgba.resize(std::size_t(kWidth) * kHeight * 4);
    img.depth.resize(std::size_t(kWidth) * kHeight);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    glReadPixels(0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT, img.depth.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    timer.drain();
    return img;
}

// The CPU side: rays, hits and shading in double precision.
class Caster {
public:
    explicit Caster(const gpu::FrameParams& f) : f_(f), screen_{glm::dmat4(f.view_proj), kWidth, kHeight} {}

    glm::dvec3 eye() const { return glm::dvec3(f_.eye); }

    // The unit direction of the ray through window position (x, y) (pixel centres at +½).
    glm::dvec3 ray(double x, double y) const { return screen_.ray(x, y); }

    // Window position of a world point.
    glm::dvec2 window(glm::dvec3 p) const { return screen_.window(p); }

    // Depth-buffer value of a world point: 0.5·z_ndc + 0.5, as impostor.frag writes it.
    double depth(glm::dvec3 p) const {
        const glm::dvec4 c = glm::dmat4(f_.proj) * glm::dmat4(f_.view) * glm::dvec4(p, 1.0);
        return 0.5 * c.z / c.w + 0.5;
    }

    // How far a world point lies in front of the eye along its view direction (−z in view space), and
    // the near plane's distance (glm::perspective: P[3][2]/(P[2][2] − 1)).
    double view_depth(glm::dvec3 p) const { return -(glm::dmat4(f_.view) * glm::dvec4(p, 1.0)).z; }
    double near_plane() const { return double(f_.proj[3][2]) / (double(f_.proj[2][2]) - 1.0); }

    // Distance along `dir` to the front of the sphere (c, r), and the ray's closest approach to c
    // in units of r (< 1: it hits; near 1: the silhouette).
    struct SphereHit {
        double t;
        double approach;
    };
    SphereHit sphere(glm::dvec3 dir, glm::dvec3 c, double r) const {
        const glm::dvec3 oc = c - eye();
        const double b = glm::dot(dir, oc);
        const double d2 = glm::dot(oc, oc) - b * b;
        const double approach = std::sqrt(std::max(d2, 0.0)) / r;
        const double t = approach < 1.0 ? b - std::sqrt(r * r - d2) : -1.0;
        return {t, approach};
    }

    // Phong of glsl/common/frame.glsl, in 0..255, and n·l (to keep clear of the terminator).
    glm::dvec3 shade(glm::dvec3 base, glm::dvec3 n, glm::dvec3 v, double* ndl_out = nullptr) const {
        const glm::dvec3 l(f_.light_dir);
        const double ndl = glm::dot(n, l);
        if (ndl_out) *ndl_out = ndl;
        const double diffuse = std::max(ndl, 0.0);
        const double specular =
            ndl > 0.0 ? std::pow(std::max(glm::dot(glm::reflect(-l, n), v), 0.0), double(f_.material.z)) : 0.0;
        const glm::dvec3 c = glm::dvec3(f_.light_color) * (double(f_.light_color.a) * base +
                                                          double(f_.material.x) * diffuse * base +
                                                          double(f_.material.y) * specular);
        return 255.0 * glm::pow(glm::clamp(c, 0.0, 1.0), glm::dvec3(1.0 / 2.2));
    }

    glm::dvec3 particle_base(glm::dvec3 velocity) const {
        const double s = std::clamp(glm::length(velocity) / std::max(double(f_.speed_scale.x), 1e-6), 0.0, 1.0);
        return glm::mix(kSlowBase, kFastBase, s);
    }

    // The floor plane y = tank_min.y: where the ray meets it inside the floor quad (the tank's
    // footprint grown by max(size.x, size.z) on each side, glsl/render/floor.vert), if it does.
    std::optional<glm::dvec3> floor_hit(glm::dvec3 dir) const {
        const double y = f_.tank_min.y;
        if (dir.y >= 0.0) return std::nullopt;
        const double t = (y - eye().y) / dir.y;
        if (t <= 0.0) return std::nullopt;
        const glm::dvec3 p = eye() + t * dir;
        const glm::dvec3 size = glm::dvec3(f_.tank_max) - glm::dvec3(f_.tank_min);
        const double margin = std::max(size.x, size.z);
        if (p.x < f_.tank_min.x - margin || p.x > f_.tank_max.x + margin || p.z < f_.tank_min.z - margin ||
            p.z > f_.tank_max.z + margin)
            return std::nullopt;
        return p;
    }
    // The floor's 0.1 m checker cell of a point (glsl/render/floor.frag).
    static glm::ivec2 checker_cell(glm::dvec3 p) { return {int(std::floor(p.x / 0.1)), int(std::floor(p.z / 0.1))}; }

    double distance(glm::dvec3 p) const { return glm::length(p - eye()); }
    const gpu::FrameParams& params() const { return f_; }

private:
    const gpu::FrameParams& f_;
    ranryu::test::Screen screen_;
};

// The tank's 12 edges are drawn as 1-px lines with depth test. Per pixel: the eye distance of the
// nearest edge point whose projection lies within 3 px (infinity if none). The edges are sampled
// finer than a pixel. A pixel is left out where an edge is not clearly behind its surface.
class EdgeMap {
public:
    explicit EdgeMap(const Caster& cast) : nearest_(std::size_t(kWidth) * kHeight, kInf) {
        const glm::dvec3 lo(cast.params().tank_min), hi(cast.params().tank_max);
        auto corner = [&](int k) { return glm::dvec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z); };
        constexpr int kSamples = 1024;
        for (int a = 0; a < 8; ++a)
            for (int bit = 1; bit < 8; bit <<= 1) {
                if (a & bit) continue;
                for (int k = 0; k <= kSamples; ++k) {
                    const glm::dvec3 p = glm::mix(corner(a), corner(a | bit), double(k) / kSamples);
                    const glm::dvec2 w = cast.window(p);
                    const double d = cast.distance(p);
                    for (int j = int(w.y) - 4; j <= int(w.y) + 4; ++j)
                        for (int i = int(w.x) - 4; i <= int(w.x) + 4; ++i) {
                            if (i < 0 || j < 0 || i >= kWidth || j >= kHeight) continue;
                            if (glm::length(glm::dvec2(i + 0.5, j + 0.5) - w) > 3.0) continue;
                            double& n = nearest_[std::size_t(j) * kWidth + std::size_t(i)];
                            n = std::min(n, d);
                        }
                }
            }
    }
    // Whether a surface at eye distance `t` at pixel (i, j) is clear of tank edges: none nearby,
    // or all at least 1 cm behind it (hidden by the depth test).
    bool clear(int i, int j, double t) const { return nearest_[std::size_t(j) * kWidth + std::size_t(i)] > t + 0.01; }
    // Whether no edge within the disc of radius `extent` (m) around `centre` (on screen, grown by
    // 3 px) is nearer than `depth`: such an edge would be drawn over the spheres there.
    bool nothing_in_front(const Caster& cast, glm::dvec3 centre, double extent, double depth) const {
        const double focal = 0.5 * kHeight / std::tan(0.5 * glm::radians(40.0));
        const double radius_px = extent * focal / cast.distance(centre) + 3.0;
        const glm::dvec2 c = cast.window(centre);
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i)
                if (glm::length(glm::dvec2(i + 0.5, j + 0.5) - c) <= radius_px &&
                    nearest_[std::size_t(j) * kWidth + std::size_t(i)] < depth)
                    return false;
        return true;
    }

private:
    static constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> nearest_;
};

struct Sphere {
    glm::dvec3 centre;
    glm::dvec3 velocity;
};

// Where the ray `dir` meets the plane of the impostor quad of the sphere centred at c: the plane
// through c facing the eye.
glm::dvec3 quad_point(const Caster& cast, glm::dvec3 dir, glm::dvec3 c) {
    const glm::dvec3 axis = glm::normalize(c - cast.eye());
    return cast.eye() + dir * (glm::dot(c - cast.eye(), axis) / glm::dot(dir, axis));
}

// What the CPU expects at one pixel, or nothing where the pixel is ambiguous (see the top).
struct Expected {
    enum Kind { sphere, floor, background } kind;
    glm::dvec3 color;               // 0..255
    std::optional<double> depth;    // checked for spheres
    int sphere_index = -1;
    double approach = 0.0;          // for spheres: closest approach / r
    double quad_depth = 0.0;        // for spheres: depth of the impostor quad's plane here
    double depth_slope = 0.0;       // for spheres: the largest change of its depth a pixel along x or y here
};
std::optional<Expected> expect_pixel(const Caster& cast, const EdgeMap& edges, const std::vector<Sphere>& spheres,
                                     double r, int i, int j) {
    const double x = i + 0.5, y = j + 0.5;
    const glm::dvec3 dir = cast.ray(x, y);

    int nearest = -1, at_zero = 0;
    double t_near = 1e30, t_second = 1e30, approach = 0.0;
    for (std::size_t k = 0; k < spheres.size(); ++k) {
        const auto h = cast.sphere(dir, spheres[k].centre, r);
        if (h.approach > 0.95 && h.approach < 1.05) return std::nullopt;   // silhouette
        if (h.approach >= 1.0) continue;
        // The draw's quad is clipped at the near plane: its fragment here exists where the quad's point
        // on this ray lies beyond it (left out within 1 % of the near plane's distance, the clip's edge).
        const double clip = cast.view_depth(quad_point(cast, dir, spheres[k].centre)) / cast.near_plane();
        if (clip > 0.99 && clip < 1.01) return std::nullopt;
        if (clip <= 1.0) continue;
        // A front nearer than the near plane writes depth 0 (below): two such tie, and either is drawn.
        if (cast.depth(cast.eye() + h.t * dir) <= 1e-6) ++at_zero;
        if (h.t < t_near) {
            t_second = t_near;
            t_near = h.t;
            nearest = int(k);
            approach = h.approach;
        } else {
            t_second = std::min(t_second, h.t);
        }
    }
    if (nearest >= 0) {
        if (t_second - t_near < 0.02 * r) return std::nullopt;   // where two spheres meet
        if (at_zero > 1) return std::nullopt;
        if (!edges.clear(i, j, t_near)) return std::nullopt;
        const Sphere& s = spheres[std::size_t(nearest)];
        const glm::dvec3 p = cast.eye() + t_near * dir;
        double ndl = 0.0;
        // The front's depth, clamped to ≥ 0 where the near plane cuts the sphere in front of it (written
        // as gl_FragDepth, clamped to the depth range).
        Expected e{Expected::sphere, cast.shade(cast.particle_base(s.velocity), (p - s.centre) / r, -dir, &ndl),
                   std::max(cast.depth(p), 0.0), nearest, approach, 0.0};
        if (std::abs(ndl) < 0.02) return std::nullopt;   // terminator: the specular term switches off there
        // The sphere's depth 1/100 pixel away along x and along y, by a hundred: its slope here.
        for (const glm::dvec2 step : {glm::dvec2(0.01, 0.0), glm::dvec2(0.0, 0.01)}) {
            const glm::dvec3 d = cast.ray(x + step.x, y + step.y);
            const auto h = cast.sphere(d, s.centre, r);
            if (h.approach >= 1.0) continue;
            const double depth = std::max(cast.depth(cast.eye() + h.t * d), 0.0);   // clamped, as written
            e.depth_slope = std::max(e.depth_slope, 100.0 * std::abs(depth - *e.depth));
        }
        e.quad_depth = cast.depth(quad_point(cast, dir, s.centre));
        return e;
    }
    // No sphere: the floor, if the pixel centre and its four corners meet it in one checker cell.
    const auto centre_hit = cast.floor_hit(dir);
    int corners_on_floor = 0;
    bool same_cell = true;
    for (int c = 0; c < 4; ++c) {
        const auto h = cast.floor_hit(cast.ray(i + double(c & 1), j + double(c >> 1)));
        if (!h) continue;
        ++corners_on_floor;
        same_cell = same_cell && centre_hit && Caster::checker_cell(*h) == Caster::checker_cell(*centre_hit);
    }
    if (centre_hit && corners_on_floor == 4 && same_cell && edges.clear(i, j, cast.distance(*centre_hit))) {
        const glm::ivec2 cell = Caster::checker_cell(*centre_hit);
        const bool even = ((cell.x + cell.y) & 1) == 0;
        const glm::dvec3 albedo(even ? 0.62 : 0.42);
        return Expected{Expected::floor, cast.shade(albedo, {0.0, 1.0, 0.0}, glm::normalize(cast.eye() - *centre_hit)),
                        std::nullopt, -1, 0.0, 0.0};
    }
    if (!centre_hit && corners_on_floor == 0 && edges.clear(i, j, 1e300))
        return Expected{Expected::background, 255.0 * kClear, std::nullopt, -1, 0.0, 0.0};
    return std::nullopt;
}

std::string describe(const glm::dvec3& c) {
    std::ostringstream s;
    s << "(" << c.r << ", " << c.g << ", " << c.b << ")";
    return s.str();
}

// Counts of the pixels compared, by what they show.
struct Tally {
    int sphere = 0, limb = 0, floor = 0, background = 0;
    int failures = 0;
    std::vector<int> per_sphere;
    bool centre_checked = false;
};

// Compares every unambiguous pixel with the CPU, colour and (spheres) depth.
// `ray_offset`: how far (pixels) the raster's eye ray may pass from the pixel's centre (below).
Tally compare(const Image& img, const Caster& cast, const std::vector<Sphere>& spheres, double r, double ray_offset,
              const std::function<void(const Expected&, int, int)>& extra = {}) {
    Tally tally;
    tally.per_sphere.assign(spheres.size(), 0);
    const EdgeMap edges(cast);
    const glm::dvec2 centre_px = cast.window(spheres[0].centre);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const auto e = expect_pixel(cast, edges, spheres, r, i, j);
            if (!e) continue;
            const glm::dvec3 got = img.color(i, j);
            const double err = std::max({std::abs(got.r - e->color.r), std::abs(got.g - e->color.g),
                                         std::abs(got.b - e->color.b)});
            bool ok = err <= kTolerance;
            // Depth: impostor.frag writes the front surface's 0.5·z_ndc + 0.5. Near 1, a 32-bit
            // float depth resolves 6e-8, and a float ray's error (~1e-6 of the ~2 m distance)
            // moves depth by near/d²·Δd ≈ 5e-9; llvmpipe stays within 1.1e-7. 1e-6 allows ten
            // times that, and is 25 times less than the 0.1 r (≥ 1 cm) gap of the occlusion case.
            // The draw's ray is the quad's interpolated point, whose corners the raster snaps to
            // 1/256 pixel: its ray may pass up to ~1/512 pixel off the centre's, so its depth may
            // also differ by the sphere's depth change over `ray_offset` = 0.02 pixel (ten times
            // that): on a sphere 0.25 m from the eye some 1e-5, where the H200's draw was 2e-6 off.
            // The compute raster casts the centre's own ray (offset 0): within 1e-6 on the H200.
            if (ok && e->depth) ok = std::abs(img.depth_at(i, j) - *e->depth) <= 1e-6 + ray_offset * e->depth_slope;
            const char* kind = e->kind == Expected::sphere ? "sphere" : e->kind == Expected::floor ? "floor" : "background";
            if (!ok && ++tally.failures <= 8) {
                FAIL_CHECK("pixel (" << i << ", " << j << ") " << kind << ": GPU " << describe(got) << " depth "
                                     << img.depth_at(i, j) << ", CPU " << describe(e->color) << " depth "
                                     << (e->depth ? *e->depth : -1.0));
            }
            if (e->kind == Expected::sphere) {
                ++tally.sphere;
                ++tally.per_sphere[std::size_t(e->sphere_index)];
                if (e->approach >= 0.8) ++tally.limb;
                if (e->sphere_index == 0 && int(std::floor(centre_px.x)) == i && int(std::floor(centre_px.y)) == j)
                    tally.centre_checked = true;
            } else if (e->kind == Expected::floor) {
                ++tally.floor;
            } else {
                ++tally.background;
            }
            if (extra) extra(*e, i, j);
        }
    return tally;
}

}  // namespace

TEST_CASE("render: a particle sphere, the floor and the background match a CPU ray caster") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float r = rng.uniform(0.09f, 0.14f);
    // At rest (base (0.10, 0.35, 0.80)), near the camera's target, clear of the floor, and with no
    // tank edge in front of it (drawn again until so: such an edge may hide the centre pixel).
    Setup s;
    gpu::FrameParams fp;
    glm::vec3 c;
    int tries = 0;
    do {
        REQUIRE(++tries < 200);
        s = random_setup(rng, r);
        fp = render::frame_params(s.scene, s.camera, kWidth, kHeight);
        c = s.camera.target + glm::vec3(rng.uniform(-0.1f, 0.1f), rng.uniform(0.0f, 0.15f), rng.uniform(-0.1f, 0.1f));
    } while (!EdgeMap(Caster(fp)).nothing_in_front(Caster(fp), glm::dvec3(c), r,
                                                   glm::length(glm::dvec3(c) - glm::dvec3(fp.eye)) + r));
    const Caster cast(fp);
    const std::vector<Sphere> spheres = {{glm::dvec3(c), glm::dvec3(0.0)}};
    // The sphere's silhouette holds more than RANRYU_IMPOSTOR_LARGE_PIXELS pixels (some 10 px in
    // radius): the compute raster's second dispatch draws it, or with no room in its list its own
    // invocation.
    for (const auto& [raster, name] : kRasters) {
        INFO("impostors: " << name);
        const Image img = render_particles(s, fp, {glm::vec4(c, 1.0f)}, {glm::vec4(0.0f)}, raster);
        const Tally t = compare(img, cast, spheres, r, ray_offset(raster));
        INFO("compared: " << t.sphere << " sphere pixels (" << t.limb << " near the limb), " << t.floor << " floor, "
                          << t.background << " background");
        // The named pixels were all among those compared: the sphere's centre, its limb (closest
        // approach ≥ 0.8 r), the floor away from the sphere, and the background.
        CHECK(t.centre_checked);
        CHECK(t.limb > 0);
        CHECK(t.floor > 0);
        CHECK(t.background > 0);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("render: impostor depth lets the nearer of two intersecting spheres occlude the other") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float r = rng.uniform(0.1f, 0.14f);
    Setup s;
    gpu::FrameParams fp;
    int tries = 0;
    bool clear = false;
    do {
        REQUIRE(++tries < 200);
        s = random_setup(rng, r);
        fp = render::frame_params(s.scene, s.camera, kWidth, kHeight);
        const glm::dvec3 a = glm::dvec3(s.camera.target) + glm::dvec3(0.0, 0.1, 0.0);
        clear = EdgeMap(Caster(fp)).nothing_in_front(Caster(fp), a, 2.0 * r, glm::length(a - glm::dvec3(fp.eye)) + 2.0 * r);
    } while (!clear);
    const Caster cast(fp);
    // A (at rest, blue) in front; B (fast, white) 0.5 r further along the view ray and 0.8 r to a
    // random side. Where the ray through A's centre meets B, B's surface lies 0.1 r in front of
    // A's impostor quad but 0.9 r behind A's surface: only the written sphere depth hides it.
    const glm::dvec3 a = glm::dvec3(s.camera.target) + glm::dvec3(0.0, 0.1, 0.0);
    const glm::dvec3 axis = glm::normalize(a - cast.eye());
    glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0.0, 1.0, 0.0)));
    const double phi = rng.uniform(0.0f, 6.2831853f);
    side = std::cos(phi) * side + std::sin(phi) * glm::cross(side, axis);
    const glm::dvec3 b = a + 0.5 * r * axis + 0.8 * r * side;
    const double fast = 2.0 * fp.speed_scale.x;
    const std::vector<Sphere> spheres = {{a, glm::dvec3(0.0)}, {b, glm::dvec3(fast, 0.0, 0.0)}};

    for (const bool a_first : {true, false}) {
        INFO((a_first ? "A drawn first" : "B drawn first"));
        std::vector<glm::vec4> x = {glm::vec4(glm::vec3(a), 1.0f), glm::vec4(glm::vec3(b), 1.0f)};
        std::vector<glm::vec4> u = {glm::vec4(0.0f), glm::vec4(float(fast), 0.0f, 0.0f, 0.0f)};
        if (!a_first) {
            std::swap(x[0], x[1]);
            std::swap(u[0], u[1]);
        }
        for (const auto& [raster, name] : kRasters) {
        INFO("impostors: " << name);
        const Image img = render_particles(s, fp, x, u, raster);
        // Pixels where A is nearest but B's surface is in front of A's quad plane.
        int hidden_by_depth = 0;
        const Tally t = compare(img, cast, spheres, r, ray_offset(raster), [&](const Expected& e, int i, int j) {
            if (e.kind != Expected::sphere || e.sphere_index != 0) return;
            const auto hb = cast.sphere(cast.ray(i + 0.5, j + 0.5), b, r);
            if (hb.approach < 1.0 && cast.depth(cast.eye() + hb.t * cast.ray(i + 0.5, j + 0.5)) < e.quad_depth)
                ++hidden_by_depth;
        });
        INFO("compared: A " << t.per_sphere[0] << ", B " << t.per_sphere[1] << " pixels; " << hidden_by_depth
                            << " of A's where B is in front of A's quad");
        // Both spheres were seen, and the case that needs per-pixel depth occurred.
        CHECK(t.per_sphere[0] > 0);
        CHECK(t.per_sphere[1] > 0);
        CHECK(t.centre_checked);
        CHECK(hidden_by_depth > 0);
        }
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("render: a cloud of impostors, small and large, matches the CPU ray caster with either raster") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float r = rng.uniform(0.015f, 0.025f);
    const Setup s = random_setup(rng, r);
    const gpu::FrameParams fp = render::frame_params(s.scene, s.camera, kWidth, kHeight);
    const Caster cast(fp);
    // Spheres along the rays through random pixels, 0.25 to 2 m from the eye and above the floor: from
    // about 1.5 px in radius to some 13, whose bounding boxes hold more than RANRYU_IMPOSTOR_LARGE_PIXELS pixels.
    const double focal = 0.5 * kHeight / std::tan(0.5 * glm::radians(40.0));
    std::vector<Sphere> spheres;
    std::vector<glm::vec4> x, u;
    int large = 0, small = 0;
    while (spheres.size() < 160) {
        const glm::dvec3 dir = cast.ray(rng.uniform(0.0f, float(kWidth)), rng.uniform(0.0f, float(kHeight)));
        const double dist = rng.uniform(0.25f, 2.0f);
        const glm::dvec3 c = cast.eye() + dist * dir;
        if (c.y - r < double(fp.tank_min.y) + 0.01) continue;   // clear of the floor, which the caster does not hide spheres behind
        const glm::dvec3 v(rng.uniform(-3.0f, 3.0f), rng.uniform(-3.0f, 3.0f), rng.uniform(-3.0f, 3.0f));
        spheres.push_back({c, v});
        x.emplace_back(glm::vec3(c), 1.0f);
        u.emplace_back(glm::vec3(v), 0.0f);
        const double box = 2.0 * r * focal / dist + 1.0;   // the silhouette's box, pixels a side
        (box * box > RANRYU_IMPOSTOR_LARGE_PIXELS ? large : small) += 1;
    }
    INFO(large << " spheres with large boxes, " << small << " small");
    REQUIRE(large > 1);
    REQUIRE(small > 10);
    for (const auto& [raster, name] : kRasters) {
        INFO("impostors: " << name);
        const Image img = render_particles(s, fp, x, u, raster);
        const Tally t = compare(img, cast, spheres, r, ray_offset(raster));
        const auto seen = std::count_if(t.per_sphere.begin(), t.per_sphere.end(), [](int n) { return n > 0; });
        INFO("compared: " << t.sphere << " sphere pixels of " << seen << " spheres, " << t.floor << " floor, " << t.background
                          << " background");
        CHECK(t.failures == 0);
        CHECK(seen > 40);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("render: spheres the near plane cuts are drawn where their quads lie beyond the near plane, by either raster") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // Two spheres, each centred d = 1.02–1.04 n from the eye (n = 0.01 m, the near plane:
    // render::frame_params) with a radius of 0.5–0.8 d (the eye outside it, its front nearer than n),
    // 12–18° off the view axis, the second 30–60° around it from the first: each fills the view,
    // and its quad's plane, tilted to the near plane, meets it on the screen. Where a ray meets a quad
    // beyond n the pixel shows that sphere's front (its depth clamped to 0: the front is nearer than n
    // everywhere here); where it meets neither quad beyond n, what lies behind them. Both are large
    // (their boxes fill the target), so with a list of one the compute raster's first dispatch draws one
    // of them itself and the list's dispatch the other.
    const double n = 0.01;
    const double d0 = n * double(rng.uniform(1.02f, 1.04f)), d1 = n * double(rng.uniform(1.02f, 1.04f));
    const float r = float(std::min(d0, d1)) * rng.uniform(0.5f, 0.8f);
    const Setup s = random_setup(rng, r);
    const gpu::FrameParams fp = render::frame_params(s.scene, s.camera, kWidth, kHeight);
    const Caster cast(fp);
    REQUIRE(std::abs(cast.near_plane() - n) < 1e-6 * n);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(s.camera.target) - cast.eye());
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 up = glm::cross(right, forward);
    // The quads are clipped on the side each sphere leans to: towards the floor (within 30° of straight
    // down, between the two), where more of what lies behind is clear of the tank's edges to compare.
    const double spread = glm::radians(double(rng.uniform(30.0f, 60.0f)));
    const double phi = glm::radians(-90.0 + double(rng.uniform(-30.0f, 30.0f))) - 0.5 * spread;
    const double phis[2] = {phi, phi + spread};
    std::vector<Sphere> spheres;
    std::vector<glm::vec4> x, u;
    for (int k = 0; k < 2; ++k) {
        const double off = glm::radians(double(rng.uniform(12.0f, 18.0f)));
        const glm::dvec3 axis = std::cos(off) * forward + std::sin(off) * (std::cos(phis[k]) * right + std::sin(phis[k]) * up);
        const glm::dvec3 c = cast.eye() + (k == 0 ? d0 : d1) * axis;
        const glm::dvec3 v(rng.uniform(-3.0f, 3.0f), rng.uniform(-3.0f, 3.0f), rng.uniform(-3.0f, 3.0f));
        REQUIRE(cast.view_depth(c) - r < n);
        REQUIRE(glm::length(c - cast.eye()) > 1.01 * r);
        spheres.push_back({c, v});
        x.emplace_back(glm::vec3(c), 1.0f);
        u.emplace_back(glm::vec3(v), 0.0f);
    }
    // The pixels where one sphere alone has its quad's point beyond n (where both have, their fronts
    // tie at depth 0 and either may be drawn), and those whose rays meet a sphere but neither quad
    // beyond n: each clear of the clip's edge.
    int shown[2] = {0, 0}, clipped = 0;
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const glm::dvec3 dir = cast.ray(i + 0.5, j + 0.5);
            int drawn = 0, which = -1, hit = 0;
            for (int k = 0; k < 2; ++k) {
                if (cast.sphere(dir, spheres[std::size_t(k)].centre, r).approach >= 0.95) continue;
                ++hit;
                if (cast.view_depth(quad_point(cast, dir, spheres[std::size_t(k)].centre)) > 1.01 * n) ++drawn, which = k;
            }
            if (drawn == 1) ++shown[which];
            else if (drawn == 0 && hit > 0) ++clipped;
        }
    INFO(shown[0] << " and " << shown[1] << " pixels show the spheres, " << clipped << " neither");
    REQUIRE(shown[0] > 200);
    REQUIRE(shown[1] > 200);
    REQUIRE(clipped > 200);
    for (const auto& [raster, name] : kRasters) {
        INFO("impostors: " << name);
        const Image img = render_particles(s, fp, x, u, raster);
        int clipped_compared = 0;
        const Tally t = compare(img, cast, spheres, r, ray_offset(raster), [&](const Expected& e, int i, int j) {
            const glm::dvec3 dir = cast.ray(i + 0.5, j + 0.5);
            if (e.kind != Expected::sphere && (cast.sphere(dir, spheres[0].centre, r).approach < 1.0 ||
                                               cast.sphere(dir, spheres[1].centre, r).approach < 1.0))
                ++clipped_compared;
        });
        INFO("compared: " << t.per_sphere[0] << " and " << t.per_sphere[1] << " sphere pixels, " << clipped_compared
                          << " behind their clipped parts, " << t.floor << " floor, " << t.background << " background");
        CHECK(t.failures == 0);
        CHECK(t.per_sphere[0] > 100);
        CHECK(t.per_sphere[1] > 100);
        CHECK(clipped_compared > 5);   // 26 to about 1,000 over 44 seeds on llvmpipe: the floor clear of the tank's edges
    }
    ranryu::test::require_no_gl_errors();
}
