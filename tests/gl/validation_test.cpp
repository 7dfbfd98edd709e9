// The validation cases at llvmpipe sizes, for each solver, with bounds derived from the resolution and
// the physics.
#include "support/gl_fixture.h"

#include <cmath>
#include <optional>
#include <string>

#include "scene/scene.h"
#include "shader/source.h"
#include "validation/cases.h"

using namespace ranryu;

namespace {

scene::Scene case_scene(const std::string& name, float dx, scene::Solver solver) {
    scene::Scene s = scene::with_spacing(validation::case_scene(name), dx, "test");
    s.sph.solver = solver;
    return s;
}

// The tank at rest at two spacings, `coarse` then `fine`: in each, pressure grows with depth less one
// layer's weight of noise (the floor layer and the top kernel support aside, as for WCSPH), the
// interior within 0.25 of rho0 g H (3 layers of 12), the floor layer within `floor_bound` and the rms
// speed within `speed_fraction` of the free-fall speed over the column, sqrt(2 g H) = 2.2 m/s; and
// neither error grows as dx shrinks, within the scatter of the averaging (0.02 of rho0 g H; the floor
// layer's within `floor_scatter`, not asked where a case gives none).
void check_columns(const validation::HydrostaticResult& coarse, const validation::HydrostaticResult& fine, double floor_bound,
                   double speed_fraction, std::optional<double> floor_scatter = 0.02) {
    INFO("interior " << coarse.max_error << " then " << fine.max_error << "; floor layer " << coarse.floor_error << " then "
                     << fine.floor_error << "; rms speed " << coarse.rms_speed << " then " << fine.rms_speed << " m/s");
    for (const auto* r : {&coarse, &fine}) {
        REQUIRE(r->layers.size() >= 10);
        for (std::size_t k = 1; k + 2 < r->layers.size(); ++k)
            CHECK(r->layers[k].pressure >= r->layers[k + 1].pressure - 1000.0 * 9.81 * r->spacing);
        CHECK(r->max_error <= 0.25);
        CHECK(r->floor_error <= floor_bound);
        CHECK(r->rms_speed <= speed_fraction * std::sqrt(2.0 * 9.81 * r->height));
    }
    CHECK(fine.max_error <= coarse.max_error + 0.02);
    if (floor_scatter) CHECK(fine.floor_error <= coarse.floor_error + *floor_scatter);
}

}  // namespace

TEST_CASE("validate: dam break surge front against Martin & Moyce (1952) at a/dx = 8, both solvers", "[validation]") {
    test::context();
    const auto& shaders = shader::FileSource::embedded();
    const validation::DamBreakResult w = validation::dam_break(case_scene("dam-break", 0.025f, scene::Solver::wcsph), shaders);
    // DFSPH as the scene ships it (the boundary rows of docs/DFSPH.md (D9) and no-slip walls, (D7)); with
    // the rows and free-slip walls, where the rows' own effect shows; and with Akinci's boundary term,
    // free-slip and no-slip, where the no-slip wall's drag shows.
    const scene::Scene shipped = case_scene("dam-break", 0.025f, scene::Solver::dfsph);
    REQUIRE(shipped.sph.boundary_rows);
    scene::Scene rows_free_slip = shipped;
    rows_free_slip.sph.boundary_viscosity = 0.0f;   // the scene's walls are no-slip (the next test case)
    scene::Scene free_slip = rows_free_slip;
    free_slip.sph.boundary_rows = false;
    scene::Scene no_slip = free_slip;
    no_slip.sph.boundary_viscosity = no_slip.sph.viscosity;   // the wall as fluid at rest (docs/DFSPH.md (D7))
    const validation::DamBreakResult as_shipped = validation::dam_break(shipped, shaders);
    const validation::DamBreakResult rows = validation::dam_break(rows_free_slip, shaders);
    const validation::DamBreakResult f = validation::dam_break(free_slip, shaders);
    const validation::DamBreakResult n = validation::dam_break(no_slip, shaders);
    INFO("WCSPH rms " << w.rms_error << ", max " << w.max_error << ", " << w.steps << " steps; DFSPH with the rows rms "
                      << rows.rms_error << ", max " << rows.max_error << ", " << rows.steps << " steps; Akinci free-slip rms "
                      << f.rms_error << ", max " << f.max_error << "; no-slip rms " << n.rms_error << ", max " << n.max_error
                      << "; as shipped rms " << as_shipped.rms_error << ", max " << as_shipped.max_error << ", " << as_shipped.steps << " steps");
    // Every experimental time up to T = 3.33 is covered, and the front moves forward.
    for (const auto* r : {&w, &rows, &f, &n, &as_shipped}) {
        CHECK(r->compared.size() == 15);
        CHECK(r->simulated.back().second > 4.0);
    }
    // WCSPH. At a/dx = 8 the front is located to one spacing, dx/a = 0.125 in Z, and the leading
    // particle of a tip one particle thick runs ahead by about another; Martin & Moyce's repeated runs
    // scatter by about 0.1 in Z, and their early times lag a free release (the gate's opening). So
    // rms <= 2 dx/a + 0.1 = 0.35 and max <= 4 dx/a = 0.5. Measured on llvmpipe: rms 0.20, max 0.39.
    CHECK(w.rms_error <= 2.0 * 0.125 + 0.1);
    CHECK(w.max_error <= 4.0 * 0.125);
    // DFSPH, free-slip, both boundaries, and as shipped: the same bounds. Measured on llvmpipe (2026-11-29,
    // the scene's (D10) and its density bounds, eta = 0.1 % with eta_p = 1 %): rms 0.21, max 0.39 with
    // Akinci's term; 0.12 and 0.20 with the rows (2026-11-26, eta = 0.01 %: 0.23, 0.42 and 0.14, 0.23);
    // as shipped, with no-slip walls as well, 0.11 and 0.18.
    for (const auto* r : {&rows, &f, &as_shipped}) {
        CHECK(r->rms_error <= 2.0 * 0.125 + 0.1);
        CHECK(r->max_error <= 4.0 * 0.125);
    }
    // The rows hold the floor layer's pressure where Akinci's term doubles it (docs/DFSPH.md
    // "Boundary pressure"), and the toe no longer runs ahead on it: closer than Akinci's free-slip front
    // by more than the scatter of one spacing's worth in rms (0.125 / 4), the reason the scene ships
    // them (its sph.why).
    CHECK(rows.rms_error <= f.rms_error - 0.125 / 4.0);
    CHECK(rows.max_error <= f.max_error);
    // No-slip walls drag the toe: closer to the experiment than free-slip by the same margin. Measured
    // with Akinci's term: rms 0.15 against 0.21 (2026-11-29; 0.17 against 0.23 at eta = 0.01 %). (With
    // the rows the drag gains less here, 0.106 against 0.122 in rms with the scene's nu_b = 1e-3: within
    // the scatter at this size, so it is checked at a/dx = 16, the next test case.)
    CHECK(n.rms_error <= f.rms_error - 0.125 / 4.0);
    CHECK(n.max_error <= f.max_error);
    // Substeps, from the GPU's records over the same frames at the same spacing: WCSPH's step is bound
    // by the artificial sound speed c = 10 v_max (dt = 0.4 dx / (c + v)), DFSPH's by the flow speed
    // (dt = 0.4 dx / v): about 10x fewer at the surge's speed. Required (issue 11): at least 5x.
    CHECK(double(w.steps) >= 5.0 * double(rows.steps));
    CHECK(double(w.steps) >= 5.0 * double(f.steps));
    CHECK(double(w.steps) >= 5.0 * double(as_shipped.steps));
    test::require_no_gl_errors();
}

