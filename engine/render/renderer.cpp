#include "render/renderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "render/shading.h"
#include "scene/scene.h"

namespace ranryu::render {

namespace {
struct ShadingName {
    Shading shading;
    const char* name;
};
constexpr ShadingName kShadingNames[] = {
    {Shading::particles, "particles"}, {Shading::phong, "phong"}, {Shading::gouraud, "gouraud"}, {Shading::fresnel, "fresnel"}};

shader::Program surface_program(const shader::FileSource& shaders, Shading s) {
    switch (s) {
        case Shading::phong: return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_phong.frag");
        case Shading::gouraud:
            return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_gouraud.frag", "#define GOURAUD\n");
        case Shading::fresnel: return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_fresnel.frag");
        case Shading::particles: break;
    }
    return {};
}
}  // namespace

std::optional<Shading> parse_shading(std::string_view name) {
    for (const ShadingName& n : kShadingNames)
        if (name == n.name) return n.shading;
    return std::nullopt;
}

const char* shading_name(Shading s) {
    for (const ShadingName& n : kShadingNames)
        if (s == n.shading) return n.name;
    return "?";
}

Shading default_shading(const scene::Scene& s) { return s.model == scene::Model::sph ? Shading::fresnel : Shading::particles; }

Camera scene_camera(const scene::Scene& s) { return Camera{s.camera_eye, s.camera_target, s.fov_deg}; }

gpu::FrameParams frame_params(const scene::Scene& s, const Camera& cam, int width, int height) {
    gpu::FrameParams p{};
    const float extent = glm::length(s.tank_max - s.tank_min) + glm::length(cam.eye - cam.target);
    p.view = glm::lookAt(cam.eye, cam.target, glm::vec3(0.0f, 1.0f, 0.0f));
    p.proj = glm::perspective(glm::radians(cam.fov_deg), float(width) / float(height), 0.01f, 4.0f * extent);
    p.view_proj = p.proj * p.view;
    p.eye = glm::vec4(cam.eye, 1.0f);
    p.light_dir = glm::vec4(glm::normalize(s.light_dir), 0.0f);
    p.light_color = glm::vec4(1.0f, 1.0f, 1.0f, s.ambient);
    p.material = glm::vec4(0.75f, 0.35f, 48.0f, s.particle_radius);
    p.viewport = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
    // Colour ramp top: the speed of a fall from the tank's height, √(2·g·H).
    const float fall = std::sqrt(2.0f * glm::length(s.gravity) * (s.tank_max.y - s.tank_min.y));
    p.speed_scale = glm::vec4(fall > 0.0f ? fall : 1.0f, 0.0f, 0.0f, 0.0f);
    p.tank_min = glm::vec4(s.tank_min, 0.0f);
    p.tank_max = glm::vec4(s.tank_max, 0.0f);
    return p;
}

Renderer::Renderer(const shader::FileSource& shaders, profile::GpuTimer& timer, Shading shading, bool subparticles, bool paddle)
    : timer_(timer),
      shading_(shading),
      clear_pass_(timer.pass("clear")),
      floor_pass_(timer.pass("draw-floor")),
      tank_pass_(timer.pass("draw-tank")),
      particles_pass_(timer.pass("draw-particles")),
      floor_(shader::Program::graphics(shaders, "render/floor.vert", "render/floor.frag")),
      tank_(shader::Program::graphics(shaders, "render/tank.vert", "render/tank.frag")),
      impostor_(shader::Program::graphics(shaders, "render/impostor.vert", "render/impostor.frag")),
      frame_ubo_(sizeof(gpu::FrameParams), GL_DYNAMIC_DRAW, nullptr, "FrameParams") {
    // Per-instance position and velocity attributes; the buffers are attached at draw time.
    glBindVertexArray(particle_vao_.id());
    glEnableVertexAttribArray(RANRYU_ATTR_POSITION);
    glEnableVertexAttribArray(RANRYU_ATTR_VELOCITY);
    glVertexAttribFormat(RANRYU_ATTR_POSITION, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribFormat(RANRYU_ATTR_VELOCITY, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribBinding(RANRYU_ATTR_POSITION, 0);
    glVertexAttribBinding(RANRYU_ATTR_VELOCITY, 1);
    glVertexBindingDivisor(0, 1);
    glVertexBindingDivisor(1, 1);
    glBindVertexArray(0);
    gl::label(GL_VERTEX_ARRAY, particle_vao_.id(), "particles.vao");
    if (subparticles) {
        impostor_levels_ = shader::Program::graphics(shaders, "render/impostor.vert", "render/impostor.frag",
                                                     "#define RANRYU_BY_LEVEL 1\n");
        // The parents: position, velocity and their levels word (uint), one each per instance.
        glBindVertexArray(parent_vao_.id());
        for (GLuint a : {GLuint(RANRYU_ATTR_POSITION), GLuint(RANRYU_ATTR_VELOCITY), GLuint(RANRYU_ATTR_LEVEL)}) {
            glEnableVertexAttribArray(a);
            glVertexAttribBinding(a, a);
            glVertexBindingDivisor(a, 1);
        }
        glVertexAttribFormat(RANRYU_ATTR_POSITION, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexAttribFormat(RANRYU_ATTR_VELOCITY, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexAttribIFormat(RANRYU_ATTR_LEVEL, 1, GL_UNSIGNED_INT, 0);
        glBindVertexArray(0);
        gl::label(GL_VERTEX_ARRAY, parent_vao_.id(), "particles.parents.vao");
    }

    if (paddle) {
        paddle_pass_ = timer.pass("draw-paddle");
        impostor_sphere_ = shader::Program::graphics(shaders, "render/impostor.vert", "render/impostor.frag", "#define RANRYU_RADIUS_IN_W 1\n");
    }

    if (needs_surface(shading_)) {
        surface_pass_ = timer.pass("draw-surface");
        surface_ = surface_program(shaders, shading_);
        // gpu::MeshVertex: position at byte 0, normal at byte 16, stride 32; buffer attached at draw time.
        glBindVertexArray(mesh_vao_.id());
        glEnableVertexAttribArray(RANRYU_ATTR_MESH_POSITION);
        glEnableVertexAttribArray(RANRYU_ATTR_MESH_NORMAL);
        glVertexAttribFormat(RANRYU_ATTR_MESH_POSITION, 4, GL_FLOAT, GL_FALSE, offsetof(gpu::MeshVertex, position));
        glVertexAttribFormat(RANRYU_ATTR_MESH_NORMAL, 4, GL_FLOAT, GL_FALSE, offsetof(gpu::MeshVertex, normal));
        glVertexAttribBinding(RANRYU_ATTR_MESH_POSITION, 0);
        glVertexAttribBinding(RANRYU_ATTR_MESH_NORMAL, 0);
        glBindVertexArray(0);
        gl::label(GL_VERTEX_ARRAY, mesh_vao_.id(), "surface.vao");
        set_absorption(glm::vec3(0.0f));
    }
}

void Renderer::set_absorption(glm::vec3 sigma) {
    if (shading_ == Shading::fresnel) glProgramUniform4f(surface_.id(), RANRYU_LOC_ABSORPTION, sigma.x, sigma.y, sigma.z, 0.0f);
}

void Renderer::set_frame(const gpu::FrameParams& p) {
    frame_ = p;
    frame_ubo_.upload_value(frame_);
}

void Renderer::draw(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
                    std::size_t count, const SurfaceMesh* surface, const SubparticleDraw* sub) {
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, target.width(), target.height());
    frame_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
    {
        auto pass = timer_.scope(clear_pass_);
        glDepthMask(GL_TRUE);
        glClearColor(0.16f, 0.18f, 0.22f, 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(empty_vao_.id());
    {
        auto pass = timer_.scope(floor_pass_);
        floor_.use();
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    {
        auto pass = timer_.scope(tank_pass_);
        tank_.use();
        glDrawArrays(GL_LINES, 0, 24);
    }
    if (needs_surface(shading_) && surface) {
        auto pass = timer_.scope(surface_pass_);
        surface_.use();
        glBindVertexArray(mesh_vao_.id());
        glBindVertexBuffer(0, surface->vertices.id(), 0, sizeof(gpu::MeshVertex));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, surface->indirect.id());
        glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(surface->draw_offset));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    } else if (sub) {
        if (!impostor_levels_.id()) throw Error("Renderer::draw: sub-particles given to a renderer built without them");
        auto pass = timer_.scope(particles_pass_);
        impostor_levels_.use();
        // The parents not split (the vertex shader drops the others), then the sub-particles, whose
        // count only the GPU knows. The level attribute is disabled there; the shader ignores it.
        glProgramUniform1ui(impostor_levels_.id(), RANRYU_LOC_IMPOSTOR_CHILDREN, 0u);
        glBindVertexArray(parent_vao_.id());
        glBindVertexBuffer(RANRYU_ATTR_POSITION, positions.id(), 0, sizeof(glm::vec4));
        glBindVertexBuffer(RANRYU_ATTR_VELOCITY, velocities.id(), 0, sizeof(glm::vec4));
        glBindVertexBuffer(RANRYU_ATTR_LEVEL, sub->parent_levels.id(), 0, sizeof(std::uint32_t));
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count));
        glProgramUniform1ui(impostor_levels_.id(), RANRYU_LOC_IMPOSTOR_CHILDREN, 1u);
        glBindVertexArray(particle_vao_.id());
        glBindVertexBuffer(0, sub->positions.id(), 0, sizeof(glm::vec4));
        glBindVertexBuffer(1, sub->velocities.id(), 0, sizeof(glm::vec4));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, sub->indirect.id());
        glDrawArraysIndirect(GL_TRIANGLE_STRIP, reinterpret_cast<const void*>(sub->draw_offset));
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    } else {
        auto pass = timer_.scope(particles_pass_);
        impostor_.use();
        glBindVertexArray(particle_vao_.id());
        glBindVertexBuffer(0, positions.id(), 0, sizeof(glm::vec4));
        glBindVertexBuffer(1, velocities.id(), 0, sizeof(glm::vec4));
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count));
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::draw_sphere(const gl::RenderTarget& target, const gl::Buffer& sphere) {
    if (!impostor_sphere_.id()) throw Error("Renderer::draw_sphere: a renderer built without the paddle");
    auto pass = timer_.scope(paddle_pass_);
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, target.width(), target.height());
    frame_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    impostor_sphere_.use();
    glBindVertexArray(particle_vao_.id());
    glBindVertexBuffer(0, sphere.id(), 0, 2 * sizeof(glm::vec4));
    glBindVertexBuffer(1, sphere.id(), sizeof(glm::vec4), 2 * sizeof(glm::vec4));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 1);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace ranryu::render
