#pragma once
// Shared by the SPH GL tests: a scene parsed from inline JSON and its sim::Simulation (the fluid's
// state, which samples the boundary and computes psi at construction, and the scene's solver), on the
// fixture's context, with the helpers the tests use to run whole frames and read fields back.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/simulation.h"
#include "sim/solvers/dfsph.h"
#include "sim/solvers/pbf.h"
#include "sim/solvers/wcsph.h"
#include "support/gl_fixture.h"

namespace ranryu::test {

struct SphRig {
    bool ready = (context(), true);
    scene::Scene scene;
    profile::GpuTimer timer{4, 4096};
    sim::Simulation sim;
    sim::Fluid& fluid;
    SphRig(const std::string& json, const std::string& origin) : SphRig(scene::parse(json, origin)) {}
    explicit SphRig(scene::Scene s) : scene(std::move(s)), sim(shader::FileSource::embedded(), timer, scene), fluid(sim.fluid()) {}

    // The solver, for tests that drive its stages one by one; the scene must have chosen it.
    sim::Wcsph& wcsph() { return solver<sim::Wcsph>("wcsph"); }
    sim::Dfsph& dfsph() { return solver<sim::Dfsph>("dfsph"); }
    sim::Pbf& pbf() { return solver<sim::Pbf>("pbf"); }

    // One whole frame: begin, the substeps the fluid plans, end; then collect arrived records.
    void frame(std::uint64_t index) {
        timer.begin_frame();
        sim.advance(index);
        timer.end_frame();
        fluid.poll_records();
    }
    // Waits for the outstanding timings and records.
    void finish() {
        timer.drain();
        fluid.drain_records();
    }
    std::vector<glm::vec4> read(const gl::Buffer& b) const { return b.read<glm::vec4>(fluid.count()); }
    // The boundary particles and their psi_b, as the GPU computed them.
    void boundary(std::vector<glm::dvec3>& xb, std::vector<double>& psi) const {
        xb.clear(), psi.clear();
        for (const glm::vec4& b : fluid.boundary().read<glm::vec4>(fluid.boundary_count())) {
            xb.emplace_back(glm::vec3(b));
            psi.push_back(double(b.w));
        }
    }
    gpu::StepState step() const { return fluid.step_state().read<gpu::StepState>(1)[0]; }

private:
    template <class S>
    S& solver(const char* name) {
        if (auto* s = dynamic_cast<S*>(&sim.solver())) return *s;
        throw std::logic_error(std::string("SphRig: the scene's solver is not ") + name);
    }
};

// The 8x8x8 block on a lattice of pitch `ratio`·dx with its lower corner at `corner`, each particle
// moved by up to ±`jitter`·dx per axis, with velocity components uniform in ±`speed`, for a rig of 512
// particles. A pitch below dx compresses the fluid (ρ ≈ ρ0/ratio³): non-zero pressures. No pair
// distance lies within 1e-5·h of h, where a float and a double distance could fall on either side of
// the kernel's support.
inline void block_state(Random& rng, const SphRig& rig, glm::vec3 corner, float ratio, float jitter, float speed,
                        std::vector<glm::vec4>& x, std::vector<glm::vec4>& v) {
    const float dx = rig.scene.spacing;
    const double h = 2.0 * double(dx);
    REQUIRE(rig.fluid.count() == 512);
    for (int attempt = 0;; ++attempt) {
        REQUIRE(attempt < 100);
        x.clear();
        for (int k = 0; k < 8; ++k)
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    const glm::vec3 wobble(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter));
                    x.emplace_back(corner + ((glm::vec3(float(i), float(j), float(k)) + 0.5f) * ratio + wobble) * dx, 0.0f);
                }
        bool ok = true;
        for (std::size_t a = 0; a < x.size() && ok; ++a)
            for (std::size_t b = a + 1; b < x.size() && ok; ++b)
                ok = std::abs(glm::length(glm::dvec3(glm::vec3(x[a])) - glm::dvec3(glm::vec3(x[b]))) - h) >= 1e-5 * h;
        if (ok) break;
    }
    v.resize(x.size());
    for (auto& u : v) u = glm::vec4(rng.uniform(-speed, speed), rng.uniform(-speed, speed), rng.uniform(-speed, speed), 0.0f);
}

}  // namespace ranryu::test