TEST_CASE("validate: the dam break's no-slip walls bring DFSPH's front closer to Martin & Moyce than free-slip ones at a/dx = 16",
          "[validation]") {
    test::context();
    // media/scenes/dam-break.json ships DFSPH's no-slip wall (docs/DFSPH.md (D7)) at nu_b = 1e-3 m^2/s,
    // chosen against the experiment (docs/VALIDATION.md): measured on llvmpipe at the scene's spacing
    // (a/dx = 16, 4,096 particles) rms 0.110, max 0.183 against 0.189, 0.241 with free-slip walls (nu_b
    // = 0, the same boundary rows; 0.107 and 0.196 before the iteration cap was scaled to the plan,
    // 2026-11-30), and on the H200 0.131 and 0.158 against 0.240 and 0.270 at a/dx = 40
    // and 80. At a/dx = 8 the gain is within a spacing's scatter (0.106 against 0.122), so it is
    // checked here, one size up: closer by at least one spacing in Z (dx/a = 0.0625) in rms, and no
    // worse at its largest.
    const auto& shaders = shader::FileSource::embedded();
    const scene::Scene shipped = case_scene("dam-break", 0.0125f, scene::Solver::dfsph);
    REQUIRE(shipped.sph.boundary_viscosity == 1e-3f);
    REQUIRE(shipped.sph.boundary_rows);
    scene::Scene free_slip = shipped;
    free_slip.sph.boundary_viscosity = 0.0f;
    const validation::DamBreakResult n = validation::dam_break(shipped, shaders);
    const validation::DamBreakResult f = validation::dam_break(free_slip, shaders);
    INFO("no-slip rms " << n.rms_error << ", max " << n.max_error << ", " << n.steps << " steps; free-slip rms " << f.rms_error << ", max "
                        << f.max_error << ", " << f.steps << " steps");
    for (const auto* r : {&n, &f}) {
        CHECK(r->compared.size() == 15);
        CHECK(r->simulated.back().second > 4.0);
    }
    CHECK(n.rms_error <= f.rms_error - 0.0625);
    CHECK(n.max_error <= f.max_error);
    test::require_no_gl_errors();
}

TEST_CASE("validate: dam break surge front with PBF at a/dx = 8, in its fixed substeps", "[validation][pbf]") {
    test::context();
    const scene::Scene s = case_scene("dam-break", 0.025f, scene::Solver::pbf);
    const validation::DamBreakResult r = validation::dam_break(s, shader::FileSource::embedded());
    INFO("PBF rms " << r.rms_error << ", max " << r.max_error << ", " << r.steps << " steps");
    CHECK(r.compared.size() == 15);
    CHECK(r.simulated.back().second > 4.0);
    // The same bounds as WCSPH's and DFSPH's above (the front located to a spacing, the tip's leading
    // particle, the experiment's scatter and gate). Measured on llvmpipe: rms 0.21, max 0.30.
    CHECK(r.rms_error <= 2.0 * 0.125 + 0.1);
    CHECK(r.max_error <= 4.0 * 0.125);
    // docs/PBF.md (P1): exactly the scene's substeps every frame, whatever the surge does.
    const double frames = r.stats.simulated_seconds / double(s.frame_dt);
    CHECK(frames > 10.0);
    CHECK(double(r.steps) == Approx(double(s.sph.pbf.substeps) * frames).margin(0.5));
    test::require_no_gl_errors();
}

