#include "sim/guard.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>

namespace ranryu::sim {
std::string Instability::detail() const {
    // NaN and escape have no value to compare: they name the particle only.
    char where[96] = "";
    if (position)
        std::snprintf(where, sizeof where, " at (%.4f, %.4f, %.4f) m", double(position->x), double(position->y), double(position->z));
    char detail[192];
    if (limit > 0.0) std::snprintf(detail, sizeof detail, "particle %u%s: %.6g, limit %.6g", particle, where, value, limit);
    else std::snprintf(detail, sizeof detail, "particle %u%s", particle, where);
    return detail;
}

std::string Instability::message() const {
    char buf[512];
    std::snprintf(buf, sizeof buf, "simulation unstable at frame %llu, step %u, t = %.6f s: %s (%s); stopped",
                  static_cast<unsigned long long>(frame), step, time, criterion.c_str(), detail().c_str());
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
    if (const float d = std::bit_cast<float>(r.frame_max_density); !(d <= limits.density_ratio)) {
        i.criterion = "density rho/rho0 beyond its bound";
        i.particle = r.density_index;
        i.position = glm::vec3(r.density_position.x, r.density_position.y, r.density_position.z);
        i.value = d;
        i.limit = limits.density_ratio;
        return i;
    }
    if (const float v = std::bit_cast<float>(r.frame_max_speed); !(v <= limits.speed)) {
        i.criterion = "speed |v| (m/s) beyond its bound";
        i.particle = r.speed_index;
        i.position = glm::vec3(r.speed_position.x, r.speed_position.y, r.speed_position.z);
        i.value = v;
        i.limit = limits.speed;
        return i;
    }
    if (r.frame_substeps > 0 && !(r.frame_min_dt >= limits.dt_floor)) {
        i.criterion = "stable time step (s) collapsed below its floor";
        i.particle = r.speed_index;
        i.position = glm::vec3(r.speed_position.x, r.speed_position.y, r.speed_position.z);
        i.value = r.frame_min_dt;
        i.limit = limits.dt_floor;
        return i;
    }
    return std::nullopt;
}

GuardLimits GuardLimits::hard() const {
    GuardLimits h = *this;
    h.density_ratio = 1.0f + hard_factor * (density_ratio - 1.0f);
    h.speed = hard_factor * speed;
    return h;
}

std::optional<Instability> Guard::observe(const gpu::StepState& r) {
    last_frame_ = r.frame;
    if (check(r, hard_)) {
        // Reported by the first criterion in check()'s order, as without the rule: a compression
        // that throws particles fast reads as the density it is.
        Instability at_once = *check(r, limits_);
        if (at_once.limit > 0.0 && at_once.criterion.find("time step") == std::string::npos)
            at_once.criterion += " (a bound broken " + std::to_string(int(limits_.hard_factor)) + "x over: stopped at once)";
        return at_once;
    }
    std::optional<Instability> past = check(r, limits_);
    auto ratio = [](const Instability& i) { return i.value / i.limit; };
    if (!past) {   // back within the bounds: the frames past them were a spike
        if (run_ > 0) {
            spikes_ += run_;
            if (!largest_spike_ || ratio(*largest_in_run_) > ratio(*largest_spike_)) largest_spike_ = largest_in_run_;
        }
        run_ = 0;
        first_.reset(), largest_in_run_.reset();
        return std::nullopt;
    }
    // Past the density or the speed bound (the hard check took every other criterion).
    if (run_ == 0) first_ = past;
    if (!largest_in_run_ || ratio(*past) > ratio(*largest_in_run_)) largest_in_run_ = past;
    if (++run_ < limits_.persist) return std::nullopt;
    // A blow-up: reported from the frame it began in, so that its frames are the ones discarded.
    Instability found = *first_;
    found.criterion += " in " + std::to_string(run_) + " frames in a row from this one";
    return found;
}

std::optional<std::uint64_t> Guard::sound_through() const {
    if (!last_frame_ || *last_frame_ < std::uint64_t(run_)) return std::nullopt;
    return *last_frame_ - std::uint64_t(run_);
}

}  // namespace ranryu::sim
