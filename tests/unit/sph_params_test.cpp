#include <catch2/catch.hpp>

#include "reference/random.h"
#include "reference/sph_reference.h"
#include "scene/scene.h"
#include "sim/fluid.h"

// sim::sph_params: the kernel's support and the constants of docs/SPH.md eq. (1) that the fluid's walks
// read from SphParams instead of deriving them from h every pair (glsl/sim/fluid/fluid.glsl kernel_w(r),
// kernel_grad(d, r); docs/PERFORMANCE.md "The kernel's constants as operands"), against the CPU
// reference's kernel, which the GPU passes' tests compare with.
TEST_CASE("sph_params: h = 2 dx, and the kernel's 1/h, W(0) and gradient scale as the reference kernel has them") {
    ranryu::reference::Random rnd;
    INFO("seed " << rnd.seed);
    for (const auto& b : ranryu::scene::bundled()) {
        ranryu::scene::Scene s = ranryu::scene::load(b.name);
        s.spacing = float(rnd.uniform(0.001, 0.05));
        INFO(b.name << " at spacing " << s.spacing);
        const ranryu::gpu::SphParams p = ranryu::sim::sph_params(s, 1000, 100);
        const ranryu::reference::CubicKernel K{2.0 * double(s.spacing)};
        CHECK(p.h == Approx(K.h).epsilon(1e-7));
        CHECK(p.inv_h == Approx(1.0 / K.h).epsilon(1e-6));
        CHECK(p.w_scale == Approx(K.W(0.0)).epsilon(1e-6));   // W = w_scale * shape(q), shape(0) = 1
        // For q <= 1/2 kernel_grad_of gives grad W = grad_scale (3q - 2)/h d: the reference's gradient at a
        // random q there, divided by (3q - 2)/h |d|, is grad_scale.
        const double q = rnd.uniform(0.05, 0.5), r = q * K.h;
        const glm::dvec3 e(0.0, 0.0, 1.0);
        CHECK(p.grad_scale == Approx(glm::dot(K.gradW(r * e), e) / ((3.0 * q - 2.0) / K.h * r)).epsilon(1e-6));
    }
}