TEST_CASE("validate: WCSPH tank at rest follows rho0 g (H - z) in its interior", "[validation]") {
    test::context();
    const scene::Scene s = case_scene("hydrostatic", 0.02f, scene::Solver::wcsph);
    // The lattice start, as these bounds were measured (no relaxation, cases.h).
    const validation::HydrostaticResult r = validation::hydrostatic(s, shader::FileSource::embedded(), 0.5, validation::Relaxation{});
    const double g = 9.81, H = r.height, c = s.sound_speed();
    REQUIRE(c > 0.0);
    INFO("interior error " << r.max_error << " of rho0 g H; speed max " << r.max_speed << ", rms " << r.rms_speed
                           << "; g H / c = " << g * H / c);
    REQUIRE(r.layers.size() >= 10);
    // Pressure grows with depth: every layer but the bottom one (docs/SPH.md eq. (4)) and the top
    // kernel support holds more than the one above it, less one layer's weight of noise.
    for (std::size_t k = 1; k + 2 < r.layers.size(); ++k)
        CHECK(r.layers[k].pressure >= r.layers[k + 1].pressure - 1000.0 * g * r.spacing);
    // Interior against rho0 g (H - z), averaged over half a second of the acoustic ringing: WCSPH at
    // 12 layers carries an offset of a few layers' weight; bound 0.25 rho0 g H (3 layers of 12).
    // Measured on llvmpipe: 0.21 against the lattice's depth H = 0.24 m (cases.h; 0.13 on llvmpipe
    // and on the H100 against the block's 0.25 m, half a layer above the fluid).
    CHECK(r.max_error <= 0.25);
    // Spurious velocity: the column starts uncompressed and rings acoustically with a velocity
    // amplitude of about g H / c (the compression rho0 g H / (rho0 c^2) over a period of 4 H / c);
    // bound rms <= 1.5 g H / c, max <= 4 g H / c, what the ringing reaches undamped (measured at
    // nu = 1e-4 m^2/s: rms 1.1, max 2.6 g H / c). The scene's nu = 1e-3 damps it: measured on
    // llvmpipe 2026-11-26, rms 0.13 and max 0.54 g H / c after 1 s.
    CHECK(r.rms_speed <= 1.5 * g * H / c);
    CHECK(r.max_speed <= 4.0 * g * H / c);
    test::require_no_gl_errors();
}

// The density solve with the whole warm start of (D6) (w = 1) and plain relaxed Jacobi (no (D10)), and
// the plain SPH gradient (no (D11)): the solver's defaults until 2026-11-26 and what the tests below
// measured, before the tank at rest set its own warm start, gradient correction and step bound and
// (D10) became the default. The engine's step bound (5 ms) too: the scene's 4 ms (2026-11-30) is for
// its own setting, and with it the plain solve's frames from rest at 0.025 m no longer come to rest.
scene::Scene with_plain_solve(scene::Scene s) {
    s.sph.warm_start = 1.0f;
    s.sph.chebyshev = 0.0f;
    s.sph.max_time_step = scene::SphSettings{}.max_time_step;
    // With (D11) a frame from rest does not come to rest (docs/VALIDATION.md "The gradient correction,
    // and half-second windows").
    s.sph.gradient_correction = false;
    s.sph.pressure_stabilisation = 0.0f;   // (D12): the plain solve's own matrix
    s.sph.eliminate_boundary_rows = false;   // (D13): (D9)'s rows, DFSPH's default
    return s;
}

