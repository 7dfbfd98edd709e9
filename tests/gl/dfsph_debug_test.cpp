// Hidden (not run by default or by ctest): a debugging aid for DFSPH on the GPU host. Runs the dam
// break (or RANRYU_DEBUG_SCENE) at RANRYU_DEBUG_SPACING (m) for RANRYU_DEBUG_FRAMES frames, reads the state back after every
// step, and at the first step whose fastest particle exceeds RANRYU_DEBUG_SPEED (m/s) prints the
// fastest particles and those of the largest kappa and kappa_v with their DFSPH fields, then fails.
// It found the wall jets that a loose density tolerance let grow at 1M particles (docs/DFSPH.md).
#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>

TEST_CASE("dfsph debug: fastest particles of the dam break", "[.dfsph-debug]") {
    const float dx = std::getenv("RANRYU_DEBUG_SPACING") ? std::strtof(std::getenv("RANRYU_DEBUG_SPACING"), nullptr) : 0.004f;
    const int frames = std::getenv("RANRYU_DEBUG_FRAMES") ? std::atoi(std::getenv("RANRYU_DEBUG_FRAMES")) : 20;
    const float trigger = std::getenv("RANRYU_DEBUG_SPEED") ? std::strtof(std::getenv("RANRYU_DEBUG_SPEED"), nullptr) : 3.5f;
    const char* name = std::getenv("RANRYU_DEBUG_SCENE") ? std::getenv("RANRYU_DEBUG_SCENE") : "dam-break";
    ranryu::scene::Scene s = ranryu::scene::with_spacing(ranryu::scene::load(name), dx, "debug");
    s.sph.solver = ranryu::scene::Solver::dfsph;
    ranryu::test::SphRig rig(s);
    auto& d = rig.dfsph();
    for (int f = 0; f < frames && !rig.fluid.instability(); ++f) {
        rig.timer.begin_frame();
        rig.sim.begin_frame(std::uint64_t(f));
        const int n_sub = rig.sim.substeps_this_frame();
        for (int k = 0; k < n_sub; ++k) {
            rig.sim.step();
            const auto v = rig.read(rig.fluid.velocities());
            float vmax = 0; std::size_t imax = 0;
            for (std::size_t i = 0; i < v.size(); ++i) { float l = glm::length(glm::vec3(v[i])); if (l > vmax) vmax = l, imax = i; }
            if (vmax < trigger) continue;
            const auto x = rig.read(rig.fluid.positions()), dens = rig.read(rig.fluid.densities());
            auto kap = d.read_kappa();
            kap.resize(rig.fluid.count());
            const auto warm = d.warm_start().read<glm::vec2>(rig.fluid.count());
            const auto pa = rig.read(d.pressure_accelerations());
            const auto acc = rig.read(rig.fluid.accelerations());
            const auto st = rig.step();
            std::printf("frame %d step %d dt %.3g: vmax %.3f at %zu\n", f, k, st.dt, vmax, imax);
            std::vector<std::size_t> idx(v.size());
            std::iota(idx.begin(), idx.end(), 0);
            std::partial_sort(idx.begin(), idx.begin() + 8, idx.end(), [&](auto a, auto b) { return glm::length(glm::vec3(v[a])) > glm::length(glm::vec3(v[b])); });
            auto show = [&](std::size_t i) {
                std::uint32_t flags; std::memcpy(&flags, &dens[i].w, 4);
                std::printf("  %zu x (%.4f %.4f %.4f) v (%.3f %.3f %.3f) rho %.2f p %.1f factor %.3g flags %u kappa %.3g warm (%.3g %.3g) pa (%.2f %.2f %.2f | %.3g) a_np (%.2f %.2f %.2f)\n",
                            i, x[i].x, x[i].y, x[i].z, v[i].x, v[i].y, v[i].z, dens[i].x, dens[i].y, dens[i].z, flags, kap[i], warm[i].x, warm[i].y,
                            pa[i].x, pa[i].y, pa[i].z, pa[i].w, acc[i].x, acc[i].y, acc[i].z);
            };
            for (int q = 0; q < 6; ++q) show(idx[q]);
            std::printf(" largest kappa_v:\n");
            std::partial_sort(idx.begin(), idx.begin() + 4, idx.end(), [&](auto a, auto b) { return warm[a].y > warm[b].y; });
            for (int q = 0; q < 4; ++q) show(idx[q]);
            std::printf(" largest kappa:\n");
            std::partial_sort(idx.begin(), idx.begin() + 4, idx.end(), [&](auto a, auto b) { return warm[a].x > warm[b].x; });
            for (int q = 0; q < 4; ++q) show(idx[q]);
            rig.timer.end_frame();
            rig.finish();
            FAIL("speed above the trigger");
        }
        rig.sim.end_frame();
        rig.timer.end_frame();
        rig.fluid.poll_records();
    }
}

