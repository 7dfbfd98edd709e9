#include <catch2/catch.hpp>

#include <numbers>
#include <random>

#include "scene/scene.h"
#include "sim/fluid.h"

// sim::sph_params: the kernel's support and the constants of docs/SPH.md eq. (1) that the fluid's walks
// read from SphParams instead of deriving them from h every pair (glsl/sim/fluid/fluid.glsl kernel_w(r),
// kernel_grad(d, r); docs/PERFORMANCE.md "The kernel's constants as operands").
TEST_CASE("sph_params: h = 2 dx, and the kernel's 1/h, 8/(pi h^3) and 48/(pi h^4) from it") {
    std::random_device rd;
    const unsigned seed = rd();
    INFO("seed " << seed);
    std::mt19937 rng(seed);
    for (const auto& b : ranryu::scene::bundled()) {
        ranryu::scene::Scene s = ranryu::scene::load(b.name);
        s.spacing = std::uniform_real_distribution<float>(0.001f, 0.05f)(rng);
        INFO(b.name << " at spacing " << s.spacing);
        const ranryu::gpu::SphParams p = ranryu::sim::sph_params(s, 1000, 100);
        const double h = 2.0 * double(s.spacing), pi = std::numbers::pi;
        CHECK(p.h == Approx(h).epsilon(1e-7));
        CHECK(p.inv_h == Approx(1.0 / h).epsilon(1e-6));
        CHECK(p.w_scale == Approx(8.0 / (pi * h * h * h)).epsilon(1e-6));
        CHECK(p.grad_scale == Approx(48.0 / (pi * h * h * h * h)).epsilon(1e-6));
    }
}