TEST_CASE("validate: DFSPH tank at rest with the plain solve against rho0 g (H - z), at two spacings", "[validation]") {
    test::context();
    // 0.025 m and 0.02 m: 10 and 12 layers, 4 and 5 particles across the tank's 0.1 m depth, so most of
    // the column lies within a kernel support of a wall. DFSPH's defaults with the plain solve (w = 1, no
    // (D10): with_plain_solve(); the next test measures the scene's own setting): the boundary rows of
    // docs/DFSPH.md (D9), with which the floor layer carries what a fluid layer would (Akinci's term
    // read it at about twice hydrostatic: 1.12 and 1.11 of rho0 g H here, its pair with the next layer
    // 0.56 and 0.52, the interior 0.16 and 0.19; llvmpipe, 2026-12-02), and the step that follows
    // the density solve's iterations ((D8)). The pressure is each frame's dt-weighted mean (docs/DFSPH.md
    // "The pressure a frame"). This solve leaves the layer-to-layer alternation that (D3) does not see
    // (docs/VALIDATION.md "The floor layer's two states"), so the single floor layer settles in one of two
    // states, which one decided by the trajectory's rounding, not by the spacing: over four trajectories
    // on llvmpipe and four on the H200, three of them at 0.025 m (the kernel's arithmetic reassociated:
    // docs/VALIDATION.md "The plain solve's floor layer, trajectory by trajectory") it read 0.025-0.035
    // of rho0 g H at 0.025 m and 0.005-0.065 at 0.02 m, the floor's pair (the floor layer and the next,
    // the alternation cancelled) 0.0002-0.008 and 0.0002-0.022, the interior 0.014-0.021. Bounds, met by
    // every trajectory measured: the floor layer within one spacing of head (rho0 g dx: 0.1 and 0.083 of
    // rho0 g H; the far state's +0.5 to +0.9 spacings of head, docs/VALIDATION.md "The floor layer's two
    // states"; 0.78 at most here), the floor's pair within 0.03, the interior within 0.03 (issue 11's 1 %
    // and 2 % are not met with this solve at these spacings, 4 and 5 particles between the front and back
    // walls), growing by at most 0.02. Whether the floor's error shrinks with dx is not asked of two runs
    // whose scatter is as large as their values (the scene's own setting, the next test, is asked).
    const auto& shaders = shader::FileSource::embedded();
    const scene::Scene coarse_scene = with_plain_solve(case_scene("hydrostatic", 0.025f, scene::Solver::dfsph));
    REQUIRE(coarse_scene.sph.boundary_rows);   // DFSPH's default
    REQUIRE(coarse_scene.sph.shrink_step_above > 0);
    // The lattice start (no relaxation): the relaxed start leaves the motion as it is (a test below).
    const validation::HydrostaticResult coarse = validation::hydrostatic(coarse_scene, shaders, 0.5, validation::Relaxation{});
    const validation::HydrostaticResult fine = validation::hydrostatic(
        with_plain_solve(case_scene("hydrostatic", 0.02f, scene::Solver::dfsph)), shaders, 0.5, validation::Relaxation{});
    const double coarse_head = coarse.spacing / coarse.height, fine_head = fine.spacing / fine.height;   // rho0 g dx over rho0 g H
    INFO("a spacing of head: " << coarse_head << " and " << fine_head << " of rho0 g H");
    // No acoustic ringing here: the initial lattice rearranges at the walls within the first frame (rms
    // 0.1 m/s after it), and the solver at rest keeps moving it (docs/DFSPH.md "The tank at rest at 250k
    // particles"), which the scene's nu = 1e-3 m^2/s does not damp away in a second: rms speed within a
    // tenth of the free-fall speed.
    check_columns(coarse, fine, coarse_head, 0.1, std::nullopt);
    CHECK(fine.floor_error <= fine_head);
    CHECK(coarse.max_error <= 0.03);
    CHECK(fine.max_error <= 0.03);
    INFO("the floor's pair: " << coarse.floor_pair_error << " then " << fine.floor_pair_error);
    CHECK(coarse.floor_pair_error <= 0.03);
    CHECK(fine.floor_pair_error <= 0.03);
    test::require_no_gl_errors();
}

TEST_CASE("validate: the tank at rest with DFSPH as the scene sets it: still, its interior within 1 % of rho0 g H at 0.0125 "
          "and 0.01 m and its floor layer within 2 %, neither growing as dx shrinks",
          "[validation]") {
    test::context();
    // media/scenes/hydrostatic.json sets DFSPH's density solve to start from three quarters of the last
    // step's pressure (sph.warm_start 0.75) with (D10)'s Chebyshev acceleration (0.98), caps the step at
    // 4 ms (sph.max_time_step: at 4.17 ms the 0.02 m column was still settling a second later), blends a
    // quarter of a compact Laplacian into the solve's residual (sph.pressure_stabilisation, docs/DFSPH.md
    // (D12)), which determines the layer-to-layer alternation (D3) leaves free, and eliminates the density
    // solve's boundary rows into the fluid's equations (sph.eliminate_boundary_rows, docs/DFSPH.md (D13)):
    // the rows take the fluid's pressure extended to them and hand their excess on. With (D9)'s rows as
    // unknowns the floor layer read 1.3-2.6 % of rho0 g H at these spacings (this test's run at 0.01 m:
    // 2.56 %), so the 2 % was asserted over the floor's pair; with (D13) it reads 0.37 % at 0.0125 m and
    // 0.04 % at 0.01 m on llvmpipe, and 0.03-0.78 % from 20 to 80 layers on the H200 (docs/VALIDATION.md
    // "The rows eliminated, in the engine"); the interior 0.55 and 0.48 % (0.48-0.93 % on the H200); the
    // column's rms speed 0.0063 and 0.0064 m/s. At 0.02 m (12 layers) the interior reads 1.35-1.49 %,
    // hence these spacings. The pressure compared is each frame's dt-weighted mean of its steps'
    // (docs/DFSPH.md "The pressure a frame"), averaged over 1 s after 1 s settled (after half a second the
    // column has not yet built its pressure at depth from the lattice start).
    const auto& shaders = shader::FileSource::embedded();
    const scene::Scene coarse_scene = case_scene("hydrostatic", 0.0125f, scene::Solver::dfsph);
    REQUIRE(coarse_scene.sph.warm_start == 0.75f);
    REQUIRE(coarse_scene.sph.chebyshev == 0.98f);
    REQUIRE(coarse_scene.sph.boundary_rows);
    REQUIRE(coarse_scene.sph.eliminate_boundary_rows);
    REQUIRE(coarse_scene.sph.max_time_step == 0.004f);
    REQUIRE(coarse_scene.sph.pressure_stabilisation == 0.25f);
    const validation::HydrostaticResult coarse = validation::hydrostatic(coarse_scene, shaders, 1.0, validation::Relaxation{}, nullptr, 1.0);
    const validation::HydrostaticResult fine =
        validation::hydrostatic(case_scene("hydrostatic", 0.01f, scene::Solver::dfsph), shaders, 1.0, validation::Relaxation{}, nullptr, 1.0);
    const double coarse_head = coarse.spacing / coarse.height, fine_head = fine.spacing / fine.height;   // rho0 g dx over rho0 g H
    INFO("a spacing of head: " << coarse_head << " and " << fine_head << " of rho0 g H");
    check_columns(coarse, fine, coarse_head, 0.05, std::nullopt);   // the floor's trend: below, within 0.003
    CHECK(fine.floor_error <= fine_head);
    // Issue 11's bounds, the interior's and the floor layer's, not growing beyond the runs' scatter as dx
    // shrinks (the half-second windows of the runs above move by 0.2-0.4 % of rho0 g H).
    CHECK(coarse.max_error <= 0.01);
    CHECK(fine.max_error <= 0.01);
    CHECK(fine.max_error <= coarse.max_error + 0.003);
    INFO("the floor layer: " << coarse.floor_error << " then " << fine.floor_error);
    CHECK(coarse.floor_error <= 0.02);
    CHECK(fine.floor_error <= 0.02);
    CHECK(fine.floor_error <= coarse.floor_error + 0.003);
    INFO("the floor's pair: " << coarse.floor_pair_error << " then " << fine.floor_pair_error);
    CHECK(coarse.floor_pair_error <= 0.02);
    CHECK(fine.floor_pair_error <= 0.02);
    CHECK(coarse.mean_rms_speed <= 0.025);   // the rms speed over the averaged second
    CHECK(fine.mean_rms_speed <= 0.01);
    test::require_no_gl_errors();
}

