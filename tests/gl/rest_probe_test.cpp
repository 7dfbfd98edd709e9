// Hidden (not run by default or by ctest): where DFSPH's tank at rest gets its motion from
// (docs/VALIDATION.md "Where the motion at rest comes from"). Relaxes the tank as validation::
// hydrostatic's Relaxation does (frames from rest, velocities zeroed after each), then runs frames
// from rest through the solver's stages one by one and prints, per step and per region of the column
// (surface, floor, side walls: within 2 dx; interior; all), the rms and largest of the divergence
// solve's a^p, the non-pressure a less g, the density solve's a^p plus g (what is left unbalanced) and
// the step's net (v_{n+1} - v_n)/dt, and each frame's end speeds. Environment:
//   RANRYU_PROBE_SCENE        a scene file (default: the bundled hydrostatic with the boundary rows)
//   RANRYU_PROBE_SPACING      m, default 0.025
//   RANRYU_PROBE_RELAX        relaxation frames, default 120 (RANRYU_PROBE_EVERY: print every N)
//   RANRYU_PROBE_RELAX_SCENE  relax with this scene file instead
//   RANRYU_PROBE_SAVE, _LOAD  save the relaxed positions with their warm starts (kappa, kappa_v), or
//                             load them instead of relaxing (RANRYU_PROBE_LATTICE_WARM: keep the
//                             probed pipeline's own initial warm start)
//   RANRYU_PROBE_FRAMES       frames probed, default 1; RANRYU_PROBE_FREE: run them on without
//                             zeroing the velocities (prints every 10th frame's speeds only)
//   RANRYU_PROBE_QUIET        one line a step
//   RANRYU_PROBE_DROP_KAPPA_V the divergence solve's warm start set to 0 before the probed frames
//   RANRYU_PROBE_SHADERS      a shader folder instead of the embedded copies
#include "support/gl_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/simulation.h"
#include "sim/solvers/dfsph.h"

using namespace ranryu;

namespace {

const char* env(const char* name, const char* fallback) { return std::getenv(name) ? std::getenv(name) : fallback; }

struct Tally {
    double s2[5] = {}, mx[5] = {};
    int n[5] = {};
    void add(int region, double value) {
        for (int r : {region, 4}) s2[r] += value * value, mx[r] = std::max(mx[r], value), ++n[r];
    }
    void print(const char* what) const {
        std::printf("  %-28s", what);
        for (int r = 0; r < 5; ++r) std::printf(" %7.4f/%7.4f", n[r] ? std::sqrt(s2[r] / n[r]) : 0.0, mx[r]);
        std::printf("\n");
    }
};

}  // namespace

