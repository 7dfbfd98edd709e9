#include "render/renderer.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "gl/context.h"
#include "render/shading.h"
#include "render/spray.h"
#include "scene/scene.h"
#include "surface/level_set.h"

namespace ranryu::render {

namespace {
struct ShadingName {
    Shading shading;
    const char* name;
};
constexpr ShadingName kShadingNames[] = {{Shading::water, "water"},
                                         {Shading::fresnel, "fresnel"},
                                         {Shading::phong, "phong"},
                                         {Shading::gouraud, "gouraud"},
                                         {Shading::particles, "particles"}};

// The define that sizes the liquid's thickness (liquid_thickness.frag, surface_water.frag).
std::string thickness_define(const WaterOptions& w) {
    return "#define THICKNESS_DIVISOR " + std::to_string(w.thickness_divisor) + "\n";
}

// A raster chosen by environment variable `name`: true for "compute", false for "draw", nothing when
// it is unset; throws InputError naming it for another value.
std::optional<bool> compute_or_draw(const char* name) {
    const char* v = std::getenv(name);
    if (!v) return std::nullopt;
    if (std::string_view(v) != "compute" && std::string_view(v) != "draw")
        throw InputError(std::string(name) + "=" + v + ": expected compute or draw");
    return std::string_view(v) == "compute";
}

shader::Program surface_program(const shader::FileSource& shaders, Shading s, const WaterOptions& w) {
    switch (s) {
        case Shading::phong: return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_phong.frag");
        case Shading::gouraud:
            return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_gouraud.frag", "#define GOURAUD\n");
        case Shading::fresnel: return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_fresnel.frag");
        case Shading::water:
            return shader::Program::graphics(shaders, "render/surface.vert", "render/surface_water.frag", thickness_define(w));
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

const char* shading_names() { return "water, fresnel, phong, gouraud, particles"; }

WaterOptions WaterOptions::from_environment() {
    WaterOptions w;
    if (const char* v = std::getenv("RANRYU_WATER_CACHE")) {
        if (std::string_view(v) != "0" && std::string_view(v) != "1")
            throw InputError(std::string("RANRYU_WATER_CACHE=") + v + ": expected 0 or 1");
        w.cache_scene = *v == '1';
    }
    if (const char* v = std::getenv("RANRYU_WATER_THICKNESS_DIVISOR")) {
        if (std::string_view(v).size() != 1 || *v < '1' || *v > '4')
            throw InputError(std::string("RANRYU_WATER_THICKNESS_DIVISOR=") + v + ": expected 1, 2, 3 or 4");
        w.thickness_divisor = *v - '0';
    }
    if (const auto compute = compute_or_draw("RANRYU_WATER_RASTER"))
        w.raster = *compute ? WaterOptions::Raster::compute : WaterOptions::Raster::draw;
    return w;
}

ImpostorOptions ImpostorOptions::from_environment() {
    ImpostorOptions o;
    if (gl::software_renderer()) o.raster = ImpostorOptions::Raster::draw;
    if (const auto compute = compute_or_draw("RANRYU_PARTICLE_RASTER"))
        o.raster = *compute ? ImpostorOptions::Raster::compute : ImpostorOptions::Raster::draw;
    return o;
}

Shading default_shading(const scene::Scene& s) { return s.model == scene::Model::sph ? Shading::water : Shading::particles; }

SunView sun_view(const gpu::FrameParams& p) {
    // The floor quad (glsl/render/floor.vert: the tank's footprint grown by max(size.x, size.z)) up to
    // twice the tank's height, where splashes of an open tank may fly.
    const glm::vec3 lo(p.tank_min), hi(p.tank_max), size = hi - lo;
    const float margin = std::max(size.x, size.z);
    const glm::vec3 box_lo(lo.x - margin, lo.y, lo.z - margin), box_hi(hi.x + margin, hi.y + size.y, hi.z + margin);
    const glm::vec3 centre = 0.5f * (box_lo + box_hi);
    const float radius = 0.5f * glm::length(box_hi - box_lo);
    const glm::vec3 l = glm::normalize(glm::vec3(p.light_dir));
    const glm::vec3 up = std::abs(l.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::mat4 view = glm::lookAt(centre + radius * l, centre, up);
    const glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, 0.0f, 2.0f * radius);
    return SunView{proj * view, centre, radius};
}

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

Renderer::Renderer(const shader::FileSource& shaders, profile::GpuTimer& timer, Shading shading, bool subparticles, bool paddle,
                   WaterOptions water, ImpostorOptions impostors)
    : timer_(timer),
      shading_(shading),
      clear_pass_(timer.pass("clear")),
      floor_pass_(timer.pass("draw-floor")),
      tank_pass_(timer.pass("draw-tank")),
      particles_pass_(timer.pass("draw-particles")),
      floor_(shader::Program::graphics(shaders, "render/floor.vert", "render/floor.frag")),
      tank_(shader::Program::graphics(shaders, "render/tank.vert", "render/tank.frag",
                                      shading == Shading::water ? "#define SUN_SHARE\n" : "")),
      impostor_(shader::Program::graphics(shaders, "render/impostor.vert", "render/impostor.frag")),
      frame_ubo_(sizeof(gpu::FrameParams), GL_DYNAMIC_DRAW, nullptr, "FrameParams"),
      water_(water),
      impostors_(impostors) {
    if (water_.thickness_divisor < 1 || water_.thickness_divisor > 4)
        throw Error("Renderer: WaterOptions::thickness_divisor " + std::to_string(water_.thickness_divisor) + " is not 1 to 4");
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

    if (shading_ == Shading::particles && impostors_.raster == ImpostorOptions::Raster::compute) {
        // The LARGE dispatch's workgroups along x are the listed spheres: within GL 4.3's least limit.
        if (impostors_.large_capacity == 0 || impostors_.large_capacity > 65535u)
            throw Error("Renderer: ImpostorOptions::large_capacity " + std::to_string(impostors_.large_capacity) + " is not 1 to 65535");
        impostor_within_ = {timer.pass("draw-particles.fill", particles_pass_), timer.pass("draw-particles.rasterise", particles_pass_),
                            timer.pass("draw-particles.resolve", particles_pass_), timer.pass("draw-particles.shade", particles_pass_)};
        const std::string capacity = "#define RANRYU_IMPOSTOR_CAPACITY " + std::to_string(impostors_.large_capacity) + "u\n";
        auto programs = [&](const std::string& defines) {
            const std::string path = "render/rasterise_impostors.comp";
            return ImpostorPrograms{shader::Program::compute(shaders, path, defines),
                                    shader::Program::compute(shaders, path, defines + "#define LARGE\n"),
                                    shader::Program::compute(shaders, path, defines + "#define RESOLVE\n"),
                                    shader::Program::compute(shaders, path, defines + "#define RESOLVE\n#define LARGE\n"),
                                    shader::Program::graphics(shaders, "render/sky.vert", "render/shade_impostors.frag", defines)};
        };
        impostor_raster_ = programs(capacity);
        if (subparticles) impostor_raster_levels_ = programs(capacity + "#define BY_LEVEL\n");
        fill_ = shader::Program::compute(shaders, "render/fill_image.comp");
        impostor_large_ = gl::Buffer(sizeof(glm::uvec4) + impostors_.large_capacity * sizeof(std::uint32_t), GL_DYNAMIC_COPY, nullptr,
                                     "impostors.large");   // as bytes_for counts it
    }

    if (paddle) {
        paddle_pass_ = timer.pass("draw-paddle");
        impostor_sphere_ = shader::Program::graphics(shaders, "render/impostor.vert", "render/impostor.frag", "#define RANRYU_RADIUS_IN_W 1\n");
    }

    if (needs_surface(shading_)) {
        surface_pass_ = timer.pass("draw-surface");
        surface_ = surface_program(shaders, shading_, water_);
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
        // The same vertices by their positions alone (mesh_position.vert): the passes that need no normal.
        glBindVertexArray(mesh_position_vao_.id());
        glEnableVertexAttribArray(RANRYU_ATTR_MESH_POSITION);
        glVertexAttribFormat(RANRYU_ATTR_MESH_POSITION, 4, GL_FLOAT, GL_FALSE, offsetof(gpu::MeshVertex, position));
        glVertexAttribBinding(RANRYU_ATTR_MESH_POSITION, 0);
        glBindVertexArray(0);
        gl::label(GL_VERTEX_ARRAY, mesh_position_vao_.id(), "surface.positions.vao");
        if (subparticles) {
            spray_pass_ = timer.pass("draw-spray");
            spray_ = shader::Program::graphics(shaders, "render/spray.vert", "render/spray.frag");
            set_spray_energy(1.0f);
        }
    }
    if (shading_ == Shading::water) {
        shadow_pass_ = timer.pass("shadow-map");
        sky_pass_ = timer.pass("draw-sky");
        walls_pass_ = timer.pass("draw-walls");
        thickness_pass_ = timer.pass("liquid-thickness");
        compose_pass_ = timer.pass("compose");
        // The compute raster's passes where it runs (the draw raster fills the targets alone).
        const bool compute = water_.raster == WaterOptions::Raster::compute;
        for (auto [within, parent, name] : {std::tuple{&shadow_within_, shadow_pass_, "shadow-map."},
                                            std::tuple{&thickness_within_, thickness_pass_, "liquid-thickness."}}) {
            const std::string n = name;
            within->fill = timer.pass(n + "fill", parent);
            if (!compute) continue;
            if (parent.index == shadow_pass_.index) within->size = timer.pass(n + "size", parent);   // sizes both
            within->rasterise = timer.pass(n + "rasterise", parent);
            within->decode = timer.pass(n + "decode", parent);
        }
        sky_ = shader::Program::graphics(shaders, "render/sky.vert", "render/sky.frag");
        const std::string inline_shadow = water_.cache_scene ? "" : "#define SHADOW_INLINE\n";
        tiles_floor_ = shader::Program::graphics(shaders, "render/floor.vert", "render/tiles.frag", inline_shadow);
        tiles_walls_ = shader::Program::graphics(shaders, "render/walls.vert", "render/tiles.frag", "#define WALLS\n" + inline_shadow);
        compose_ = shader::Program::compute(shaders, "render/compose.comp");
        fill_ = shader::Program::compute(shaders, "render/fill_image.comp");
        constexpr int n = RANRYU_SHADOW_MAP_SIZE;
        shadow_near_ = gl::Texture2D(GL_R32F, n, n, "shadow.near");
        shadow_thickness_ = gl::Texture2D(GL_R32F, n, n, "shadow.thickness");
        if (water_.raster == WaterOptions::Raster::compute) {
            size_raster_ = shader::Program::compute(shaders, "render/size_raster.comp");
            raster_shadow_ = shader::Program::compute(shaders, "render/rasterise_layers.comp", "#define SUN_VIEW\n");
            raster_thickness_ = shader::Program::compute(shaders, "render/rasterise_layers.comp", thickness_define(water_));
            raster_shadow_large_ =
                shader::Program::compute(shaders, "render/rasterise_layers.comp", "#define SUN_VIEW\n#define LARGE_TRIANGLES\n");
            raster_thickness_large_ = shader::Program::compute(shaders, "render/rasterise_layers.comp",
                                                               thickness_define(water_) + "#define LARGE_TRIANGLES\n");
            decode_shadow_ = shader::Program::compute(shaders, "render/decode_raster.comp", "#define SUN_VIEW\n");
            decode_thickness_ = shader::Program::compute(shaders, "render/decode_raster.comp");
            raster_dispatch_ = gl::Buffer(sizeof(glm::uvec4), GL_DYNAMIC_COPY, nullptr, "raster.dispatch");
            raster_large_ = gl::Buffer(2 * sizeof(glm::uvec4) + 2 * RANRYU_RASTER_LARGE_CAPACITY * sizeof(std::uint32_t), GL_DYNAMIC_COPY,
                                       nullptr, "raster.large");   // as bytes_for counts them
        } else {
            shadow_ = shader::Program::graphics(shaders, "render/mesh_position.vert", "render/shadow_map.frag", "#define SUN_VIEW\n");
            thickness_prog_ = shader::Program::graphics(shaders, "render/mesh_position.vert", "render/liquid_thickness.frag",
                                                        thickness_define(water_));
            const gl::Texture2D* maps[] = {&shadow_near_, &shadow_thickness_};
            shadow_fbo_ = gl::Framebuffer(maps, nullptr, "shadow");
        }
    }
    if (needs_surface(shading_)) set_absorption(glm::vec3(0.0f));
}

namespace {
int reduced(int size, int divisor) { return (size + divisor - 1) / divisor; }
}  // namespace

std::size_t Renderer::bytes_for(Shading s, int width, int height, WaterOptions water, ImpostorOptions impostors) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height), n = RANRYU_SHADOW_MAP_SIZE;
    if (s == Shading::particles)   // the impostors' two targets and the list of large ones (R15)
        return impostors.raster == ImpostorOptions::Raster::compute
                   ? 2 * pixels * gl::Texture2D::texel_bytes(GL_R32F) + sizeof(glm::uvec4) + impostors.large_capacity * sizeof(std::uint32_t)
                   : 0;
    if (s != Shading::water) return 0;
    const int d = water.thickness_divisor;
    const std::size_t thickness = std::size_t(reduced(width, d)) * std::size_t(reduced(height, d));
    // The compute raster's dispatch and lists of large triangles (its targets are the draws').
    const std::size_t raster = water.raster == WaterOptions::Raster::compute
                                   ? 3 * sizeof(glm::uvec4) + 2 * RANRYU_RASTER_LARGE_CAPACITY * sizeof(std::uint32_t)
                                   : 0;
    // The scene cache (C_lit and q, depth), the scene with the shadow, the thickness, the shadow map.
    return pixels * (gl::Texture2D::texel_bytes(GL_RGBA16F) + gl::Texture2D::texel_bytes(GL_DEPTH_COMPONENT32F) +
                     gl::Texture2D::texel_bytes(GL_RGBA16F)) +
           thickness * gl::Texture2D::texel_bytes(GL_R32F) + 2 * n * n * gl::Texture2D::texel_bytes(GL_R32F) + raster;
}

void Renderer::resize(int width, int height) {
    if (impostor_raster_.depth.id() && (impostor_near_.width() != width || impostor_near_.height() != height)) {
        impostor_near_ = gl::Texture2D(GL_R32F, width, height, "impostors.near");
        impostor_id_ = gl::Texture2D(GL_R32F, width, height, "impostors.particle");
    }
    if (shading_ != Shading::water) return;
    if (scene_color_.width() == width && scene_color_.height() == height) return;
    lit_color_ = gl::Texture2D(GL_RGBA16F, width, height, "scene.lit");
    scene_color_ = gl::Texture2D(GL_RGBA16F, width, height, "scene.color");
    scene_depth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width, height, "scene.depth");
    const int d = water_.thickness_divisor;
    thickness_ = gl::Texture2D(GL_R32F, reduced(width, d), reduced(height, d), "liquid.thickness");
    // The refraction's lookup and the thickness's upsampling may land on the border: clamp there.
    for (const gl::Texture2D* t : {&scene_color_, &thickness_}) {
        glBindTexture(GL_TEXTURE_2D, t->id());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    const gl::Texture2D* scene[] = {&lit_color_};
    scene_fbo_ = gl::Framebuffer(scene, &scene_depth_, "scene.cache");
    ++generation_;   // a new cache, not drawn yet
    if (water_.raster == WaterOptions::Raster::draw) {
        const gl::Texture2D* thick[] = {&thickness_};
        thickness_fbo_ = gl::Framebuffer(thick, nullptr, "liquid.thickness");
    }
}

void Renderer::bind_target(const gl::RenderTarget& target) {
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, target.width(), target.height());
    frame_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
}

void Renderer::set_spray_energy(float e_min) {
    if (spray_.id()) glProgramUniform4f(spray_.id(), RANRYU_LOC_SPRAY, e_min, 0.0f, 0.0f, 0.0f);
}

void Renderer::draw_spray(const gl::RenderTarget& target, const SubparticleDraw& sub) {
    if (!spray_.id()) throw Error("Renderer::draw_spray: a renderer built without sub-particles or without a surface shading");
    auto pass = timer_.scope(spray_pass_);
    bind_target(target);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    spray_.use();
    glBindVertexArray(particle_vao_.id());
    glBindVertexBuffer(0, sub.positions.id(), 0, sizeof(glm::vec4));
    glBindVertexBuffer(1, sub.velocities.id(), 0, sizeof(glm::vec4));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, sub.indirect.id());
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, reinterpret_cast<const void*>(sub.draw_offset));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::set_absorption(glm::vec3 sigma) {
    if (shading_ == Shading::fresnel || shading_ == Shading::water)
        glProgramUniform4f(surface_.id(), RANRYU_LOC_ABSORPTION, sigma.x, sigma.y, sigma.z, 0.0f);
    if (shading_ == Shading::water)
        for (const shader::Program* p : {&tiles_floor_, &tiles_walls_, &compose_})
            glProgramUniform4f(p->id(), RANRYU_LOC_ABSORPTION, sigma.x, sigma.y, sigma.z, 0.0f);
}