TEST_CASE("validate: the tank's average in half-second windows: each window's profile, the whole no worse than its worst window",
          "[validation]") {
    test::context();
    // 480 particles, 0.25 s settled, 1.2 s averaged: windows of 0.5, 0.5 and 0.2 s. The whole average's
    // profile is, layer by layer, a weighted mean of the windows' (weights: the particles each window
    // counted there), so its error in every layer is at most the largest of theirs.
    const scene::Scene s = case_scene("hydrostatic", 0.025f, scene::Solver::dfsph);
    const validation::HydrostaticResult r =
        validation::hydrostatic(s, shader::FileSource::embedded(), 0.25, validation::Relaxation{}, nullptr, 1.2);
    const double frames = std::ceil(1.2 / double(s.frame_dt)), window = std::ceil(0.5 / double(s.frame_dt));
    CHECK(r.average_seconds == Approx(frames * s.frame_dt));
    REQUIRE(r.windows.size() == 3);
    double worst = 0.0, worst_floor = 0.0;
    for (std::size_t k = 0; k < r.windows.size(); ++k) {
        INFO("window " << k << ": from " << r.windows[k].start << " s, interior " << r.windows[k].max_error << ", floor layer "
                       << r.windows[k].floor_error);
        CHECK(r.windows[k].start == Approx(double(k) * window * s.frame_dt));
        CHECK(r.windows[k].max_error > 0.0);
        worst = std::max(worst, r.windows[k].max_error);
        worst_floor = std::max(worst_floor, r.windows[k].floor_error);
    }
    INFO("whole: interior " << r.max_error << ", floor layer " << r.floor_error);
    CHECK(r.max_error <= worst * (1.0 + 1e-12));
    CHECK(r.floor_error <= worst_floor * (1.0 + 1e-12));
    // Pairs of layers pooled: each pair's error a weighted mean of its two layers' (the reference is
    // linear in z, taken at the pair's mean height), so at most the largest layer's.
    CHECK(r.pair_error > 0.0);
    CHECK(r.pair_error <= r.max_error * (1.0 + 1e-12));
    // The floor's pair the same way: at most the larger of its two layers' errors, and not both at once
    // zero.
    REQUIRE(r.layers.size() >= 2);
    const double e0 = std::abs(r.layers[0].pressure - r.layers[0].reference) / r.reference_scale,
                 e1 = std::abs(r.layers[1].pressure - r.layers[1].reference) / r.reference_scale;
    CHECK(r.floor_error == Approx(e0).epsilon(1e-12));
    CHECK(r.floor_pair_error > 0.0);
    CHECK(r.floor_pair_error <= std::max(e0, e1) * (1.0 + 1e-12));
    // The windows are not one profile repeated: the column moves (docs/VALIDATION.md).
    CHECK(r.windows[0].max_error != r.windows[1].max_error);
    // Each layer's rms speed over the average, and its vertical part: pooled over the layers (weighted by
    // their particles) the root of the mean square speed over the average, at least the mean of the
    // frames' rms speeds (Jensen's inequality; 2 % for the layers' whole particles a frame, rounded).
    double square = 0.0, particles = 0.0;
    for (const auto& l : r.layers) {
        INFO("layer at " << l.z << " m: rms " << l.rms_speed << ", vertical " << l.rms_vertical);
        CHECK(l.rms_speed > 0.0);
        CHECK(l.rms_vertical > 0.0);
        CHECK(l.rms_vertical <= l.rms_speed * (1.0 + 1e-12));
        square += double(l.particles) * l.rms_speed * l.rms_speed, particles += double(l.particles);
    }
    CHECK(std::sqrt(square / particles) >= r.mean_rms_speed * (1.0 - 0.02));
    test::require_no_gl_errors();
}

