#include "sim/particles.h"

#include "core/error.h"
#include "scene/scene.h"

namespace ranryu::sim {

Particles::Particles(const shader::FileSource& shaders, profile::GpuTimer& timer)
    : timer_(timer),
      integrate_pass_(timer.pass("ballistic.integrate")),   // not WCSPH's "integrate": another shader
      integrate_(shader::Program::compute(shaders, "sim/integrate.comp")),
      params_ubo_(sizeof(gpu::SimParams), GL_DYNAMIC_DRAW, nullptr, "SimParams") {}

void Particles::reset(const std::vector<glm::vec4>& positions, const std::vector<glm::vec4>& velocities) {
    if (positions.size() != velocities.size()) throw Error("Particles::reset: positions and velocities differ in count");
    count_ = positions.size();
    position_ = gl::Buffer::from<glm::vec4>(positions, GL_DYNAMIC_COPY, "particles.position");
    velocity_ = gl::Buffer::from<glm::vec4>(velocities, GL_DYNAMIC_COPY, "particles.velocity");
    params_.particle_count = gpu::uint(count_);
    params_ubo_.upload_value(params_);
}

void Particles::set_params(const gpu::SimParams& p) {
    params_ = p;
    params_.particle_count = gpu::uint(count_);
    params_ubo_.upload_value(params_);
}

void Particles::integrate() {
    auto pass = timer_.scope(integrate_pass_);
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SIM);
    integrate_.bind({{"Positions", &position_}, {"Velocities", &velocity_}}).dispatch(count_);
    // The next substep and the impostor draw (vertex attributes) read what this wrote.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

gpu::SimParams sim_params(const scene::Scene& s, std::size_t count) {
    gpu::SimParams p{};
    p.gravity = glm::vec4(s.gravity, 0.0f);
    p.domain_min = glm::vec4(s.tank_min, 0.0f);
    p.domain_max = glm::vec4(s.tank_max, 0.0f);
    p.dt = s.frame_dt / float(s.substeps());
    p.restitution = s.restitution;
    p.particle_radius = s.particle_radius;
    p.particle_count = gpu::uint(count);
    return p;
}

void Particles::persist(StateIo& io) {
    io.buffer("ballistic.positions", position_);
    io.buffer("ballistic.velocities", velocity_);
}

}  // namespace ranryu::sim
