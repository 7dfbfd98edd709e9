#pragma once
// Divergence-free SPH (docs/DFSPH.md; Bender & Koschier 2015, 2017). A step:
//
//     "choose-time-step", "hash", "sort.*", "reorder"       (Fluid)
//     "dfsph.density"                rho, factor (D2), flags and masks, the non-pressure accelerations
//                                    (D7), the divergence solve's source (D5), warm start and first
//                                    pressure accelerations
//     (hooks.after_density, hooks.add_accelerations)
//     "dfsph.divergence.solve"       (D6) iterations: the first correct_pressure.comp direct, then
//                                    accelerate.comp and correct_pressure.comp issued in pairs,
//                                    dispatched indirectly
//     "dfsph.divergence.finish"      v += dt (a^p(kappa_v) + a)
//     "dfsph.pressure.predict"       the density solve's source (D4), warm start and first a^p
//     "dfsph.pressure.solve"         (D6) iterations, likewise
//     "dfsph.integrate"              v += dt a^p(kappa), x += dt v, docs/SPH.md (8), the guard
//
// With sph.gradient_correction the density pass also computes each particle's kernel-gradient
// correction L_i, and every pressure acceleration is L_i times (D3)'s (docs/DFSPH.md (D11)).
//
// With the boundary rows of (D9) (sph.boundary_rows), the wall's own density of each boundary particle
// is computed when the boundary is built ("dfsph.boundary.wall": at the first step, and after the
// paddle moves), the density pass's walk also lists the boundary particles near the fluid as the
// step's rows and size_boundary_rows.comp closes the list (both timed as "dfsph.density"), each solve
// opens with "dfsph.boundary.prepare" (their sources, diagonals and warm start; the step's first also
// records each row's neighbour masks), and every iteration's correct_pressure.comp updates the rows
// too, in workgroups after the fluid's, walking the rows' masks. With sph.eliminate_boundary_rows the
// density solve's rows are no unknowns (docs/DFSPH.md (D13)): each of its iterations runs
// hand_off_excess.comp before correct_pressure.comp and extend_pressure.comp before accelerate.comp,
// over the rows, and extend_pressure.comp once after the last; all timed as "dfsph.pressure.solve".
//
// Convergence is decided on the GPU (correct_pressure.comp): once a solve's mean error is at most its
// bound after its minimum iterations, its remaining issued iterations dispatch zero workgroups. The
// CPU issues a cap of iterations a solve each step (next_iteration_cap()), learnt from the records that
// come back frames late, one a frame (Fluid::planning_record()): the scene's maximum until the first
// and after any step stopped at the cap, otherwise 1.5 times the most one step needed over the last
// records (the newest scaled to a plan of longer steps, iterations_at_plan()), plus two. Iterations run
// and the errors reached come back in StepState; a step that stops at its cap is counted there, and
// profile reports it.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/fluid.h"
#include "sim/solver.h"