TEST_CASE("validate: the tank at rest as shipped (PBF) against rho0 g (H - z), at two spacings", "[validation]") {
    test::context();
    // media/scenes/hydrostatic.json ships PBF at 8 substeps of 4 iterations at 0.0125 m, scaled with
    // the spacing (docs/PBF.md "Resolution"): 4 at 0.025 m, 5 at 0.02 m. Its `sph.why` says the column
    // holds hydrostatic pressure as closely as DFSPH's and stiller. Measured on llvmpipe
    // (docs/VALIDATION.md "The tank at rest as shipped"): interior 0.21 and 0.19 of rho0 g H, floor
    // layer 1.10 and 1.04 (the boundary term's doubled floor, as with DFSPH), rms speed 0.030 and 0.022
    // m/s against DFSPH's 0.11 and 0.08 here.
    const auto& shaders = shader::FileSource::embedded();
    const scene::Scene coarse_scene = scene::with_spacing(validation::case_scene("hydrostatic"), 0.025f, "test");
    const scene::Scene fine_scene = scene::with_spacing(validation::case_scene("hydrostatic"), 0.02f, "test");
    REQUIRE(coarse_scene.sph.solver == scene::Solver::pbf);
    CHECK(coarse_scene.sph.pbf.substeps == 4);
    CHECK(fine_scene.sph.pbf.substeps == 5);
    const validation::HydrostaticResult coarse = validation::hydrostatic(coarse_scene, shaders, 0.5, validation::Relaxation{});
    const validation::HydrostaticResult fine = validation::hydrostatic(fine_scene, shaders, 0.5, validation::Relaxation{});
    // The floor layer within its known doubling plus a quarter (it reads 2.1 times hydrostatic at most);
    // stiller than DFSPH's bound by four: a fortieth of the free-fall speed, 0.055 m/s.
    check_columns(coarse, fine, 1.25, 0.025);
    test::require_no_gl_errors();
}

TEST_CASE("validate: DFSPH tank with the boundary rows from a relaxed start", "[validation]") {
    test::context();
    // cases.h Relaxation: frames from rest, velocities zeroed after each, here for at most 1 s at
    // 0.025 m (480 particles), until a frame from rest ends within a bound. With the boundary rows'
    // kappa_b starting hydrostatic (docs/DFSPH.md (D9)) the lattice starts held: measured on llvmpipe
    // 0.0033 m/s rms after the first frame, where from kappa_b = 0 it ended at 0.083 m/s and the
    // relaxation levelled off at 0.008-0.013 m/s (docs/VALIDATION.md "Where the motion at rest comes
    // from"). Frames from rest then end around hydrostatic_relaxation()'s 1 % of g frame_dt (0.0016
    // m/s), at 0.0025-0.01 m/s over 60 frames (llvmpipe, the plan two frames back:
    // Fluid::planning_record()), and whether one meets it is the trajectory's (docs/VALIDATION.md "The
    // relaxed start"). So the bound here is 2 % of g frame_dt (0.0033 m/s), met at the 9th frame
    // (0.0025 m/s): what this test measures is that the relaxation relaxes, and the rows' hydrostatic
    // start (the first frame within 0.005 m/s).
    // The plain solve, as measured: with the scene's own weaker warm start (w = 0.75, the test
    // above) each frame from rest starts its steps a quarter short of the column's pressure, and a frame
    // from rest ends at about 0.02 m/s rms (60 frames, llvmpipe), so the relaxation never reaches its
    // bound; what this test measures is the relaxation and the rows' hydrostatic start.
    scene::Scene s = with_plain_solve(case_scene("hydrostatic", 0.025f, scene::Solver::dfsph));
    s.sph.boundary_rows = true;
    validation::Relaxation relax = validation::hydrostatic_relaxation(s);
    CHECK(relax.rms_speed == Approx(0.01 * 9.81 * s.frame_dt));
    relax.rms_speed *= 2.0;
    relax.max_frames = int(std::ceil(1.0 / s.frame_dt));
    const validation::HydrostaticResult r = validation::hydrostatic(s, shader::FileSource::embedded(), 0.5, relax);
    // The same relaxation with its snapshots handed over as late as the ring allows (frames more from
    // rest run after the one that met the bound): the same start, so the same run, to the bit.
    validation::Relaxation late = relax;
    late.late_snapshots = true;
    const validation::HydrostaticResult l = validation::hydrostatic(s, shader::FileSource::embedded(), 0.5, late);
    CHECK(l.relax_frames == r.relax_frames);
    CHECK(l.relax_steps == r.relax_steps);
    CHECK(l.relax_rms_speeds == r.relax_rms_speeds);
    CHECK(l.relax_max_speed == r.relax_max_speed);
    CHECK(l.steps == r.steps);
    CHECK(l.max_error == r.max_error);
    CHECK(l.floor_error == r.floor_error);
    CHECK(l.mean_rms_speed == r.mean_rms_speed);
    REQUIRE(r.relax_rms_speeds.size() == std::size_t(r.relax_frames));
    REQUIRE(r.relax_frames >= 2);
    INFO("relaxation: " << r.relax_frames << " frames, rms " << r.relax_rms_speeds.front() << " then " << r.relax_rms_speeds.back()
                        << " m/s; run: interior " << r.max_error << ", floor layer " << r.floor_error << ", rms speed "
                        << r.mean_rms_speed << " m/s over the half second");
    CHECK(r.relax_rms_speeds.front() <= 0.005);
    CHECK(r.relax_frames <= relax.max_frames);
    CHECK(r.relax_steps >= std::uint64_t(r.relax_frames));
    // The relaxation reaches its bound within the second, and ends there.
    CHECK(r.relaxed);
    CHECK(r.relax_rms_speeds.back() <= relax.rms_speed);
    CHECK(r.relax_frames < relax.max_frames);
    // The measured run from the relaxed start keeps the lattice start's bounds (the test above): the
    // motion of about 0.05 m/s rms comes back within the first second whatever the start
    // (docs/VALIDATION.md "The relaxed start"), so the start does not buy tighter ones.
    CHECK(r.max_error <= 0.25);
    CHECK(r.floor_error <= 0.15);
    CHECK(r.mean_rms_speed <= 0.1 * std::sqrt(2.0 * 9.81 * r.height));
    test::require_no_gl_errors();
}

