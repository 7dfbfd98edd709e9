#pragma once
// Weakly compressible SPH on the GPU (docs/SPH.md). A frame:
//
//     begin_frame()                       "begin-frame"       opens the frame's StepState record
//     substep() × N                       "choose-time-step"  eq. (7), on the GPU
//                                         "hash", "sort.*", "reorder"   (NeighbourGrid)
//                                         "density"           eqs. (2), (3)
//                                         "wavelet"           turbulence only: ê (METHOD.md §3)
//                                         "forces"            eqs. (4), (5) and gravity
//                                         "turbulence-force"  turbulence only: METHOD.md §5
//                                         "integrate"         eq. (6) and the guard's records
//     end_frame()                         "diagnostics"       queues the record's readback
//
// The CPU never waits: N comes from records that arrive frames late (enough substeps at the
// smallest stable dt seen), and the dt each substep uses is chosen on the GPU. A record that breaks
// a guard criterion is kept as instability(); the caller stops the run.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/readback.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/grid.h"
#include "sim/guard.h"

namespace ranryu::scene { struct Scene; }
namespace ranryu::turbulence { class TurbulenceForce; }

namespace ranryu::sim {

// SphParams for a scene (docs/SPH.md symbols table), with `count` fluid and `boundary` particles.
gpu::SphParams sph_params(const scene::Scene& s, std::size_t count, std::size_t boundary);
GuardLimits guard_limits(const scene::Scene& s);
// Timed passes one substep can make (the GpuTimer's capacity): radix sorts make 3 a key digit,
// bitonic sorts up to ~100 at 16M pairs.
int timed_passes_per_substep(const scene::Scene& s);

class Sph {
public:
    Sph(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene);
    ~Sph();

    void begin_frame(std::uint64_t frame_index);
    void substep();   // the five stages below, in order
    void end_frame();

    // A substep's stages, public for tests that compare each with the CPU reference.
    void choose_time_step();   // "choose-time-step"
    void rebuild_grid();       // "hash", "sort.*", "reorder": state now in cell order
    void compute_density();    // "density"
    void compute_forces();     // "forces"
    // The turbulence force (engine/turbulence/force.h), only when the scene's turbulence is on
    // (amplitude > 0; otherwise these do nothing and nothing was constructed).
    void analyse_turbulence();   // "wavelet": after compute_density(), on the current cell order
    void apply_turbulence();     // "turbulence-force": after compute_forces(), before integrate()
    const turbulence::TurbulenceForce* turbulence() const { return turbulence_.get(); }
    // The carried noise's seeds (gpu::NoiseSeed per particle, in the current cell order; the
    // reorder moves them with the particles), or null when the turbulence is off.
    gl::Buffer* noise_seeds() { return turbulence_ ? &seed_[current_] : nullptr; }
    void integrate();          // "integrate"
    int substeps_this_frame() const { return substeps_; }

    // Fluid state, in the cell order of the last substep.
    const gl::Buffer& positions() const { return position_[current_]; }
    const gl::Buffer& velocities() const { return velocity_[current_]; }
    const gl::Buffer& densities() const { return density_; }
    const gl::Buffer& accelerations() const { return accel_; }
    // The density pass's (run start, mask) pairs, 2·runs·count() uints (sph.neighbour_masks; tests),
    // and whether they describe the current cell order and positions: set by compute_density(),
    // cleared by rebuild_grid() and integrate() (which move or reorder the particles).
    const gl::Buffer& neighbour_masks() const { return neighbours_; }
    bool neighbour_masks_current() const { return masks_current_; }
    int neighbour_runs() const { return runs_; }   // runs a neighbour walk visits: 9 merged rows or 27 cells
    const gl::Buffer& boundary() const { return boundary_; }
    const gl::Buffer& step_state() const { return step_; }
    const CellRanges& cell_ranges() const { return ranges_; }
    NeighbourGrid& grid() { return grid_; }
    std::size_t count() const { return count_; }
    std::size_t boundary_count() const { return boundary_count_; }
    const gpu::SphParams& params() const { return params_; }

    // Latest StepState record read back (frames late), and the first instability seen, if any.
    const std::optional<gpu::StepState>& last_record() const { return last_; }
    const std::optional<Instability>& instability() const { return instability_; }
    // Every record, as it arrives (validation series). Set before the first frame.
    void set_record_sink(std::function<void(const gpu::StepState&)> sink) { sink_ = std::move(sink); }
    // Collects the records that have arrived (never waits); waits for every queued one (end of a run).
    void poll_records() { readback_.poll(); }
    void drain_records() { readback_.drain(); }

    // Tests: frames of `frame_dt_override` made of substeps of exactly `dt` when stable allows.
    void set_fixed_dt(float dt);
    // Tests: replaces the fluid state (count() positions and velocities, any order) before a substep.
    void upload_state(const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v);

private:
    void on_record(std::uint64_t frame, const void* bytes);
    void bind_fields();

    profile::GpuTimer& timer_;
    profile::PassId begin_pass_, step_pass_, density_pass_, forces_pass_, integrate_pass_, diag_pass_,
        boundary_pass_, boundary_cells_pass_;
    shader::Program begin_, choose_, density_prog_, forces_, integrate_, boundary_volume_, flag_boundary_;
    gpu::SphParams params_{};
    GuardLimits limits_;
    float frame_dt_;
    int max_substeps_;
    NeighbourGrid grid_;
    std::size_t count_ = 0, boundary_count_ = 0;
    gl::Buffer position_[2], velocity_[2];
    gl::Buffer seed_[2];   // turbulence only (noise_seeds())
    int current_ = 0;
    gl::Buffer density_, accel_, boundary_, step_, params_ubo_;
    gl::Buffer neighbours_;   // sph.neighbour_masks only
    bool masks_current_ = false;
    int runs_ = 9;
    gl::Buffer obstacles_;   // obstacle_shapes(): integrate's last-resort projection (docs/SPH.md (8))
    gl::Buffer pair_terms_;      // vec2 per particle: (rho, p/rho^2) for the forces pass's gathers
    gl::Buffer boundary_near_;   // uint per key: a boundary particle within the 27 cells (start-up)
    CellRanges ranges_, boundary_ranges_;
    gl::AsyncReadback readback_;
    std::optional<gpu::StepState> last_;
    std::optional<Instability> instability_;
    std::function<void(const gpu::StepState&)> sink_;
    int substeps_ = 1;
    float dt_estimate_;
    std::optional<float> fixed_dt_;
    std::unique_ptr<turbulence::TurbulenceForce> turbulence_;   // null unless the scene turns it on
};

}  // namespace ranryu::sim