TEST_CASE("rest probe: DFSPH's tank, one frame from rest, by stage and region", "[.rest-probe]") {
    test::context();
    const float dx = std::strtof(env("RANRYU_PROBE_SPACING", "0.025"), nullptr);
    const int relax = std::atoi(env("RANRYU_PROBE_RELAX", "120"));
    const int probes = std::atoi(env("RANRYU_PROBE_FRAMES", "1"));
    scene::Scene s = std::getenv("RANRYU_PROBE_SCENE") ? scene::load(std::getenv("RANRYU_PROBE_SCENE")) : scene::load("hydrostatic");
    if (!std::getenv("RANRYU_PROBE_SCENE")) s.sph.boundary_rows = true;
    s = scene::with_spacing(s, dx, "probe");
    s.sph.solver = scene::Solver::dfsph;
    const shader::FileSource shaders =
        std::getenv("RANRYU_PROBE_SHADERS") ? shader::FileSource::directory(std::getenv("RANRYU_PROBE_SHADERS")) : shader::FileSource::embedded();
    const glm::vec3 g = s.gravity;
    auto rms = [](const std::vector<glm::vec4>& v) {
        double s2 = 0.0;
        for (const auto& u : v) s2 += double(glm::dot(glm::vec3(u), glm::vec3(u)));
        return std::sqrt(s2 / double(v.size()));
    };
    // Regions: 0 surface (within 2 dx of the top), 1 floor (within 2 dx of the floor), 2 side walls
    // (within 2 dx), 3 interior; 4 all.
    auto region = [&](glm::vec3 x, float top) {
        const float m = 2.0f * dx;
        if (x.y > top - m) return 0;
        if (x.y - s.tank_min.y < m) return 1;
        if (x.x - s.tank_min.x < m || s.tank_max.x - x.x < m || x.z - s.tank_min.z < m || s.tank_max.z - x.z < m) return 2;
        return 3;
    };
    // The relaxed positions: from RANRYU_PROBE_LOAD, or relaxed here with RANRYU_PROBE_RELAX_SCENE
    // (default: the probed scene), saved to RANRYU_PROBE_SAVE.
    std::vector<glm::vec4> relaxed;
    std::vector<glm::vec2> warm;   // the density and divergence solves' warm starts that go with them
    if (const char* path = std::getenv("RANRYU_PROBE_LOAD")) {
        std::FILE* f = std::fopen(path, "rb");
        REQUIRE(f);
        glm::vec4 q;
        glm::vec2 k;
        while (std::fread(&q, sizeof q, 1, f) == 1 && std::fread(&k, sizeof k, 1, f) == 1) relaxed.push_back(q), warm.push_back(k);
        std::fclose(f);
    } else {
        scene::Scene rs = s;
        if (const char* e = std::getenv("RANRYU_PROBE_RELAX_SCENE")) {
            rs = scene::with_spacing(scene::load(e), dx, "probe");
            rs.sph.solver = scene::Solver::dfsph;
        }
        profile::GpuTimer timer{4, 4096};
        sim::Simulation sim(shaders, timer, rs);
        sim::Fluid& fluid = sim.fluid();
        const std::size_t n = fluid.count();
        auto read = [&](const gl::Buffer& b) { return b.read<glm::vec4>(n); };
        std::vector<glm::vec4> x = read(fluid.positions());
        for (int f = 0; f < relax; ++f) {
            timer.begin_frame();
            sim.advance(std::uint64_t(f));
            timer.end_frame();
            fluid.poll_records();
            x = read(fluid.positions());
            const auto v = read(fluid.velocities());
            if (f < 3 || (f + 1) % std::atoi(env("RANRYU_PROBE_EVERY", "20")) == 0) {
                float top = -1e9f;
                for (const auto& xi : x) top = std::max(top, xi.y);
                double s2[4] = {}, vy[4] = {};
                int c[4] = {};
                for (std::size_t i = 0; i < n; ++i) {
                    const int r = region(glm::vec3(x[i]), top);
                    s2[r] += double(glm::dot(glm::vec3(v[i]), glm::vec3(v[i]))), vy[r] += v[i].y, ++c[r];
                }
                std::printf("relax frame %d: rms %.5f m/s; surface %.5f (mean v_y %+.5f), floor %.5f, walls %.5f, interior %.5f\n", f + 1,
                            rms(v), std::sqrt(s2[0] / std::max(c[0], 1)), vy[0] / std::max(c[0], 1), std::sqrt(s2[1] / std::max(c[1], 1)),
                            std::sqrt(s2[2] / std::max(c[2], 1)), std::sqrt(s2[3] / std::max(c[3], 1)));
            }
            fluid.upload_state(x, std::vector<glm::vec4>(n, glm::vec4(0.0f)));
        }
        timer.drain();
        fluid.drain_records();
        relaxed = x;
        warm = dynamic_cast<sim::Dfsph&>(sim.solver()).warm_start().read<glm::vec2>(n);
        if (const char* path = std::getenv("RANRYU_PROBE_SAVE")) {
            std::FILE* f = std::fopen(path, "wb");
            for (std::size_t i = 0; i < n; ++i) std::fwrite(&relaxed[i], sizeof(glm::vec4), 1, f), std::fwrite(&warm[i], sizeof(glm::vec2), 1, f);
            std::fclose(f);
        }
    }
    profile::GpuTimer timer{4, 4096};
    sim::Simulation sim(shaders, timer, s);
    sim::Fluid& fluid = sim.fluid();
    auto& d = dynamic_cast<sim::Dfsph&>(sim.solver());
    const std::size_t n = fluid.count();
    REQUIRE(relaxed.size() == n);
    auto read = [&](const gl::Buffer& b) { return b.read<glm::vec4>(n); };
    fluid.upload_state(relaxed, std::vector<glm::vec4>(n, glm::vec4(0.0f)));
    if (!std::getenv("RANRYU_PROBE_LATTICE_WARM")) d.upload_warm_start(warm);
    std::uint64_t frame = 0;
    if (std::getenv("RANRYU_PROBE_DROP_KAPPA_V")) {   // the divergence solve's warm start dropped
        auto w = d.warm_start().read<glm::vec2>(n);
        for (auto& k : w) k.y = 0.0f;
        d.upload_warm_start(w);
    }
    std::printf("columns: surface, floor, walls, interior, all: rms/max (m/s^2 or m/s)\n");
    for (int p = 0; p < probes; ++p, ++frame) {
        timer.begin_frame();
        sim.begin_frame(frame);
        const int steps = sim.substeps_this_frame();
        for (int k = 0; k < steps; ++k) {
            fluid.choose_time_step();
            fluid.rebuild_grid();
            d.compute_density(fluid);
            const auto v0 = read(fluid.velocities()), x = read(fluid.positions()), a = read(fluid.accelerations());
            d.solve_divergence(fluid);
            const auto v1 = read(fluid.velocities());
            d.predict_density(fluid);
            d.solve_density(fluid);
            d.integrate(fluid);
            const auto v2 = read(fluid.velocities()), rho = read(fluid.densities());
            const gpu::StepState st = fluid.step_state().read<gpu::StepState>(1)[0];
            const float dt = st.dt;
            float top = -1e9f;
            for (const auto& xi : x) top = std::max(top, xi.y);
            Tally div, visc, dens, net, speed, comp;
            int counts[4] = {};
            for (std::size_t i = 0; i < n; ++i) {
                const int r = region(glm::vec3(x[i]), top);
                ++counts[r];
                const glm::vec3 anp = glm::vec3(a[i]);
                const glm::vec3 ad = (glm::vec3(v1[i]) - glm::vec3(v0[i])) / dt - anp;
                div.add(r, glm::length(ad));
                visc.add(r, glm::length(anp - g));
                dens.add(r, glm::length((glm::vec3(v2[i]) - glm::vec3(v1[i])) / dt + g));
                net.add(r, glm::length((glm::vec3(v2[i]) - glm::vec3(v0[i])) / dt));
                speed.add(r, glm::length(glm::vec3(v2[i])));
                comp.add(r, rho[i].x / s.sph.rest_density - 1.0);
            }
            if (std::getenv("RANRYU_PROBE_FREE")) continue;
            if (std::getenv("RANRYU_PROBE_QUIET")) {
                std::printf("step %d dt %.5f it (%u %u) div %.3f dens+g %.3f net %.3f (max %.3f) speed %.4f\n", k, dt, st.iterations.x,
                            st.iterations.y, std::sqrt(div.s2[4] / n), std::sqrt(dens.s2[4] / n), std::sqrt(net.s2[4] / n), net.mx[4],
                            std::sqrt(speed.s2[4] / n));
                continue;
            }
            std::printf("frame %d step %d: dt %.5f, iterations (%u %u), errors (%.2e %.2e); particles %d %d %d %d\n", p, k, dt,
                        st.iterations.x, st.iterations.y, st.error.x, st.error.y, counts[0], counts[1], counts[2], counts[3]);
            div.print("divergence a^p");
            visc.print("non-pressure a - g");
            dens.print("density a^p + g");
            net.print("net (v1 - v0)/dt");
            speed.print("speed after");
            comp.print("rho/rho0 - 1 (start)");
        }
        sim.end_frame();
        timer.end_frame();
        fluid.poll_records();
        const auto x = read(fluid.positions()), v = read(fluid.velocities());
        {
            float top = -1e9f;
            for (const auto& xi : x) top = std::max(top, xi.y);
            Tally end;
            for (std::size_t i = 0; i < n; ++i) end.add(region(glm::vec3(x[i]), top), glm::length(glm::vec3(v[i])));
            if (std::getenv("RANRYU_PROBE_FREE") && (p + 1) % 10 != 0) continue;
            std::printf("frame %d from rest: rms %.5f m/s", p, rms(v));
            end.print("; by region (rms/max)");
        }
        if (p + 1 < probes && !std::getenv("RANRYU_PROBE_FREE")) fluid.upload_state(x, std::vector<glm::vec4>(n, glm::vec4(0.0f)));
    }
    timer.drain();
    fluid.drain_records();
}
