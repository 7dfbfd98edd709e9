#include "sim/guard.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace ranryu::sim {
namespace {
float from_bits(std::uint32_t b) {
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
}
}  // namespace

std::string Instability::message() const {
    // NaN and escape have no value to compare: they name the particle only.
    char detail[96];
    if (limit > 0.0) std::snprintf(detail, sizeof detail, "particle %u: %.6g, limit %.6g", particle, value, limit);
    else std::snprintf(detail, sizeof detail, "particle %u", particle);
    char buf[512];
    std::snprintf(buf, sizeof buf, "simulation unstable at frame %llu, step %u, t = %.6f s: %s (%s); stopped",
                  static_cast<unsigned long long>(frame), step, time, criterion.c_str(), detail);
    return buf;
}

std::optional<Instability> check(const gpu::StepState& r, const GuardLimits& limits) {
    Instability i;
    i.frame = r.frame;
    i.step = r.steps;
    i.time = r.time;
    if (r.nan_count > 0) {
        i.criterion = "non-finite position or velocity in " + std::to_string(r.nan_count) + " particle updates";
        i.particle = r.nan_index;
        i.value = NAN;
        return i;
    }
    if (r.escaped_count > 0) {
        i.criterion = std::to_string(r.escaped_count) + " particles left the domain";
        i.particle = r.escaped_index;
        return i;
    }
    if (const float d = from_bits(r.frame_max_density); !(d <= limits.density_ratio)) {
        i.criterion = "density rho/rho0 beyond its bound";
        i.particle = r.density_index;
        i.value = d;
        i.limit = limits.density_ratio;
        return i;
    }
    if (const float v = from_bits(r.frame_max_speed); !(v <= limits.speed)) {
        i.criterion = "speed |v| (m/s) beyond its bound";
        i.particle = r.speed_index;
        i.value = v;
        i.limit = limits.speed;
        return i;
    }
    if (r.frame_substeps > 0 && !(r.frame_min_dt >= limits.dt_floor)) {
        i.criterion = "stable time step (s) collapsed below its floor";
        i.particle = r.speed_index;
        i.value = r.frame_min_dt;
        i.limit = limits.dt_floor;
        return i;
    }
    return std::nullopt;
}

}  // namespace ranryu::sim
