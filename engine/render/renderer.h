#pragma once
// The raster stage: floor, tank and particles drawn into a render target with per-pixel Phong.
#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"

namespace ranryu::scene { struct Scene; }

namespace ranryu::render {

struct Camera {
    glm::vec3 eye{2.0f, 1.5f, 2.5f};
    glm::vec3 target{0.5f, 0.3f, 0.3f};
    float fov_deg = 40.0f;
};
Camera scene_camera(const scene::Scene& s);

// FrameParams for a scene seen through `cam` at `width`×`height`. Pure math (tests use it).
gpu::FrameParams frame_params(const scene::Scene& s, const Camera& cam, int width, int height);

class Renderer {
public:
    Renderer(const shader::FileSource& shaders, profile::GpuTimer& timer);

    void set_frame(const gpu::FrameParams& p);   // copied into the FrameParams UBO
    const gpu::FrameParams& frame() const { return frame_; }

    // Passes "clear", "draw-floor", "draw-tank", "draw-particles" into `target`: `count` particles
    // whose positions and velocities are vec4 arrays.
    void draw(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
              std::size_t count);

private:
    profile::GpuTimer& timer_;
    profile::PassId clear_pass_, floor_pass_, tank_pass_, particles_pass_;
    shader::Program floor_, tank_, impostor_;
    gl::VertexArray empty_vao_, particle_vao_;
    gl::Buffer frame_ubo_;
    gpu::FrameParams frame_{};
};

}  // namespace ranryu::render