namespace ranryu::sim {

// The rule of next_iteration_cap(): ceil(factor · needed) + margin.
struct IterationCapRule {
    double factor = 1.5, margin = 2.0;
    // The default, or RANRYU_DFSPH_CAP="FACTOR,MARGIN" (FACTOR in [1, 4], MARGIN a whole number in [0, 20]: to measure
    // another rule on one build); throws InputError naming the variable otherwise. Start-up only.
    static IterationCapRule from_environment();
};

// The iterations a solve is issued in the next frames, from the most one step `needed` over the recent
// records and whether the latest had a step `stopped` at its cap: ceil(factor · needed) + margin
// (`rule`), or `most` after a stop, within [least, most]. A stop means the cap fell behind what the
// steps need, as when the time step grows (docs/DFSPH.md, "The iteration cap"); the records that would
// show how far come back frames late, and a step cut short leaves its excess to the next as a kick, so
// the cap goes to the maximum at once, and comes back down with the records.
std::uint32_t next_iteration_cap(std::uint32_t needed, bool stopped, int least, int most, IterationCapRule rule = {});

// The most iterations a step of this frame needs, from a record's `most` at its `record_substeps` a
// frame, when this frame plans `planned` substeps: fewer, longer steps than the record's need
// proportionally more (ceil(most · record_substeps / planned), at most 10^6); more, shorter ones no
// fewer; `planned` <= 0: `most`. A solve's iterations grow about in proportion to its step
// (docs/DFSPH.md (D8): 15.5 a step at 0.8 ms, 59 at 3.3 ms, the density solve), and a plan lengthens
// its steps most at once when its first frames' estimate gives way to the records' step
// (docs/DFSPH.md "The iteration cap"). begin_frame() scales the newest record's need, of both solves,
// and takes the window's older records as they were.
std::uint32_t iterations_at_plan(std::uint32_t most, std::uint32_t record_substeps, int planned);

// The step the density solve's iterations allow (docs/DFSPH.md (D8)), the CPU's mirror of the GPU's
// next_iteration_dt() (glsl/sim/dfsph/dfsph.glsl), which the residual pass applies when a density solve
// ends: 0.9 times the step's stable dt after more than `shrink_above` iterations, 1.1 times after fewer
// than `grow_below`, the same between, within [least, most].
float next_iteration_dt(float stable_dt, std::uint32_t iterations, std::uint32_t shrink_above, std::uint32_t grow_below, float least,
                        float most);

class Dfsph final : public Solver {
public:
    Dfsph(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene, Fluid& fluid);
    // Whether the density pass stores the wall's gradient sum for the residual pass (dfsph.cpp wall_gradient()).
    static bool wall_gradient_stored(const scene::Scene& scene, std::size_t boundary);
    // Device memory the constructor allocates for `count` particles and `boundary` boundary particles
    // (the rows of (D9) when `rows`, the previous iterates of (D10) when `chebyshev`, (D11)'s L_i when
    // `correction`, the wall's gradient sum when `wall_gradient`; a row's neighbour masks take two words
    // for each of the `runs` runs of a walk), its carried warm start included (frame/memory.h).
    static std::size_t bytes_for(std::size_t count, std::size_t boundary, bool rows, bool chebyshev, bool correction, int runs,
                                 bool wall_gradient);
    scene::Solver kind() const override { return scene::Solver::dfsph; }
    double pressure_sample_offset() const override { return 0.5; }   // the frame's mean (integrate_pressure.comp)
    void begin_frame(Fluid& fluid) override;
    void step(Fluid& fluid, StepHooks& hooks) override;
    void persist(StateIo& io) override;

    // A step's stages, public for tests that compare each with the CPU reference; step() runs them
    // with the hooks between compute_density() and solve_divergence().
    void compute_density(Fluid& fluid);    // "dfsph.density"
    void solve_divergence(Fluid& fluid);   // iterations and "dfsph.divergence.finish"
    void predict_density(Fluid& fluid);    // "dfsph.pressure.predict"
    void solve_density(Fluid& fluid);      // iterations
    void integrate(Fluid& fluid);          // "dfsph.integrate"

    // The iterations a solve is issued this frame (its cap), and a way for tests to fix them.
    int issued_iterations() const { return int(params_.issued); }
    int issued_divergence_iterations() const { return int(params_.issued_divergence); }
    void set_issued_iterations(int density, int divergence);

