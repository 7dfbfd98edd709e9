#include "sim/simulation.h"

#include <algorithm>

#include "turbulence/force.h"

namespace ranryu::sim {

Simulation::Simulation(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene)
    : fluid_(shaders, timer, scene), solver_(make_solver(shaders, timer, scene, fluid_)), frame_dt_(scene.frame_dt),
      paddle_speed_(kPaddleSpeed * scene.speed_estimate()) {
    if (scene.turbulence.enabled())
        turbulence_ = std::make_unique<turbulence::TurbulenceForce>(shaders, timer, scene.turbulence, fluid_);
}

Simulation::~Simulation() = default;

void Simulation::begin_frame(std::uint64_t frame) {
    fluid_.begin_frame(frame);
    if (emitting_ && fluid_.has_budget()) fluid_.emit();
    solver_->begin_frame(fluid_);
}

// Before a step: the paddle where set_paddle() asked, a substep's move (and growth) at a time. The projection's
// velocity u is the move over the substep's share of the frame (the GPU's dt splits the frame
// nearly evenly between the substeps the CPU issued).
void Simulation::place_paddle() {
    if (!fluid_.has_paddle()) return;
    if (!paddle_on_) {
        if (paddle_placed_on_) fluid_.move_paddle(paddle_center_, glm::vec3(0.0f), false);
        paddle_placed_on_ = false;
        paddle_velocity_ = glm::vec3(0.0f);
        return;
    }
    if (!paddle_placed_on_) paddle_center_ = paddle_goal_, paddle_scale_ = 0.0f, paddle_placed_on_ = true;
    const float substep = frame_dt_ / float(fluid_.substeps_this_frame());
    const float most = std::min(kPaddleStep * fluid_.params().spacing, paddle_speed_ * substep);
    glm::vec3 d = paddle_goal_ - paddle_center_;
    const float len = glm::length(d);
    if (len > most) d *= most / len;
    if (len == 0.0f && paddle_velocity_ == glm::vec3(0.0f) && paddle_scale_ == 1.0f) return;
    paddle_center_ = len > most ? paddle_center_ + d : paddle_goal_;
    paddle_velocity_ = d / substep;
    paddle_scale_ = std::min(1.0f, paddle_scale_ + most / fluid_.paddle_radius());
    fluid_.move_paddle(paddle_center_, paddle_velocity_, true, paddle_scale_);
}

void Simulation::step() {
    place_paddle();
    if (turbulence_) solver_->step(fluid_, *turbulence_);
    else solver_->step(fluid_, none_);
}

void Simulation::end_frame() { fluid_.end_frame(); }

void Simulation::advance(std::uint64_t frame) {
    begin_frame(frame);
    for (int s = 0; s < fluid_.substeps_this_frame(); ++s) step();
    end_frame();
}

void Simulation::persist(StateIo& io) {
    fluid_.persist(io);
    solver_->persist(io);
}

}  // namespace ranryu::sim
