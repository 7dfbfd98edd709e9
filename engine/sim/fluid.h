#pragma once
// The fluid's state: what every SPH solver (sim/solver.h), the turbulence (turbulence/force.h) and
// the surface (surface/level_set.h) read and write, apart from the algorithm that advances it.
//
//     positions, velocities          vec4 per particle, in the neighbour grid's cell order of the
//                                    last rebuild_grid(), moved by the last integration
//     densities                      vec4 (rho, p, solver's own, flags): written by a solver's density
//                                    pass, which also writes the neighbour masks
//                                    (glsl/sim/fluid/density_walk.glsl)
//     accelerations                  vec4: the step's non-pressure accelerations (WCSPH: all of them)
//     carried arrays                 per-particle arrays that the reorder moves with the particles
//     grid, cell ranges, boundary    the neighbour grid, and the boundary particles with their psi_b
//     step record (StepState)        the adaptive time step, the guard's findings, the solver's
//                                    iteration record; read back frames late (planning_record());
//                                    after it the frame's extremes per span of particles (FrameExtreme)
//
// and the passes that belong to the state, not to a solver:
//
//     begin_frame()       "begin-frame"        opens the frame's StepState record
//     choose_time_step()  "choose-time-step"   docs/SPH.md (7), docs/DFSPH.md (D8), on the GPU
//     rebuild_grid()      "hash", "sort.*", "reorder"   the state into cell order
//     integrate()         "integrate"          docs/SPH.md (6) and (8): the explicit step
//     emit()              "emit"               the emitter pours a sheet of parked particles (run)
//     move_paddle()       "hash", "sort.*", "reorder", "boundary-volume", "boundary-cells": the
//                         boundary re-sorted about the paddle, docs/SPH.md (9) (run)
//     end_frame()         "record-extremes"    the frame's fastest and densest particles into the record
//                         "diagnostics"        queues the record's readback
//
// The CPU reads nothing back in the frame: the substeps a frame are planned from the record of the
// frame plan_lag() frames before it (enough at the smallest stable dt it saw), which the readback ring's
// back-pressure has always returned by then, and the dt each step uses is chosen on the GPU. A record
// that breaks a guard criterion is kept as instability(); the caller stops the run.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/readback.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/grid.h"
#include "sim/guard.h"
#include "sim/state_io.h"

namespace ranryu::scene { struct Scene; }

namespace ranryu::sim {

// The kernel's support radius h for particles `spacing` apart: h = 2 dx (docs/SPH.md, symbols table).
constexpr float kernel_support(float spacing) { return 2.0f * spacing; }

// SphParams for a scene (docs/SPH.md symbols table), with `count` fluid and `boundary` particles. The
// time step's sound speed is the scene's: WCSPH's c, 0 for DFSPH (docs/DFSPH.md (D8)).
gpu::SphParams sph_params(const scene::Scene& s, std::size_t count, std::size_t boundary);
GuardLimits guard_limits(const scene::Scene& s);

// Where the emitter pours (Fluid::emit): a side x side sheet, spacing dx, in the horizontal plane
// through `nozzle` (over the middle of the tank, at 0.85 of its height, 2 dx under a lid), moving at
// `velocity` = dx / frame_dt downwards, so that one sheet a frame leaves a column at the spacing
// (gravity only spreads it). side: 0.15 of the tank's narrower horizontal extent, in [2, 16] spacings.
struct EmitterShape {
    glm::vec3 nozzle{0.0f};
    int side = 2;
    glm::vec3 velocity{0.0f};
};
EmitterShape emitter_for(const scene::Scene& s);
// The parked particles' places (Fluid, the emitter's budget): `count` of them, below the tank.
std::vector<glm::vec4> parked_positions(const scene::Scene& s, std::size_t count);

class Fluid {
public:
    // Samples the boundary, computes its psi_b and the cells near it (start-up passes
    // "boundary-volume", "boundary-cells"), and places the scene's particles.
    Fluid(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene);
    // Whether the density pass records the boundary's masks beside the fluid's (neighbours.glsl): with
    // sph.neighbour_masks, where both fit one storage block for `count` particles (this context's bound).
    static bool boundary_masks(const scene::Scene& s, std::size_t count);
    // The most bytes one storage block holds in this context (GL_MAX_SHADER_STORAGE_BLOCK_SIZE; llvmpipe
    // 128 MiB), and at most 2^32 words: the shaders index the masks with 32-bit uints.
    static std::size_t storage_block_bytes();
    // InputError naming the scene, `what` takes `bytes`, the bound and the sph key `off` that turns it
    // off, where `bytes` exceed storage_block_bytes().
    static void require_one_block(const scene::Scene& s, const std::string& what, std::size_t bytes, const std::string& off);
    // Device memory the constructor keeps for `count` particles and `boundary` boundary particles
    // (scene.particle_count(), boundary_count()): the state, the masks, the boundary, the grid and its
    // sort (frame/memory.h). `transient`: what start-up holds besides, and frees.
    static std::size_t bytes_for(const scene::Scene& scene, std::size_t count, std::size_t boundary);
    static std::size_t transient_bytes(std::size_t boundary);
    // The step record's buffer: the StepState and its FrameExtreme entries for `count` particles.
    static std::size_t step_bytes(std::size_t count);
    // The boundary particles a Fluid of `scene` samples: sample_boundary()'s count at its layers.
    static std::size_t boundary_count(const scene::Scene& scene);
    // Runs a neighbour walk visits in `scene`: 9 merged x-rows, or 27 cells (glsl/sim/fluid/fluid.glsl).
    static int neighbour_runs(const scene::Scene& scene);
    // Device memory of one carry() of `words` words a particle.
    static std::size_t carried_bytes(std::size_t count, std::uint32_t words);

