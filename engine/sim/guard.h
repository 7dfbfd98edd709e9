#pragma once
// The instability guard: reads a frame's StepState record (which arrives frames late, through an
// AsyncReadback) and names the first criterion it breaks. The simulation is then stopped cleanly:
// the app reports the finding and exits with code 3 (ranryu::Exit::unstable).
//
// A density or speed past its bound is a blow-up when it persists, and a spike when it does not: a
// lone splash particle thrown fast at an impact, or one step's compression there, that the next frame
// no longer shows (the 1M-particle dam break's run-up falling back at t = 1.16 s throws one particle to
// 20 m/s for one frame, after which the fastest is back at 3.7 m/s: docs/DFSPH.md). Guard::observe()
// therefore stops the run at once on a non-finite value, an escaped particle, a collapsed time step or
// a density or speed past `hard_factor` times its bound (for the density, its excess ρ/ρ0 − 1), and
// on a density or speed past its bound only when `persist` frame records in a row show it.
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "core/error.h"
#include "shared/bindings.h"

namespace ranryu::sim {

struct GuardLimits {
    float density_ratio = 1.5f;   // rho/rho0 above this: exploding density
    float speed = 100.0f;         // |v| above this (m/s): exploding velocity
    float dt_floor = 1e-6f;       // a stable dt below this (s): the time step has collapsed
    int persist = 2;              // frames in a row past the density or speed bound that stop the run
    float hard_factor = 2.0f;     // past this many times a bound (density: its excess) stops it at once

    // The bounds that stop a run at once: density 1 + hard_factor·(density_ratio − 1), speed
    // hard_factor·speed, dt_floor as it is.
    GuardLimits hard() const;
};

struct Instability {
    std::string criterion;   // "non-finite value", "particles left the domain", "density", "velocity", "time step"
    std::uint64_t frame = 0;
    std::uint32_t step = 0;  // substeps since the start
    double time = 0.0;       // simulated time (s)
    std::uint32_t particle = 0;   // a worst particle (index in the frame's sorted order)
    std::optional<glm::vec3> position;   // where it was (density, speed, time step: StepState's positions)
    double value = 0.0, limit = 0.0;
    std::string detail() const;    // "particle N at (x, y, z) m: value, limit L"
    std::string message() const;
};

// The first bound one frame's record breaks (in the order: non-finite, escaped, density, speed, time
// step), whether or not it persists.
std::optional<Instability> check(const gpu::StepState& record, const GuardLimits& limits);

// The guard over a run's records, in frame order: check() with the persistence rule above.
class Guard {
public:
    explicit Guard(const GuardLimits& limits) : limits_(limits), hard_(limits.hard()) {}
    // The finding that stops the run, or nothing (a sound frame, or a spike that may yet pass).
    std::optional<Instability> observe(const gpu::StepState& record);
    const GuardLimits& limits() const { return limits_; }
    // Spikes that passed: frames past a bound whose next frame was back within it.
    int spikes() const { return spikes_; }
    // The largest of them (by value over limit), for the run's report.
    const std::optional<Instability>& largest_spike() const { return largest_spike_; }
    // The last frame known sound: the last record's, less the frames of a run past a bound that has
    // not ended yet (they stop the run if it persists). Nothing before the first sound record.
    std::optional<std::uint64_t> sound_through() const;

private:
    GuardLimits limits_, hard_;
    int run_ = 0, spikes_ = 0;
    std::optional<std::uint64_t> last_frame_;
    std::optional<Instability> first_, largest_in_run_, largest_spike_;
};

class UnstableError : public Error {
public:
    explicit UnstableError(const Instability& i) : Error(i.message(), Exit::unstable), finding(i) {}
    Instability finding;
};

}  // namespace ranryu::sim
