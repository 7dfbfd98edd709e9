#pragma once
// The instability guard: reads a frame's StepState record (which arrives frames late, through an
// AsyncReadback) and names the first criterion it breaks. The simulation is then stopped cleanly:
// the app reports the finding and exits with code 3 (ranryu::Exit::unstable).
#include <cstdint>
#include <optional>
#include <string>

#include "core/error.h"
#include "shared/bindings.h"

namespace ranryu::sim {

struct GuardLimits {
    float density_ratio = 1.5f;   // rho/rho0 above this: exploding density
    float speed = 100.0f;         // |v| above this (m/s): exploding velocity
    float dt_floor = 1e-6f;       // a stable dt below this (s): the time step has collapsed
};

struct Instability {
    std::string criterion;   // "non-finite value", "particles left the domain", "density", "velocity", "time step"
    std::uint64_t frame = 0;
    std::uint32_t step = 0;  // substeps since the start
    double time = 0.0;       // simulated time (s)
    std::uint32_t particle = 0;   // a worst particle (index in the frame's sorted order)
    double value = 0.0, limit = 0.0;
    std::string message() const;
};

std::optional<Instability> check(const gpu::StepState& record, const GuardLimits& limits);

class UnstableError : public Error {
public:
    explicit UnstableError(const Instability& i) : Error(i.message(), Exit::unstable), finding(i) {}
    Instability finding;
};

}  // namespace ranryu::sim