    // ---- the frame
    void begin_frame(std::uint64_t frame_index);   // plans substeps_this_frame() from planning_record()
    int substeps_this_frame() const { return substeps_; }
    // Queues the frame's record. With the GPU more than record_depth() frames behind, first waits for
    // the oldest record in flight (the ring's back-pressure): the CPU runs at most that far ahead.
    void end_frame();
    void choose_time_step();
    void rebuild_grid();   // the masks are no longer current
    void integrate();      // v += dt a, x += dt v, the projection and the guard (the masks are no longer current)

    // ---- the paddle (scene.paddle_radius > 0; sim/boundary.h): a kinematic sphere, on or parked.
    // Places its boundary particles about `center` (m), sets its projection entry (radius, velocity u
    // in m/s: docs/SPH.md (9)) and re-sorts the boundary with psi_b and the near-boundary cells
    // ("hash", "sort.*", "reorder", "boundary-volume", "boundary-cells"), inside the caller's timer
    // frame, before a step. Off: the particles wait at paddle_park(), the entry's radius is 0. Uploads
    // the paddle's few boundary particles and 32 bytes, allocates nothing; when only the velocity
    // changes, the 32 bytes alone. sim::Simulation::set_paddle() moves it a substep at a time.
    // `scale` in (0, 1]: the paddle grown to that part of its radius (offsets and cell volumes scaled).
    void move_paddle(glm::vec3 center, glm::vec3 velocity, bool on, float scale = 1.0f);
    bool has_paddle() const { return !paddle_offsets_.empty(); }
    // Counts the boundary's re-sorts (move_paddle): a solver that keeps per-boundary-particle state by
    // index (DFSPH's boundary rows, docs/DFSPH.md (D9)) drops it when this changes.
    std::uint64_t boundary_generation() const { return boundary_generation_; }
    float paddle_radius() const { return paddle_radius_; }

    // ---- the emitter (scene.particle_budget above scene.particle_count()): count() particles are
    // allocated, the scene's and the rest parked (position.w = -1, glsl/sim/fluid/fluid.glsl) on a
    // lattice below the tank, farther apart and from everything else than a support: the density and
    // neighbour walks visit nothing for them, the integrations leave them at rest and out of the
    // guard's records, the surface's bounds and the impostors skip them. emit(), pass "emit", pours
    // one sheet of emitter_for(scene) from the parked ones, on the GPU (StepState.live_count counts the
    // particles not parked: the count never comes back to the CPU but in the records).
    void emit();
    bool has_budget() const { return count_ > scene_count_; }
    std::size_t scene_count() const { return scene_count_; }

    // ---- the state, in the cell order of the last rebuild_grid()
    std::size_t count() const { return count_; }
    std::size_t boundary_count() const { return boundary_count_; }
    const gpu::SphParams& params() const { return params_; }
    // Live settings (run's panel): the kinematic viscosity (m^2/s) and the Courant number of the time
    // step, written into the SphParams block between frames; every later dispatch reads them. A fixed
    // step (cfl 0: PBF) keeps no Courant number.
    void set_viscosity_and_cfl(float viscosity, float cfl);
    const gl::Buffer& positions() const { return position_[current_]; }
    const gl::Buffer& velocities() const { return velocity_[current_]; }
    const gl::Buffer& densities() const { return density_; }
    const gl::Buffer& accelerations() const { return accel_; }
    const gl::Buffer& boundary() const { return boundary_; }
    const gl::Buffer& step_state() const { return step_; }
    const CellRanges& cell_ranges() const { return ranges_; }
    NeighbourGrid& grid() { return grid_; }
    const NeighbourGrid& grid() const { return grid_; }