void Renderer::set_frame(const gpu::FrameParams& p) {
    // FrameParams is vec4s and mat4s, no padding: equal bytes, equal view.
    if (std::memcmp(&p, &frame_, sizeof p) != 0) ++generation_;
    frame_ = p;
    frame_ubo_.upload_value(frame_);
    if (shading_ != Shading::water) return;
    const SunView sun = sun_view(p);
    for (const shader::Program* prog : {&shadow_, &raster_shadow_, &raster_shadow_large_, &tiles_floor_, &tiles_walls_, &compose_}) {
        if (!prog->id()) continue;   // the other raster's
        glProgramUniformMatrix4fv(prog->id(), RANRYU_LOC_SHADOW_MATRIX, 1, GL_FALSE, &sun.matrix[0][0]);
        glProgramUniform4f(prog->id(), RANRYU_LOC_SHADOW_ORIGIN, sun.origin.x, sun.origin.y, sun.origin.z, 0.0f);
    }
}

void Renderer::draw_mesh(const SurfaceMesh& surface, const gl::VertexArray& vao) {
    glBindVertexArray(vao.id());
    glBindVertexBuffer(0, surface.vertices.id(), 0, sizeof(gpu::MeshVertex));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, surface.indirect.id());
    glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(surface.draw_offset));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