// Hidden: the hydrostatic tank under DFSPH at RANRYU_DEBUG_SPACING, frame by frame: the rms and max
// speed, where the fastest particle is, the step's records.
TEST_CASE("dfsph debug: the tank at rest, frame by frame", "[.dfsph-rest]") {
    const float dx = std::getenv("RANRYU_DEBUG_SPACING") ? std::strtof(std::getenv("RANRYU_DEBUG_SPACING"), nullptr) : 0.02f;
    const int frames = std::getenv("RANRYU_DEBUG_FRAMES") ? std::atoi(std::getenv("RANRYU_DEBUG_FRAMES")) : 60;
    ranryu::scene::Scene s = ranryu::scene::with_spacing(ranryu::scene::load("hydrostatic"), dx, "debug");
    s.sph.solver = ranryu::scene::Solver::dfsph;
    if (const char* e = std::getenv("RANRYU_DEBUG_VISCOSITY")) s.sph.viscosity = std::strtof(e, nullptr);
    if (const char* e = std::getenv("RANRYU_DEBUG_WARM")) s.sph.warm_start = std::strtof(e, nullptr), s.sph.divergence_warm_start = std::strtof(e, nullptr);
    if (const char* e = std::getenv("RANRYU_DEBUG_DIVERGENCE")) s.sph.divergence_solve = std::atoi(e) != 0;
    if (const char* e = std::getenv("RANRYU_DEBUG_MAX_DT")) s.sph.max_time_step = std::strtof(e, nullptr);
    if (const char* e = std::getenv("RANRYU_DEBUG_ETA")) s.sph.max_density_error = std::strtof(e, nullptr);
    if (const char* e = std::getenv("RANRYU_DEBUG_SOLVER")) s.sph.solver = std::string(e) == "wcsph" ? ranryu::scene::Solver::wcsph : ranryu::scene::Solver::dfsph;
    ranryu::test::SphRig rig(s);
    for (int f = 0; f < frames && !rig.fluid.instability(); ++f) {
        rig.frame(std::uint64_t(f));
        const auto v = rig.read(rig.fluid.velocities());
        const auto x = rig.read(rig.fluid.positions());
        const auto dens = rig.read(rig.fluid.densities());
        double s2 = 0; float vmax = 0; std::size_t imax = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const float l = glm::length(glm::vec3(v[i]));
            s2 += double(l) * l;
            if (l > vmax) vmax = l, imax = i;
        }
        const auto st = rig.step();
        std::printf("frame %d: dt %.3g substeps %u iters (%u %u) err (%.2e %.2e) rms %.4f max %.4f at (%.3f %.3f %.3f) v (%.3f %.3f %.3f) rho %.1f p %.1f\n",
                    f, st.dt, st.frame_substeps, st.iterations.x, st.iterations.y, st.error.x, st.error.y,
                    std::sqrt(s2 / double(v.size())), vmax, x[imax].x, x[imax].y, x[imax].z, v[imax].x, v[imax].y, v[imax].z,
                    dens[imax].x, dens[imax].y);
    }
    rig.finish();
}