TEST_CASE("validate: DFSPH's standing wave keeps the period of linear theory", "[validation]") {
    test::context();
    // 0.4 m tank, a 0.1 m block at dx = 0.0133 m: the lattice's 7 layers, H = 0.0931 m deep (the depth
    // the reference uses), A = H/10, 30 columns of 3, three periods; each column holds round(η/dx)
    // layers at rest density (engine/validation/cases.cpp). T_linear = 2π/√(g k tanh kH) with k = π/L.
    // Bound on |T - T_linear| / T_linear: the depth SPH sees is uncertain by half a spacing at the floor
    // and at the surface, and dT/T = -(k sech^2(kH) / (2 tanh(kH))) dH = -3.5 /m x 0.0067 m = 2.3 %;
    // the amplitude's second-order shift (k A)^2 = 0.5 %: 3 %. Measured on llvmpipe: 2.0 % (1.2 % before the
    // defaults of 2026-11-29, eta = 0.1 % with eta_p = 1 %; docs/VALIDATION.md). The mode
    // must oscillate (at least four mean crossings after the first quarter period) and lose energy at
    // least as fast as the bulk's 2 nu k^2 (the walls' boundary layers and SPH's own dissipation add).
    const validation::StandingWaveResult r =
        validation::standing_wave(case_scene("standing-wave", 0.0133f, scene::Solver::dfsph), shader::FileSource::embedded());
    INFO("period " << r.period << " s against " << r.period_theory << " s (error " << r.period_error << "), decay " << r.decay_rate
                   << " /s against the bulk's " << r.decay_theory << " /s, " << r.half_periods << " half periods");
    const double H = 7.0 * 0.0133, k = 3.14159265358979 / 0.4;
    CHECK(r.depth == Approx(H).epsilon(1e-5));
    CHECK(r.period_theory == Approx(2.0 * 3.14159265358979 / std::sqrt(9.81 * k * std::tanh(k * H))).epsilon(1e-6));
    CHECK(r.half_periods >= 4);
    CHECK(r.period_error < 0.03);
    CHECK(r.decay_rate > r.decay_theory);
    CHECK(r.stats.energy_drift < 0.0);
}


