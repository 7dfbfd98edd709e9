#pragma once
// The particle state on the GPU and the passes that advance it. Positions and velocities are
// std430 vec4 arrays (storage blocks Positions, Velocities).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/state_io.h"

namespace ranryu::scene { struct Scene; }

namespace ranryu::sim {

class Particles {
public:
    Particles(const shader::FileSource& shaders, profile::GpuTimer& timer);
    // Device memory a reset() of `count` particles leaves allocated (frame/memory.h).
    static std::size_t bytes_for(std::size_t count) { return sizeof(gpu::SimParams) + 2 * count * sizeof(glm::vec4); }

    // Allocates the state for `positions.size()` particles and uploads it. Start-up only.
    void reset(const std::vector<glm::vec4>& positions, const std::vector<glm::vec4>& velocities);
    void set_params(const gpu::SimParams& p);   // copied into the SimParams UBO
    const gpu::SimParams& params() const { return params_; }

    // One substep of every particle (pass "ballistic.integrate").
    void integrate();

    std::size_t count() const { return count_; }
    // Checkpoints (frame/checkpoint.h, sim/state_io.h): positions and velocities.
    void persist(StateIo& io);
    const gl::Buffer& positions() const { return position_; }
    const gl::Buffer& velocities() const { return velocity_; }

private:
    profile::GpuTimer& timer_;
    profile::PassId integrate_pass_;
    shader::Program integrate_;
    gl::Buffer position_, velocity_, params_ubo_;
    gpu::SimParams params_{};
    std::size_t count_ = 0;
};

// SimParams for a scene (dt is the scene's substep).
gpu::SimParams sim_params(const scene::Scene& s, std::size_t count);

}  // namespace ranryu::sim
