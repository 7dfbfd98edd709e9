// Spray and foam (render::Renderer::draw_spray, glsl/render/spray.vert, spray.frag) against the CPU:
// random sub-particles of random level and energy drawn over a frame (floor and tank) must
//   - leave every pixel farther than 2 px outside every visible disc exactly as it was (the frame
//     without sub-particles: turbulence off) and change the pixels inside the visible discs (on);
//   - inside a disc (within 0.7 of its radius in pixels, clear of its edge) be the blend
//         out = α·1 + (1 − α)·before,   α = RANRYU_SPRAY_ALPHA·clamp(e/e_min − 1, 0, 1)
//     of white over the frame, with the disc of radius r/2^E centred on the sub-particle's
//     projection (a disc facing the camera projects to a circle about its centre's projection).
// Tolerance 1.5/255: the blend is done in float and stored in 8 bits (0.5 of rounding) on an 8-bit
// `before` (1 of quantisation at most between the CPU's formula and the GPU's).
#include "support/gl_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "render/spray.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "support/read_pixels.h"

namespace {

namespace render = ranryu::render;
namespace gpu = ranryu::gpu;
constexpr int kWidth = 160, kHeight = 120;

struct Sprite {
    glm::vec2 window;   // the centre's projection (pixels)
    double radius_px;
    double alpha;
};

}  // namespace

TEST_CASE("spray: sub-particles are white discs of the CPU's size and opacity, and change the frame only there", "[render]") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    ranryu::scene::Scene scene;
    scene.tank_min = glm::vec3(0.0f);
    scene.tank_max = glm::vec3(1.0f, 0.6f, 1.0f);
    scene.particle_radius = rng.uniform(0.12f, 0.2f);
    // The sub-particles lie between the tank's front wall (z = 1) and the eye: nothing the frame
    // draws (floor, tank edges) is in front of them.
    const render::Camera camera{glm::vec3(0.5f, 0.9f, 2.6f), glm::vec3(0.5f, 0.35f, 1.35f), 40.0f};
    const gpu::FrameParams fp = render::frame_params(scene, camera, kWidth, kHeight);
    const float e_min = std::exp(rng.uniform(-6.0f, 0.0f));

    ranryu::profile::GpuTimer timer;
    const auto shaders = ranryu::shader::FileSource::embedded();
    render::Renderer renderer(shaders, timer, render::Shading::phong, /*subparticles=*/true);
    REQUIRE(renderer.draws_spray());
    renderer.set_frame(fp);
    renderer.set_spray_energy(e_min);

    // Sub-particles whose discs do not overlap on screen; some below e_min (not drawn).
    std::vector<glm::vec4> pos, vel;
    std::vector<Sprite> sprites;
    const glm::dmat4 vp(fp.view_proj), view(fp.view), proj(fp.proj);
    for (int tries = 0; tries < 400 && pos.size() < 12; ++tries) {
        const glm::vec3 p(rng.uniform(0.1f, 0.9f), rng.uniform(0.15f, 0.55f), rng.uniform(1.1f, 1.6f));
        const int level = 1 + int(rng.below(2));
        const float e = e_min * rng.uniform(0.5f, 2.5f);
        const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(p), 1.0);
        const glm::vec2 w(float((0.5 * c.x / c.w + 0.5) * kWidth), float((0.5 * c.y / c.w + 0.5) * kHeight));
        const double depth = -(view * glm::dvec4(glm::dvec3(p), 1.0)).z;
        const double r_px = std::ldexp(double(scene.particle_radius), -level) * proj[1][1] / depth * 0.5 * kHeight;
        if (w.x < r_px + 3 || w.x > kWidth - r_px - 3 || w.y < r_px + 3 || w.y > kHeight - r_px - 3) continue;
        bool clear = true;
        for (const Sprite& s : sprites) clear = clear && glm::length(s.window - w) > s.radius_px + r_px + 6.0;
        if (!clear) continue;
        const double alpha = RANRYU_SPRAY_ALPHA * std::clamp(double(e) / e_min - 1.0, 0.0, 1.0);
        sprites.push_back({w, r_px, alpha});
        pos.emplace_back(p, float(level));
        vel.emplace_back(0.0f, 0.0f, 0.0f, e);
    }
    REQUIRE(sprites.size() >= 4);
    const auto positions = ranryu::gl::Buffer::from<glm::vec4>(pos, GL_STATIC_DRAW, "test.spray.positions");
    const auto velocities = ranryu::gl::Buffer::from<glm::vec4>(vel, GL_STATIC_DRAW, "test.spray.velocities");
    const glm::uvec4 draw(4u, std::uint32_t(pos.size()), 0u, 0u);   // glDrawArraysIndirect, as SubparticleState.draw
    const ranryu::gl::Buffer indirect(sizeof draw, GL_STATIC_DRAW, &draw, "test.spray.indirect");
    const render::SubparticleDraw sub{positions, positions, velocities, indirect, 0};

    ranryu::gl::RenderTarget target(kWidth, kHeight, "spray_test");
    timer.begin_frame();
    renderer.draw(target, positions, velocities, 0);
    timer.end_frame();
    const auto before = ranryu::test::read_rgba(target);   // turbulence off: no sub-particles
    timer.begin_frame();
    renderer.draw(target, positions, velocities, 0);
    renderer.draw_spray(target, sub);
    timer.end_frame();
    const auto after = ranryu::test::read_rgba(target);
    timer.drain();

    std::size_t outside_changed = 0, inside = 0, inside_bad = 0, changed = 0;
    double worst = 0.0;
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
            const glm::vec2 centre(float(i) + 0.5f, float(j) + 0.5f);
            const std::size_t k = 4 * (std::size_t(j) * kWidth + std::size_t(i));
            bool differs = false;
            for (int c = 0; c < 3; ++c) differs = differs || before[k + c] != after[k + c];
            changed += differs;
            const Sprite* in = nullptr;
            bool near = false;
            for (const Sprite& s : sprites) {
                const double d = glm::length(centre - s.window);
                if (s.alpha > 0.0 && d < s.radius_px + 2.0) near = true;
                if (d < 0.7 * s.radius_px) in = &s;
            }
            if (!near) {
                outside_changed += differs;
                continue;
            }
            if (!in || in->alpha == 0.0) continue;
            ++inside;
            for (int c = 0; c < 3; ++c) {
                const double want = 255.0 * in->alpha + (1.0 - in->alpha) * before[k + c];
                const double err = std::abs(double(after[k + c]) - want);
                worst = std::max(worst, err);
                inside_bad += err > 1.5;
            }
        }
    INFO(sprites.size() << " sub-particles; " << inside << " pixels inside visible discs, " << inside_bad
                        << " channels off the blend (worst " << worst << "/255); " << changed << " pixels changed, "
                        << outside_changed << " of them outside the discs");
    CHECK(outside_changed == 0);
    CHECK(inside_bad == 0);
    CHECK(changed > 0);
    if (std::any_of(sprites.begin(), sprites.end(), [](const Sprite& s) { return s.alpha > 0.05 && s.radius_px > 3; }))
        CHECK(inside > 0);
    ranryu::test::require_no_gl_errors();
}