TEST_CASE("validate: the surge's pressure on the wall it strikes against Lobovsky et al. (2014) at H/dx = 24, DFSPH's two walls",
          "[validation]") {
    test::context();
    // The case's geometry (H = 0.3 m, the wall 1.01 m from the column) at dx = 0.0125 m, the tank 0.075 m
    // wide (six particles; the probe's strip the middle half) to keep it small, run to T = 5.6, past the
    // compared run-up T in [3, 5.5]. DFSPH with free-slip walls, and with the no-slip walls the dam break
    // ships (sph.boundary_viscosity 1e-3 m^2/s, docs/DFSPH.md (D7)).
    scene::Scene free_slip = case_scene("impact-pressure", 0.0125f, scene::Solver::dfsph);
    free_slip.tank_max.z = 0.075f;
    free_slip.blocks.front().max.z = 0.075f;
    REQUIRE(free_slip.sph.boundary_viscosity > 0.0f);   // the case's scene has the dam break's walls
    scene::Scene no_slip = free_slip;
    free_slip.sph.boundary_viscosity = 0.0f;
    const auto& shaders = shader::FileSource::embedded();
    const validation::ImpactPressureResult f = validation::impact_pressure(free_slip, shaders, nullptr, 5.6);
    const validation::ImpactPressureResult n = validation::impact_pressure(no_slip, shaders, nullptr, 5.6);
    REQUIRE(f.sensors.size() == 3);
    REQUIRE(n.sensors.size() == 3);
    CHECK(f.particles == 48u * 24u * 6u);
    for (const auto* r : {&f, &n})
        for (const auto& s : r->sensors) {
            INFO((r == &f ? "free-slip " : "no-slip ") << s.name << ": impact at T = " << (s.onset_simulated ? *s.onset_simulated : -1.0)
                                                       << " (experiment " << *s.onset_measured << "), run-up mean " << s.mean_simulated
                                                       << " (experiment " << s.mean_measured << "), rms " << s.rms_error);
            REQUIRE(s.onset_measured);
            CHECK(s.compared > 10);
            // No surge outruns the dry-bed dam break of shallow-water theory (Ritter), whose front moves at
            // 2 sqrt(gH): the wall 1.01 m = 3.37 H away is reached no sooner than T = 3.37 / 2 = 1.68.
            if (s.onset_simulated) CHECK(*s.onset_simulated >= 1.68);
        }
    // The foot of the wall is struck first: P1 (3 mm) and P3 (30 mm) read the impact, and P4 (80 mm) no
    // sooner than P1, as the run-up climbs.
    for (const auto* r : {&f, &n}) {
        REQUIRE(r->sensors[0].onset_simulated);
        REQUIRE(r->sensors[1].onset_simulated);
        if (r->sensors[2].onset_simulated) CHECK(*r->sensors[2].onset_simulated >= *r->sensors[0].onset_simulated - 0.05);
    }
    REQUIRE(f.sensors[2].onset_simulated);   // with free-slip walls the run-up reaches 80 mm within the run
    // Free-slip against the experiment (measured on llvmpipe: P1's impact 0.15 late, the run-up at P1 and
    // P3 6 % over and 6 % under, rms 0.08 of rho0 g H at both; on the H200 at the full width 0.12 late,
    // 25 % and 15 % over, rms 0.17 and 0.12): P1's impact within 0.3 of T, the run-up at P1 and P3 within
    // 30 % and its rms within 0.2.
    CHECK(std::abs(*f.sensors[0].onset_simulated - *f.sensors[0].onset_measured) < 0.3);
    for (int k : {0, 1}) {
        const auto& s = f.sensors[std::size_t(k)];
        CHECK(std::abs(s.mean_simulated / s.mean_measured - 1.0) < 0.3);
        CHECK(s.rms_error < 0.2);
    }
    // The no-slip walls' drag slows the surge: its impact later and its run-up weaker than free-slip's
    // (measured: 0.35 later at P1, the run-up at P1 and P3 0.38 and 0.31 against 0.67 and 0.58). At this
    // width their kernel support reaches four of the six particles across (docs/VALIDATION.md "Impact
    // pressure").
    CHECK(*n.sensors[0].onset_simulated > *f.sensors[0].onset_simulated + 0.1);
    for (int k : {0, 1}) CHECK(n.sensors[std::size_t(k)].mean_simulated < f.sensors[std::size_t(k)].mean_simulated);
    CHECK(f.stats.guard_spikes == 0);
    CHECK(n.stats.guard_spikes == 0);
    test::require_no_gl_errors();
}

TEST_CASE("validate: the surge's pressure on a box against Kleefsman et al. (2005) at H/dx = 10, DFSPH as the case ships",
          "[validation]") {
    test::context();
    // SPHERIC's test 2 (H = 0.55 m, the box's face 1.1675 m = 2.12 H from the column) at dx = 0.055 m,
    // 3,960 particles, to T = 7.5, past the compared window T in [2.5, 7]. DFSPH with the case's walls
    // (the dam break's no-slip ones).
    const validation::ImpactPressureResult r =
        validation::obstacle_impact(case_scene("obstacle-impact", 0.055f, scene::Solver::dfsph), shader::FileSource::embedded(), nullptr, 7.5);
    REQUIRE(r.sensors.size() == 2);
    CHECK(r.face == Approx(0.8245));
    CHECK(r.sample_offset == 0.5);   // DFSPH: the frame's mean pressure, of its middle
    for (const auto& s : r.sensors) {
        INFO(s.name << ": impact at T = " << (s.onset_simulated ? *s.onset_simulated : -1.0) << " (experiment " << *s.onset_measured
                    << "), window mean " << s.mean_simulated << " (experiment " << s.mean_measured << "), rms " << s.rms_error);
        REQUIRE(s.onset_measured);
        REQUIRE(s.onset_simulated);
        CHECK(s.compared > 5);
        // Ritter's dry-bed front at 2 sqrt(gH) reaches the face no sooner than T = 2.12 / 2 = 1.06.
        CHECK(*s.onset_simulated >= 1.06);
        // Measured on llvmpipe: the impact 0.27 (P1) and 0.23 (P3) late at this resolution with the
        // no-slip walls (docs/VALIDATION.md "Impact pressure"), the flow piled against the box 10 % (P1)
        // and 22 % (P3) under the experiment's, rms 0.13 and 0.16: within 0.45, 30 % and 0.2.
        CHECK(*s.onset_simulated - *s.onset_measured < 0.45);
        CHECK(std::abs(s.mean_simulated / s.mean_measured - 1.0) < 0.3);
        CHECK(s.rms_error < 0.2);
    }
    CHECK(r.stats.guard_spikes == 0);
    test::require_no_gl_errors();
}