namespace {
void bind_texture(GLuint unit, const gl::Texture2D& t) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, t.id());
}
}  // namespace

void Renderer::fill(const gl::Texture2D& r32f, float value) {
    fill_.use();
    glProgramUniform4f(fill_.id(), RANRYU_LOC_FILL_VALUE, value, 0.0f, 0.0f, 0.0f);
    glBindImageTexture(RANRYU_IMG_TARGET, r32f.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    const auto local = fill_.local_size();
    glDispatchCompute(GLuint(r32f.width() + int(local[0]) - 1) / local[0], GLuint(r32f.height() + int(local[1]) - 1) / local[1], 1);
    glBindImageTexture(RANRYU_IMG_TARGET, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
}

void Renderer::size_raster(const SurfaceMesh& surface) {
    size_raster_.bind(
        shader::StorageSet{{"MeshDraw", &surface.indirect}, {"RasterDispatch", &raster_dispatch_}, {"RasterLarge", &raster_large_}});
    glProgramUniform4ui(size_raster_.id(), RANRYU_LOC_RASTER_GROUP, raster_shadow_.local_size()[0],
                        GLuint(surface.draw_offset / sizeof(std::uint32_t)), 0u, 0u);
    size_raster_.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

void Renderer::rasterise(const SurfaceMesh& surface, const shader::Program& program, const shader::Program& large,
                         const gl::Texture2D& sum, const gl::Texture2D* near) {
    const shader::StorageSet buffers{
        {"MeshVertices", &surface.vertices}, {"RasterDispatch", &raster_dispatch_}, {"RasterLarge", &raster_large_}};
    // R32F textures as 32-bit integer images: the same size class, the bits as they are.
    glBindImageTexture(RANRYU_IMG_RASTER_SUM, sum.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
    if (near) glBindImageTexture(RANRYU_IMG_RASTER_NEAR, near->id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    program.bind(buffers).use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, raster_dispatch_.id());
    glDispatchComputeIndirect(0);
    // The large triangles the first dispatch listed, at the view's header in raster_large_.
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    large.bind(buffers).use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, raster_large_.id());
    glDispatchComputeIndirect(near ? 0 : sizeof(glm::uvec4));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void Renderer::decode(const shader::Program& program, const gl::Texture2D& sum, const gl::Texture2D* near) {
    program.use();
    glBindImageTexture(RANRYU_IMG_RASTER_SUM, sum.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
    if (near) glBindImageTexture(RANRYU_IMG_RASTER_NEAR, near->id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    const auto local = program.local_size();
    glDispatchCompute(GLuint(sum.width() + int(local[0]) - 1) / local[0], GLuint(sum.height() + int(local[1]) - 1) / local[1], 1);
    for (GLuint unit : {GLuint(RANRYU_IMG_RASTER_SUM), GLuint(RANRYU_IMG_RASTER_NEAR)})
        glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void Renderer::draw_layers(const SurfaceMesh& surface, const gl::Framebuffer& fbo, const gl::Texture2D& size_of,
                           const shader::Program& program) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, size_of.width(), size_of.height());
    program.use();
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    draw_mesh(surface, mesh_position_vao_);
    glDisable(GL_BLEND);
}

void Renderer::draw_scene() {
    // The scene cache (R13): C_lit and q of every pixel, with its depth. Expects the frame UBO and the
    // shadow map bound (the redraw path's floor and walls read it).
    glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_.id());
    glViewport(0, 0, scene_depth_.width(), scene_depth_.height());
    {
        // The depth alone: the sky covers every pixel's colour.
        auto pass = timer_.scope(clear_pass_);
        glDepthMask(GL_TRUE);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
    }
    glBindVertexArray(empty_vao_.id());
    {
        auto pass = timer_.scope(sky_pass_);
        sky_.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    {
        auto pass = timer_.scope(floor_pass_);
        tiles_floor_.use();
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    {
        auto pass = timer_.scope(walls_pass_);
        tiles_walls_.use();
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glDrawArrays(GL_TRIANGLES, 0, 24);
        glDisable(GL_CULL_FACE);
    }
    {
        auto pass = timer_.scope(tank_pass_);
        tank_.use();
        glDrawArrays(GL_LINES, 0, 24);
    }
    glDisable(GL_DEPTH_TEST);
    drawn_generation_ = generation_;
}

void Renderer::draw_water(const gl::RenderTarget& target, const SurfaceMesh* surface) {
    if (scene_color_.width() != target.width() || scene_color_.height() != target.height())
        throw Error("Renderer::draw: the water mode's targets are " + std::to_string(scene_color_.width()) + "x" +
                    std::to_string(scene_color_.height()) + ", the frame is " + std::to_string(target.width()) + "x" +
                    std::to_string(target.height()) + " (Renderer::resize first)");
    frame_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    {
        // (R8), (R10): every layer of the liquid, seen from the sun. Cleared by a compute fill.
        auto pass = timer_.scope(shadow_pass_);
        if (surface && water_.raster == WaterOptions::Raster::compute) {
            // (R14): the sizes of both passes' dispatches, the map cleared to the encodings of s_near =
            // 1e30 and d_sun = 0 (0 is 0.0's bits), the triangles, and the floats the readers read.
            {
                auto within = timer_.scope(shadow_within_.size);
                size_raster(*surface);
            }
            {
                auto within = timer_.scope(shadow_within_.fill);
                fill(shadow_near_, std::bit_cast<float>(surface::ordered_bits(1e30f)));
                fill(shadow_thickness_, 0.0f);
            }
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            {
                auto within = timer_.scope(shadow_within_.rasterise);
                rasterise(*surface, raster_shadow_, raster_shadow_large_, shadow_thickness_, &shadow_near_);
            }
            auto within = timer_.scope(shadow_within_.decode);
            decode(decode_shadow_, shadow_thickness_, &shadow_near_);
        } else {
            auto within = timer_.scope(shadow_within_.fill);
            fill(shadow_near_, 1e30f);
            fill(shadow_thickness_, 0.0f);
            glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        if (surface && water_.raster == WaterOptions::Raster::draw) {
            glBlendEquationi(0, GL_MIN);
            glBlendEquationi(1, GL_FUNC_ADD);
            draw_layers(*surface, shadow_fbo_, shadow_near_, shadow_);
            glBlendEquation(GL_FUNC_ADD);
        }
    }
    bind_texture(RANRYU_TEX_SHADOW_NEAR, shadow_near_);
    bind_texture(RANRYU_TEX_SHADOW_THICKNESS, shadow_thickness_);
    // (R13): the opaque scene only when the view changed (a CPU decision: set_frame, resize).
    if (!water_.cache_scene || drawn_generation_ != generation_) draw_scene();
    bind_texture(RANRYU_TEX_SCENE_DEPTH, scene_depth_);
    {
        // (R5): the thickness of the liquid in front of the opaque scene, at 1/thickness_divisor of the size.
        auto pass = timer_.scope(thickness_pass_);
        {
            auto within = timer_.scope(thickness_within_.fill);
            fill(thickness_, 0.0f);   // also the fixed-point 0 of the compute raster (R14)
        }
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        if (surface && water_.raster == WaterOptions::Raster::compute) {
            // The dispatch size_raster() wrote in "shadow-map".
            {
                auto within = timer_.scope(thickness_within_.rasterise);
                rasterise(*surface, raster_thickness_, raster_thickness_large_, thickness_, nullptr);
            }
            auto within = timer_.scope(thickness_within_.decode);
            decode(decode_thickness_, thickness_, nullptr);
        } else if (surface) {
            glBlendEquation(GL_FUNC_ADD);
            draw_layers(*surface, thickness_fbo_, thickness_, thickness_prog_);
        }
    }
    {
        // (R13): the cache with this frame's shadow, into the scene the surface refracts and the frame.
        auto pass = timer_.scope(compose_pass_);
        bind_texture(RANRYU_TEX_SCENE_LIT, lit_color_);
        glBindImageTexture(RANRYU_IMG_SCENE, scene_color_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(RANRYU_IMG_FRAME, target.color().id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        compose_.use();
        const auto local = compose_.local_size();
        glDispatchCompute(GLuint(target.width() + int(local[0]) - 1) / local[0], GLuint(target.height() + int(local[1]) - 1) / local[1], 1);
        for (GLuint unit : {GLuint(RANRYU_IMG_SCENE), GLuint(RANRYU_IMG_FRAME)})
            glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        glCopyImageSubData(scene_depth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, target.depth().id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                           target.width(), target.height(), 1);
        // The frame is drawn over, blended, blitted and read back; the scene is sampled and read back.
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_PIXEL_BUFFER_BARRIER_BIT);
    }
    bind_target(target);
    if (surface) {
        // (R1)-(R7): the front faces nearest the eye, over the opaque scene.
        auto pass = timer_.scope(surface_pass_);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        bind_texture(RANRYU_TEX_THICKNESS, thickness_);
        bind_texture(RANRYU_TEX_SCENE_COLOR, scene_color_);
        surface_.use();
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        draw_mesh(*surface, mesh_vao_);
        glDisable(GL_CULL_FACE);
    }
    for (GLuint unit : {RANRYU_TEX_SCENE_COLOR, RANRYU_TEX_SCENE_DEPTH, RANRYU_TEX_THICKNESS, RANRYU_TEX_SHADOW_NEAR,
                        RANRYU_TEX_SHADOW_THICKNESS, RANRYU_TEX_SCENE_LIT}) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::draw(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
                    std::size_t count, const SurfaceMesh* surface, const SubparticleDraw* sub) {
    if (shading_ == Shading::water) {
        draw_water(target, surface);
        return;
    }
    bind_target(target);
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
        draw_mesh(*surface, mesh_vao_);
    } else if (impostor_raster_.depth.id() && (!sub || sub->dispatch_group != 0)) {
        rasterise_impostors(target, positions, velocities, count, sub);
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

void Renderer::rasterise_impostors(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
                                   std::size_t count, const SubparticleDraw* sub) {
    if (sub && !impostor_raster_levels_.depth.id())
        throw Error("Renderer::draw: sub-particles given to a renderer built without them");
    const ImpostorPrograms& raster = sub ? impostor_raster_levels_ : impostor_raster_;
    if (impostor_near_.width() != target.width() || impostor_near_.height() != target.height())
        throw Error("Renderer::draw: the impostors' targets are " + std::to_string(impostor_near_.width()) + "x" +
                    std::to_string(impostor_near_.height()) + ", the frame is " + std::to_string(target.width()) + "x" +
                    std::to_string(target.height()) + " (Renderer::resize first)");
    auto pass = timer_.scope(particles_pass_);
    {
        // No depth (the bits of +inf order above every depth in [0, 1]), no particle, no large one.
        auto within = timer_.scope(impostor_within_.fill);
        fill(impostor_near_, std::numeric_limits<float>::infinity());
        fill(impostor_id_, 0.0f);
        const glm::uvec4 header(0u, RANRYU_IMPOSTOR_LARGE_TILES, 1u, 0u);
        glBindBuffer(GL_COPY_WRITE_BUFFER, impostor_large_.id());
        glClearBufferSubData(GL_COPY_WRITE_BUFFER, GL_RGBA32UI, 0, sizeof header, GL_RGBA_INTEGER, GL_UNSIGNED_INT, &header);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    }
    shader::StorageSet buffers{{"Positions", &positions}, {"ImpostorLarge", &impostor_large_}};
    if (sub)
        buffers.add("SubparticleLevels", sub->parent_levels).add("SubparticlePositions", sub->positions).add("Subparticles", sub->indirect);
    // R32F textures as 32-bit unsigned images: the same size class, the bits as they are.
    glBindImageTexture(RANRYU_IMG_IMPOSTOR_DEPTH, impostor_near_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(RANRYU_IMG_IMPOSTOR_ID, impostor_id_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    // Each particle (and each sub-particle, from the spawn pass's indirect dispatch), then the large
    // ones they listed, from the list's header.
    auto both = [&](const shader::Program& each, const shader::Program& large) {
        glProgramUniform1ui(each.id(), RANRYU_LOC_COUNT, GLuint(count));
        const GLuint draw_word = sub ? GLuint(sub->draw_offset / sizeof(std::uint32_t)) : 0u;
        if (sub) glProgramUniform3ui(each.id(), RANRYU_LOC_IMPOSTOR_CHILDREN, 0u, sub->dispatch_group, draw_word);
        each.bind(buffers).dispatch(count);
        if (sub) {   // no barrier between: both take their pixels and the list's slots by atomics
            glProgramUniform3ui(each.id(), RANRYU_LOC_IMPOSTOR_CHILDREN, 1u, sub->dispatch_group, draw_word);
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, sub->indirect.id());
            glDispatchComputeIndirect(GLintptr(sub->dispatch_offset));
        }
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        large.bind(buffers).use();
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, impostor_large_.id());
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    };
    {
        auto within = timer_.scope(impostor_within_.rasterise);
        both(raster.depth, raster.depth_large);
    }
    {
        auto within = timer_.scope(impostor_within_.resolve);
        both(raster.resolve, raster.resolve_large);
    }
    {
        auto within = timer_.scope(impostor_within_.shade);
        bind_target(target);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glBindVertexArray(empty_vao_.id());
        raster.shade.bind(buffers.with("Velocities", velocities)).use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    for (GLuint unit : {GLuint(RANRYU_IMG_IMPOSTOR_DEPTH), GLuint(RANRYU_IMG_IMPOSTOR_ID)})
        glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void Renderer::draw_sphere(const gl::RenderTarget& target, const gl::Buffer& sphere) {
    if (!impostor_sphere_.id()) throw Error("Renderer::draw_sphere: a renderer built without the paddle");
    auto pass = timer_.scope(paddle_pass_);
    bind_target(target);
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