    // Every buffer of the state by the storage block name the passes declare (glsl/sim/fluid/*.glsl):
    // Positions, Velocities, Density, Accelerations, Step, CellRange, SortedKeys, Boundary,
    // BoundaryCellRange, BoundaryNear, Obstacles, NeighbourMasks (when on) and each
    // carried array under its name. Binds the SphParams and GridParams uniform blocks too.
    shader::StorageSet bind_state();
    // "#define" lines every neighbour pass of this fluid is built with: RANRYU_MERGE_ROWS (9 merged
    // rows of linear keys instead of 27 cells), RANRYU_NEIGHBOUR_MASKS (sph.neighbour_masks) and with
    // it RANRYU_BOUNDARY_MASKS, and for PBF RANRYU_BOUNDARY_SKIN (glsl/sim/fluid/neighbours.glsl).
    std::string neighbour_defines() const;

    // The density pass's (run start, mask) pairs, 2·runs·count() uints for the fluid (sph.neighbour_masks)
    // and as many again for the boundary (boundary_masks()), and whether they describe the current cell
    // order and positions: a density pass sets it, and rebuild_grid() and every integration clear it.
    const gl::Buffer& neighbour_masks() const { return neighbours_; }
    bool neighbour_masks_current() const { return masks_current_; }
    void set_neighbour_masks_current(bool current) { masks_current_ = current && neighbours_.id() != 0; }
    int neighbour_runs() const { return runs_; }   // runs a neighbour walk visits: 9 merged rows or 27 cells

    // ---- carried arrays: `words` 32-bit words per particle, starting as `fill`: one particle's
    // words for every particle, or every particle's in the scene's initial order; the reorder moves
    // them with the particles (at most NeighbourGrid::max_carried). `block` is the storage block name
    // bind_state() gives the current one.
    int carry(std::string block, std::uint32_t words, const std::vector<std::uint32_t>& fill);
    const gl::Buffer& carried(int id) const { return carried_[std::size_t(id)].buffer[carried_current_]; }
    gl::Buffer& carried(int id) { return carried_[std::size_t(id)].buffer[carried_current_]; }

    // ---- a solver's fused integration writes the next state into the other buffers, then swaps
    gl::Buffer& next_positions() { return position_[1 - current_]; }
    gl::Buffer& next_velocities() { return velocity_[1 - current_]; }
    void swap_state() { current_ = 1 - current_; masks_current_ = false; }

    // ---- records: the latest StepState read back (frames late), and the first instability seen
    const std::optional<gpu::StepState>& last_record() const { return last_; }
    // What a frame is planned from (its substeps here, a solver's iteration caps): the record of the
    // frame opened plan_lag() = record_depth() + 1 frames before it, none for the first plan_lag()
    // frames. The readback ring holds record_depth() records in flight and, to reuse a slot, waits for
    // the record in it (back-pressure, gl/fence_ring.h), so when frame n opens the record of frame
    // n - plan_lag() has always been handed over. A plan that reads that one, and never a newer one that
    // happened to arrive already, is the same however fast the GPU and the CPU run: a run is determined
    // by its scene (a resumed one by its checkpoint), not by the timing of its readbacks
    // (docs/METHOD.md §0). Newer records still feed the guard, the sink and last_record() as
    // they arrive.
    // record_depth(): one where the records plan the steps (the CPU builds frame n while the GPU runs
    // frame n - 1, the plan two frames old: docs/PERFORMANCE.md "The plan pinned to one record"), four
    // where they plan nothing (a fixed step, PBF's: docs/PBF.md (P1)).
    static constexpr int most_plan_lag = 5;
    static int record_depth(const scene::Scene& scene);
    int plan_lag() const { return plan_lag_; }
    const std::optional<gpu::StepState>& planning_record() const { return plan_; }
    // Tests: records handed over only when the ring needs their slot again, the latest it allows
    // (gl::AsyncReadback::hand_over_only_when_reused).
    void hand_over_records_late(bool on) { readback_.hand_over_only_when_reused(on); }
    const std::optional<Instability>& instability() const { return instability_; }
    // The guard's spikes that passed (guard.h): frames past the density or speed bound, and the largest.
    const Guard& guard() const { return guard_; }
    // Every record, as it arrives (validation series). Set before the first frame.
    void set_record_sink(std::function<void(const gpu::StepState&)> sink) { sink_ = std::move(sink); }
    void poll_records() { readback_.poll(); }   // collects what has arrived (never waits)
    void drain_records() { readback_.drain(); } // waits for every queued one (end of a run)

    // Frames of `frame_dt` made of substeps of exactly `dt` when stable allows: PBF's fixed step
    // (docs/PBF.md (P1)), and tests that need a known dt.
    void set_fixed_dt(float dt) { fixed_dt_ = dt; }

