// Resource limits (frame/memory.h): the estimate a pipeline is checked against before it allocates
// is within 10 % of what its construction allocated, for each kind of pipeline; the boundary is
// counted as it is sampled; an estimate above the available memory is refused with the spacing
// that fits.
#include "support/gl_fixture.h"

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "frame/memory.h"
#include "frame/pipeline.h"
#include "gl/objects.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/boundary.h"

using namespace ranryu;
using Catch::Matchers::Contains;

namespace {

// Builds the pipeline and compares its estimate with the bytes its construction left allocated.
void check_estimate(const scene::Scene& s, const frame::View& view) {
    test::context();
    const std::uint64_t before = gl::allocated_bytes();
    frame::Pipeline p(s, shader::FileSource::embedded(), view);
    const std::uint64_t allocated = gl::allocated_bytes() - before;
    const double estimate = double(p.memory().estimate.total());
    INFO(s.name << " spacing " << s.spacing << " solver " << scene::solver_name(s.sph.solver) << ": estimated "
                << estimate << " B, allocated " << allocated << " B");
    CHECK(p.memory().allocated == allocated);
    CHECK(estimate >= 0.9 * double(allocated));
    CHECK(estimate <= 1.1 * double(allocated));
    test::require_no_gl_errors();
}

// A view of w x h pixels (and a shading), the rest as View's defaults.
frame::View sized(int w, int h, std::optional<render::Shading> shading = std::nullopt) {
    frame::View v;
    v.width = w;
    v.height = h;
    v.shading = shading;
    return v;
}

}  // namespace

TEST_CASE("memory: the estimate is within 10 % of what a pipeline allocates", "[gl][memory]") {
    SECTION("dam break, DFSPH, its surface") {
        check_estimate(scene::with_spacing(scene::load("dam-break"), 0.01f, "test"), sized(160, 90));
    }
    SECTION("dam break, DFSPH with the boundary rows of (D9) and the Chebyshev iterates of (D10)") {
        scene::Scene s = scene::with_spacing(scene::load("dam-break"), 0.01f, "test");
        s.sph.boundary_rows = true;
        s.sph.chebyshev = 0.95f;
        check_estimate(s, sized(160, 90, render::Shading::particles));
    }
    SECTION("dam break, WCSPH, drawn as particles") {
        scene::Scene s = scene::with_spacing(scene::load("dam-break"), 0.01f, "test");
        s.sph.solver = scene::Solver::wcsph;
        check_estimate(s, sized(160, 90, render::Shading::particles));
    }
    SECTION("turbulent jet: the turbulence force and sub-particles on, its surface") {
        const scene::Scene s = scene::load("turbulent-jet");
        REQUIRE(s.turbulence.enabled());
        REQUIRE(s.turbulence.subparticles.enabled());
        check_estimate(s, sized(160, 90));
    }
    SECTION("falling block: ballistic") { check_estimate(scene::load("falling-block"), sized(160, 90)); }
    SECTION("drop, simulated only (validation)") {
        frame::View v;
        v.draw = false;
        check_estimate(scene::load("drop"), v);
    }
}

TEST_CASE("memory: the boundary count is the size of the sampled boundary", "[gl][memory]") {
    for (const scene::BundledScene& b : scene::bundled()) {
        const scene::Scene s = scene::load(b.name);
        for (int layers : {1, 3}) {
            INFO(b.name << ", " << layers << " layers");
            CHECK(sim::boundary_count(s, layers) == sim::sample_boundary(s, layers).size());
        }
    }
}

TEST_CASE("memory: a scene above the available memory is refused with the spacing that fits", "[gl][memory]") {
    test::context();
    // Drawn as particles: the particle arrays dominate (a surface's level set and mesh do not scale).
    const scene::Scene s = scene::with_spacing(scene::load("dam-break"), 0.004f, "test");
    const frame::View view{160, 90, render::Shading::particles};
    const std::uint64_t need = frame::Pipeline::memory_estimate(s, view).total();
    // Room for half of it: refused, naming the scene, its particles, the estimate and a spacing.
    const frame::DeviceMemory half{need / 2, "test", std::nullopt};
    try {
        frame::check_memory(s, view, half);
        FAIL("not refused");
    } catch (const InputError& e) {
        const std::string m = e.what();
        INFO(m);
        CHECK_THAT(m, Contains("dam-break"));
        CHECK_THAT(m, Contains(std::to_string(s.particle_count()) + " particles"));
        CHECK_THAT(m, Contains(frame::mib(need)));
        CHECK_THAT(m, Contains("--spacing"));
    }
    const auto fit = frame::finest_spacing_within(s, view, std::uint64_t(frame::kMemoryFraction * double(*half.available)));
    REQUIRE(fit);
    CHECK(*fit > s.spacing);
    // At the suggested spacing it fits.
    const scene::Scene at = scene::with_spacing(s, *fit, "test");
    CHECK_NOTHROW(frame::check_memory(at, view, half));
    // Room for it all: accepted.
    CHECK_NOTHROW(frame::check_memory(s, view, frame::DeviceMemory{2 * need, "test", std::nullopt}));
    // A device that says nothing is not checked.
    CHECK_NOTHROW(frame::check_memory(s, view, frame::DeviceMemory{std::nullopt, "nothing", std::nullopt}));
}

TEST_CASE("memory: a scene with more particles than one dispatch reaches is refused with the spacing that does", "[gl][memory]") {
    // A device of 100 workgroups reaches 12,800 particles (kParticleWorkgroup 128): the dam break at
    // 0.01 m (8,000) passes, at 0.005 m (64,000) it is refused, and the spacing named passes.
    ranryu::test::context();
    const frame::View view = sized(64, 48, render::Shading::particles);
    const frame::DeviceMemory device{std::nullopt, "test", 100};
    const scene::Scene coarse = scene::with_spacing(scene::load("dam-break"), 0.01f, "test");
    CHECK_NOTHROW(frame::check_memory(coarse, view, device));
    const scene::Scene fine = scene::with_spacing(scene::load("dam-break"), 0.005f, "test");
    std::string message;
    try {
        frame::check_memory(fine, view, device);
    } catch (const InputError& e) {
        message = e.what();
    }
    INFO(message);
    REQUIRE_FALSE(message.empty());
    CHECK_THAT(message, Catch::Matchers::Contains("64000 particles are more than one dispatch reaches on this device (100 workgroups of 128: 12800 particles)"));
    const std::size_t at = message.find("--spacing ");
    REQUIRE(at != std::string::npos);
    const float dx = std::stof(message.substr(at + 10));
    const scene::Scene fitted = scene::with_spacing(scene::load("dam-break"), dx, "test");
    CHECK(fitted.particle_count() <= 12800);
    CHECK(fitted.particle_count() > 12800 / 2);
    CHECK_NOTHROW(frame::check_memory(fitted, view, device));
}