    // Per-particle arrays, in the fluid's current cell order (tests).
    // The Kappa block (glsl/sim/dfsph/dfsph.glsl): vec4 (x_i, kappa_i) a particle, x_i the position the
    // density pass found it at; then, with the boundary rows of (D9), (kappa_b, kappa_v,b) floats per
    // boundary particle, kappa_b kept from step to step (with (D13) the extension of the last density
    // solve's kappa, and the second slot its rows' q_b after a step). read_kappa(): the solve's current
    // kappa_i, count() of them, then the rows' pairs; read_kappa_positions(): the x_i.
    const gl::Buffer& kappa() const { return kappa_; }
    std::vector<float> read_kappa() const;
    std::vector<glm::vec3> read_kappa_positions() const;
    // The Kappa block's floats for `count` particles and `rows` boundary rows (0 without (D9)): the
    // rows' pairs padded to whole vec4s, so that the passes reading it as vec4 kappa4[] read a row's
    // pair from an element inside the buffer, whatever the rows' parity.
    static std::size_t kappa_floats(std::size_t count, std::size_t rows);
    // Sets every row's kept (kappa_b, kappa_v,b) to 0, the fluid's (x_i, kappa_i) untouched: what a step
    // does when the boundary was re-sorted (the paddle moved), public for its test. Nothing without rows.
    void forget_boundary_kappa();
    // vec4: xyz a^p, w the source s_i; then, with sph.gradient_correction, (D11)'s L_i, two vec4 a
    // particle: (L_xx, L_yy, L_zz, L_xy), (L_xz, L_yz, det M_i, its blend s_i) (glsl/sim/dfsph/dfsph.glsl).
    const gl::Buffer& pressure_accelerations() const { return pressure_accel_; }
    // Whether this solver's density pass stores the wall's gradient sum, one vec4 a particle after the
    // above, for its residual passes (wall_gradient_stored()): tests say which residual they check.
    bool stores_wall_gradient() const { return wall_gradient_; }
    const gl::Buffer& warm_start() const;                                 // vec2: (kappa, dt kappa_v) of the last step
    const gl::Buffer& frame_pressure() const;   // vec2: (sum p dt, sum dt) over this frame's steps so far
    // Tests: replaces the warm start (count() pairs in the fluid's current order; the next
    // rebuild_grid() moves them with the particles).
    void upload_warm_start(const std::vector<glm::vec2>& kappa);
    const gl::Buffer& solve_states() const { return solve_; }             // SolveState, density at 0, divergence at RANRYU_DFSPH_SOLVE_STRIDE
    const gpu::DfsphParams& params() const { return params_; }
    // (D9), tests: this step's rows (BoundaryRowsState, then a uint mark per boundary particle), their
    // list (uint entries, kFreshRow's bit on the ones that were no row the step before) and the walls'
    // own density per boundary particle (compute_wall_density.comp); empty without rows.
    const gl::Buffer& boundary_rows() const { return rows_state_; }
    const gl::Buffer& boundary_list() const { return boundary_list_; }
    const gl::Buffer& row_masks() const { return row_masks_; }   // (run start, mask) a run a row, run-major
    const gl::Buffer& boundary_wall() const { return boundary_wall_; }

private:
    shader::StorageSet state(Fluid& fluid, int solve) const;
    void iterate(Fluid& fluid, int solve, int issued, profile::PassId pass);
    void upload_params();
    void open_solve(int solve);
    void prepare_rows(Fluid& fluid, int solve);   // "dfsph.boundary.prepare"
    void dispatch_rows(const shader::Program& program);   // indirectly over the step's rows

    profile::GpuTimer& timer_;
    profile::PassId density_pass_, divergence_solve_, divergence_finish_, predict_pass_, pressure_solve_, integrate_pass_,
        prepare_pass_, wall_pass_;
    // The dispatches within those passes (GpuTimer::pass(name, within): timed apart with profile
    // --detail): each solve's accelerate and correct passes by solve (0 the density solve), the rows'
    // sizing within the density pass, and (D13)'s two passes within the density solve.
    std::array<profile::PassId, 2> accelerate_passes_{}, correct_passes_{};
    profile::PassId size_rows_pass_, extend_pass_, hand_off_pass_;
    bool divergence_, rows_, correction_, eliminated_, wall_gradient_;
    shader::Program density_, accelerate_, correct_, finish_, predict_, integrate_;
    shader::Program size_rows_, prepare_rows_, wall_density_;   // (D9), built when rows_
    shader::Program extend_rows_, hand_off_rows_;               // (D13), built when eliminated_
    gpu::DfsphParams params_{};
    int least_, most_, most_divergence_;
    IterationCapRule cap_rule_;
    bool fixed_caps_ = false;
    std::array<glm::uvec2, 16> recent_{};   // the most iterations a step needed, of the last records
    std::size_t recent_next_ = 0;
    gl::Buffer params_ubo_, solve_, opened_, kappa_, pressure_accel_, kappa_previous_;
    // (D9), per boundary particle: the step's list entry and row, and the wall's own density
    // (compute_wall_density.comp); the rows' BoundaryRowsState followed by a mark per boundary particle;
    // the rows' neighbour masks (glsl/sim/dfsph/boundary_rows.glsl).
    gl::Buffer boundary_list_, boundary_row_, boundary_wall_, rows_state_, row_masks_;
    Fluid& fluid_;
    int warm_;
    int frame_pressure_;   // (sum p dt, sum dt) over the frame's steps: docs/DFSPH.md "The pressure a frame"
    std::uint64_t boundary_generation_ = 0;   // Fluid::boundary_generation() the kept kappa_b belong to
    std::uint64_t wall_generation_ = ~std::uint64_t(0);   // ... and boundary_wall_ (none yet)
};

}  // namespace ranryu::sim
