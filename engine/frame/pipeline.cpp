#include "frame/pipeline.h"

namespace ranryu::frame {

Pipeline::Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, int width, int height)
    : scene_(scene),
      timer_(),
      particles_(shaders, timer_),
      renderer_(shaders, timer_),
      target_(width, height, "frame"),
      camera_(render::scene_camera(scene)),
      substeps_(scene.substeps()) {
    particles_.reset(scene_.initial_positions(), scene_.initial_velocities());
    particles_.set_params(sim::sim_params(scene_, particles_.count()));
    renderer_.set_frame(render::frame_params(scene_, camera_, width, height));
}

void Pipeline::simulate() {
    for (int s = 0; s < substeps_; ++s) particles_.integrate();
    sim_time_ += double(particles_.params().dt) * substeps_;
}

void Pipeline::draw() { renderer_.draw(target_, particles_); }

void Pipeline::end_frame() {
    timer_.end_frame();
    ++frames_;
}

void Pipeline::set_camera(const render::Camera& cam) {
    camera_ = cam;
    renderer_.set_frame(render::frame_params(scene_, camera_, target_.width(), target_.height()));
}

}  // namespace ranryu::frame