    // ---- checkpoints (frame/checkpoint.h): the state a run carries from frame to frame, in the cell
    // order of the last rebuild_grid(): positions, velocities, densities, accelerations, the StepState
    // (the clock, the next step's dt), every carried array and the emitter's counter; on the CPU the
    // substep plan's inputs (the records of the last plan_lag() frames, the frames opened) and the last
    // record seen. The boundary is the scene's and is rebuilt by the constructor. Refused
    // (StateIo::refuse): saving a fluid whose paddle has moved, loading records that do not cover the
    // frames before the last. Saving with a frame open or records not back is a caller's error (Error;
    // write_checkpoint() drains first). Loading needs a fluid built from the same scene.
    void persist(StateIo& io);

    // ---- tests
    // Replaces the fluid state (count() positions and velocities, any order); the next
    // rebuild_grid() sorts it into cell order.
    void upload_state(const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v);
    // Sets every velocity (the whole vec4) to zero on the GPU, after the commands issued so far: a
    // validation case's relaxation (validation/cases.h) between frames from rest.
    void stop_particles();

private:
    void on_record(std::uint64_t opened, const void* bytes);
    void compute_boundary(const std::vector<glm::vec4>& wall);
    void rebuild_boundary();   // raw_ into boundary_: the sort, psi_b, the near-boundary cells

    profile::GpuTimer& timer_;
    profile::PassId begin_pass_, step_pass_, integrate_pass_, extremes_pass_, diag_pass_, boundary_pass_, boundary_cells_pass_, emit_pass_;
    std::string defines_;
    shader::Program begin_, choose_, integrate_, record_extremes_, boundary_volume_, flag_boundary_, emit_;
    EmitterShape emitter_;
    gl::Buffer emit_claimed_;   // the emit pass's slot counter (a uint), with a budget only
    std::size_t scene_count_ = 0;
    gpu::SphParams params_{};
    Guard guard_;
    float frame_dt_;
    int max_substeps_;
    NeighbourGrid grid_;
    std::size_t count_ = 0, boundary_count_ = 0;
    gl::Buffer position_[2], velocity_[2];
    int current_ = 0;
    gl::Buffer density_, accel_, boundary_, step_, params_ubo_;
    gl::Buffer neighbours_;   // sph.neighbour_masks only
    bool masks_current_ = false;
    int runs_ = 9;
    gl::Buffer obstacles_;       // obstacle_shapes(): the integration's last-resort projection (docs/SPH.md (8))
    gl::Buffer boundary_near_;   // uint per key: a boundary particle within the 27 cells (start-up, and when the paddle moves)
    // The boundary before its sort and the sort's scratch: freed after start-up, kept with a paddle.
    gl::Buffer raw_, zeros_, zeros_sorted_, weighted_;
    std::vector<glm::vec4> paddle_offsets_, paddle_placed_;   // paddle_offsets(); the placed ones (reused)
    std::size_t paddle_first_ = 0;                             // its first boundary particle in raw_
    float paddle_radius_ = 0.0f;
    glm::vec3 paddle_park_{0.0f}, paddle_at_{0.0f};   // where it waits off; where its particles are
    float paddle_scale_ = 1.0f;                       // the part of its radius they stand at
    std::uint64_t boundary_generation_ = 0;
    CellRanges ranges_, boundary_ranges_;
    struct Carried {
        std::string block;
        std::uint32_t words;
        gl::Buffer buffer[2];
    };
    std::vector<Carried> carried_;
    int carried_current_ = 0;
    gl::AsyncReadback readback_;
    std::optional<gpu::StepState> last_;
    // The records of the last most_plan_lag frames, each in slot (its frame's opening count) %
    // most_plan_lag beside that count (~0: none), and the one this frame was planned from.
    int plan_lag_;
    std::uint64_t opened_ = 0;   // frames opened: the readback's tags
    bool open_ = false;          // between begin_frame() and end_frame()
    std::array<gpu::StepState, most_plan_lag> history_{};
    std::array<std::uint64_t, most_plan_lag> history_opened_ = unheard();
    std::optional<gpu::StepState> plan_;
    static std::array<std::uint64_t, most_plan_lag> unheard() {
        std::array<std::uint64_t, most_plan_lag> a;
        a.fill(~std::uint64_t(0));
        return a;
    }
    bool has_records_of_last_frames() const;   // of the last min(opened_, plan_lag_) frames
    std::optional<Instability> instability_;
    std::function<void(const gpu::StepState&)> sink_;
    int substeps_ = 1;
    float dt_estimate_;
    std::optional<float> fixed_dt_;
};

}  // namespace ranryu::sim
