#pragma once
// The raster stage: floor, tank, and either the particles (per-pixel Phong on sphere impostors) or
// the liquid surface that marching cubes meshed, shaded in one of the Shading modes.
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"

namespace ranryu::scene { struct Scene; }

namespace ranryu::render {

// How the liquid is drawn. particles: sphere impostors (no surface is built). The others draw the
// marching-cubes mesh: phong (per pixel, glsl/render/surface_phong.frag), gouraud (Phong per vertex,
// interpolated), fresnel (reflection and refraction of the environment, surface_fresnel.frag).
enum class Shading { particles, phong, gouraud, fresnel };
std::optional<Shading> parse_shading(std::string_view name);
const char* shading_name(Shading s);
// particles for the ballistic model (no level set), fresnel for SPH.
Shading default_shading(const scene::Scene& s);
inline bool needs_surface(Shading s) { return s != Shading::particles; }

// The mesh to draw: marching cubes' vertices (gpu::MeshVertex[]) and the buffer holding the
// glDrawArraysIndirect arguments at byte draw_offset (MarchingCubes::state(), draw_offset).
struct SurfaceMesh {
    const gl::Buffer& vertices;
    const gl::Buffer& indirect;
    std::size_t draw_offset;
};

// Sub-particles to draw with the particles (turbulence/subparticles.h): the parents' levels words
// (uint per parent, same order as the parents' positions), the sub-particles' positions (w = level)
// and velocities, and the buffer holding their glDrawArraysIndirect arguments at byte draw_offset.
struct SubparticleDraw {
    const gl::Buffer& parent_levels;
    const gl::Buffer& positions;
    const gl::Buffer& velocities;
    const gl::Buffer& indirect;
    std::size_t draw_offset;
};

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
    // Builds the floor, tank and impostor programs, and the surface program of `shading` only (with
    // its pass "draw-surface") when it is not particles. `subparticles`: also the impostor variant that
    // draws by sub-particle level (glsl/render/impostor.*, RANRYU_BY_LEVEL). `paddle`: also the one
    // that draw_sphere() draws with (RANRYU_RADIUS_IN_W).
    Renderer(const shader::FileSource& shaders, profile::GpuTimer& timer, Shading shading = Shading::particles,
             bool subparticles = false, bool paddle = false);

    void set_frame(const gpu::FrameParams& p);   // copied into the FrameParams UBO
    const gpu::FrameParams& frame() const { return frame_; }
    // Fresnel mode: Beer-Lambert absorption coefficients of the water (1/m, per channel).
    void set_absorption(glm::vec3 sigma);
    Shading shading() const { return shading_; }

    // Passes "clear", "draw-floor", "draw-tank", then "draw-particles" into `target` (`count`
    // particles whose positions and velocities are vec4 arrays) or, when the shading is not
    // particles and `surface` is given, "draw-surface": glDrawArraysIndirect of the mesh, no readback.
    // With `sub` (particles shading, built with subparticles), "draw-particles" draws the parents
    // that were not split and then the sub-particles (glDrawArraysIndirect), coloured by level and of
    // radius r/2^level.
    void draw(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
              std::size_t count, const SurfaceMesh* surface = nullptr, const SubparticleDraw* sub = nullptr);
    // Pass "draw-paddle": one sphere into `target` over what draw() left in it (depth-tested), from
    // `sphere`: vec4 (center, radius) then vec4 (velocity, 0), drawn as an impostor coloured by its
    // speed like the particles. Needs a renderer built with `paddle`.
    void draw_sphere(const gl::RenderTarget& target, const gl::Buffer& sphere);

private:
    profile::GpuTimer& timer_;
    Shading shading_;
    profile::PassId clear_pass_, floor_pass_, tank_pass_, particles_pass_, surface_pass_{}, paddle_pass_{};
    shader::Program floor_, tank_, impostor_, surface_, impostor_levels_, impostor_sphere_;
    gl::VertexArray empty_vao_, particle_vao_, mesh_vao_, parent_vao_;
    gl::Buffer frame_ubo_;
    gpu::FrameParams frame_{};
};

}  // namespace ranryu::render
