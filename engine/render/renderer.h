#pragma once
// The raster stage: floor, tank, and either the particles (per-pixel Phong on sphere impostors) or
// the liquid surface that marching cubes meshed, shaded in one of the Shading modes.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/shading.h"
#include "shader/program.h"
#include "shared/bindings.h"

namespace ranryu::scene { struct Scene; }

namespace ranryu::render {

// How the liquid is drawn. particles: sphere impostors (no surface is built). The others draw the
// marching-cubes mesh: phong (per pixel, glsl/render/surface_phong.frag), gouraud (Phong per vertex,
// interpolated), fresnel (reflection and refraction of the environment, surface_fresnel.frag), water
// (docs/RENDERING.md: the opaque scene of sky, tiled floor and walls drawn first, with the liquid's
// shadow from the sun; the surface refracts it through the liquid's thickness with Beer-Lambert
// absorption and reflects the sky by Fresnel, with a sun highlight; surface_water.frag).
enum class Shading { particles, phong, gouraud, fresnel, water };
std::optional<Shading> parse_shading(std::string_view name);
const char* shading_name(Shading s);
// The names of the modes, comma-separated, in the order the window's key cycles them.
const char* shading_names();
// particles for the ballistic model (no level set), water for SPH.
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
// and velocities, and the buffer holding their glDrawArraysIndirect arguments at byte draw_offset (its
// instances: the sub-particles) and, for the impostors' compute raster, the indirect dispatch of
// `dispatch_group` sub-particles a workgroup at byte dispatch_offset, in the same buffer.
// dispatch_group 0: no dispatch given, the draw draws them.
struct SubparticleDraw {
    const gl::Buffer& parent_levels;
    const gl::Buffer& positions;
    const gl::Buffer& velocities;
    const gl::Buffer& indirect;
    std::size_t draw_offset;
    std::size_t dispatch_offset = 0;
    GLuint dispatch_group = 0;
};

struct Camera {
    glm::vec3 eye{2.0f, 1.5f, 2.5f};
    glm::vec3 target{0.5f, 0.3f, 0.3f};
    float fov_deg = 40.0f;
};
Camera scene_camera(const scene::Scene& s);

// FrameParams for a scene seen through `cam` at `width`×`height`. Pure math (tests use it).
gpu::FrameParams frame_params(const scene::Scene& s, const Camera& cam, int width, int height);

// The sun's orthographic view for the water mode's shadow map (docs/RENDERING.md (R8)): a cube of
// half-side `radius` around `origin`, the centre of the box holding the floor quad and twice the
// tank's height, looking along −light_dir. `matrix` takes world to its clip space; s(x) = (x −
// origin)·(−l) is the sun depth. Pure math (tests use it).
struct SunView {
    glm::mat4 matrix;
    glm::vec3 origin;
    float radius;
};
SunView sun_view(const gpu::FrameParams& p);

// The water mode's cost options (docs/RENDERING.md (R5), (R13); docs/PERFORMANCE.md).
struct WaterOptions {
    // true: the opaque scene (sky, floor, walls, tank edges) is drawn into the scene cache only when
    // the view changes (set_frame() with other parameters, resize()); "compose" applies the liquid's
    // shadow to it every frame, (R13). false: drawn every frame, the floor and walls shading their
    // own shadow (R11): the reference the tests compare the cache with.
    bool cache_scene = true;
    // The liquid's thickness (R5) is drawn at 1/thickness_divisor of the frame's size along each axis
    // (1 to 4; sizes rounded up) and upsampled bilinearly by the surface pass.
    int thickness_divisor = 2;
    // How the two passes that need the mesh's positions alone, "shadow-map" and "liquid-thickness",
    // rasterise it: compute, one invocation per triangle with fixed-point edge functions and integer
    // atomics into the same targets (docs/RENDERING.md (R14)), off the raster hardware; draw,
    // glDrawArraysIndirect with MIN and ADD blending. Both leave the same quantities in the same R32F
    // textures, within (R14)'s bounds.
    enum class Raster { compute, draw };
    Raster raster = Raster::compute;
    // The scene every frame, the thickness at the frame's size (the drawing before the first two
    // options), with the default raster.
    static WaterOptions reference() { return WaterOptions{false, 1}; }
    // The defaults, or what the environment sets (to measure each option on one build):
    // RANRYU_WATER_CACHE=0|1 (cache_scene), RANRYU_WATER_THICKNESS_DIVISOR=1..4,
    // RANRYU_WATER_RASTER=compute|draw; throws InputError for another value. Start-up only.
    static WaterOptions from_environment();
};

// How "draw-particles" rasterises the sphere impostors (docs/RENDERING.md (R15)). compute: by
// rasterise_impostors.comp into two R32F targets of the frame's size (the nearest depth, then the
// particle there), shaded by one full-target fragment pass (shade_impostors.frag): the raster
// hardware draws one triangle, where the draw sends it two a particle (on the H100 and H200 two TPCs are
// graphics-capable). draw: glDrawArraysInstanced of the silhouette quads (impostor.vert, impostor.frag). Both
// leave the same pixels within the rounding of the eye ray, but for a sphere the near plane cuts,
// which only the draw shows. The paddle is drawn by the draw either way.
struct ImpostorOptions {
    enum class Raster { compute, draw };
    Raster raster = Raster::compute;
    // Particles whose silhouette holds more than RANRYU_IMPOSTOR_LARGE_PIXELS pixels that the second
    // dispatch takes (glsl/render/shading.h), 1 to 65535 (its workgroups along x); the rest are done by
    // their own invocation. Tests lower it.
    unsigned large_capacity = RANRYU_IMPOSTOR_LARGE_CAPACITY;
    // For the current context: compute, but draw on a software rasteriser (gl::software_renderer()),
    // whose draw visits only the covered pixels where compute's fill and shading visit every one
    // (llvmpipe at 960x540: about 0.3 against 25 ms); RANRYU_PARTICLE_RASTER=compute|draw sets it,
    // and throws InputError for another value.
    static ImpostorOptions from_environment();
};

class Renderer {
public:
    // Builds the floor, tank and impostor programs, and the surface program of `shading` only (with
    // its pass "draw-surface") when it is not particles. `subparticles`: also the impostor variant that
    // draws by sub-particle level (glsl/render/impostor.*, RANRYU_BY_LEVEL). `paddle`: also the one
    // that draw_sphere() draws with (RANRYU_RADIUS_IN_W).
    // `water`: the water mode's options; `impostors`: the particles mode's, whose compute raster's
    // programs are built in that mode (and, with `subparticles`, their BY_LEVEL variants).
    Renderer(const shader::FileSource& shaders, profile::GpuTimer& timer, Shading shading = Shading::particles,
             bool subparticles = false, bool paddle = false, WaterOptions water = {}, ImpostorOptions impostors = {});

    // Copied into the FrameParams UBO (and the sun's view). Parameters other than the last ones make
    // the water mode's scene cache stale: the next draw() draws it again (a CPU decision, no readback).
    void set_frame(const gpu::FrameParams& p);
    const gpu::FrameParams& frame() const { return frame_; }
    // Fresnel and water modes: Beer-Lambert absorption coefficients of the water (1/m, per channel).
    void set_absorption(glm::vec3 sigma);
    Shading shading() const { return shading_; }

    // Water mode: allocates the targets of a width x height frame (the scene cache, the opaque scene's
    // colour, the liquid's thickness); particles mode with the compute raster: the impostors' depth and
    // particle targets. draw() requires them at its target's size. Start-up or resize only: nothing is
    // allocated while drawing. Other modes: nothing.
    void resize(int width, int height);
    // Device memory of those targets for a width x height frame (0 for the other modes).
    static std::size_t bytes_for(Shading s, int width, int height, WaterOptions water = {}, ImpostorOptions impostors = {});
    const WaterOptions& water_options() const { return water_; }
    // Water mode, for tests: the opaque scene with this frame's shadow (RGBA16F, linear) and its depth
    // (the cache's), the liquid's thickness along each view ray (R32F, m; at 1/thickness_divisor of
    // the frame's size), and the sun's map of the liquid: nearest sun depth and thickness (R32F, m).
    const gl::Texture2D& scene_color() const { return scene_color_; }
    const gl::Texture2D& scene_depth() const { return scene_depth_; }
    const gl::Texture2D& thickness() const { return thickness_; }
    const gl::Texture2D& shadow_near() const { return shadow_near_; }
    const gl::Texture2D& shadow_thickness() const { return shadow_thickness_; }

    // Passes "clear", "draw-floor", "draw-tank", then "draw-particles" into `target` (`count`
    // particles whose positions and velocities are vec4 arrays) or, when the shading is not
    // particles and `surface` is given, "draw-surface": glDrawArraysIndirect of the mesh, no readback.
    // Water mode: "shadow-map"; "clear", "draw-sky", "draw-floor", "draw-walls", "draw-tank" (the
    // opaque scene, into the scene cache) only in a frame whose view changed (every frame without
    // WaterOptions::cache_scene); "liquid-thickness", "compose" (the cache with this frame's shadow,
    // into `target` with its depth), "draw-surface"; without `surface`, the scene with no liquid.
    // "draw-particles" by the compute raster (ImpostorOptions) times its dispatches within it:
    // "draw-particles.fill", ".rasterise", ".resolve" and ".shade".
    // With `sub` (particles shading, built with subparticles), "draw-particles" draws the parents
    // that were not split and then the sub-particles (the compute raster from sub's dispatch; the draw
    // by glDrawArraysIndirect, and where sub gives no dispatch), coloured by level and of radius
    // r/2^level.
    void draw(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
              std::size_t count, const SurfaceMesh* surface = nullptr, const SubparticleDraw* sub = nullptr);
    // Pass "draw-paddle": one sphere into `target` over what draw() left in it (depth-tested), from
    // `sphere`: vec4 (center, radius) then vec4 (velocity, 0), drawn as an impostor coloured by its
    // speed like the particles. Needs a renderer built with `paddle`.
    void draw_sphere(const gl::RenderTarget& target, const gl::Buffer& sphere);

    // Spray and foam over a drawn frame (renderers built with subparticles and a surface shading):
    // pass "draw-spray", the sub-particles as white discs of radius r/2^level and opacity rising with
    // their energy above e_min (glsl/render/spray.vert), blended and depth-tested against what
    // draw() left in `target`; glDrawArraysIndirect of sub.indirect, no readback.
    void draw_spray(const gl::RenderTarget& target, const SubparticleDraw& sub);
    // e_min (m²/s²): the sub-particles' least energy, e_th·2^(−2β) (spray.vert).
    void set_spray_energy(float e_min);
    bool draws_spray() const { return spray_.id() != 0; }

private:
    void bind_target(const gl::RenderTarget& target);   // its framebuffer, its viewport, the frame's constants
    void draw_water(const gl::RenderTarget& target, const SurfaceMesh* surface);
    void draw_scene();   // the water mode's scene cache: "clear", "draw-sky", "draw-floor", "draw-walls", "draw-tank"
    void fill(const gl::Texture2D& r32f, float value);   // fill_image.comp over the whole texture
    // The compute raster (R14): size_raster.comp writes raster_dispatch_ from the mesh's draw count and
    // empties raster_large_'s lists; rasterise() dispatches `program` (rasterise_layers.comp)
    // indirectly over the triangles, then `large` over those it listed, into `sum` (r32i) and `near`
    // (r32ui, the sun's view only, whose list is the first); decode() turns them into the floats the
    // draws leave (decode_raster.comp). Each ends with the barrier its reader needs.
    void size_raster(const SurfaceMesh& surface);
    void rasterise(const SurfaceMesh& surface, const shader::Program& program, const shader::Program& large, const gl::Texture2D& sum,
                   const gl::Texture2D* near);
    void decode(const shader::Program& program, const gl::Texture2D& sum, const gl::Texture2D* near);
    // Every layer of the mesh, by its positions alone, into `fbo` at the size of `size_of`, blended
    // (ONE, ONE) with the equations the caller set: the shadow map and the thickness.
    void draw_layers(const SurfaceMesh& surface, const gl::Framebuffer& fbo, const gl::Texture2D& size_of,
                     const shader::Program& program);
    void draw_mesh(const SurfaceMesh& surface, const gl::VertexArray& vao);
    // "draw-particles" by the compute raster (R15), into the bound target over its floor and tank.
    void rasterise_impostors(const gl::RenderTarget& target, const gl::Buffer& positions, const gl::Buffer& velocities,
                             std::size_t count, const SubparticleDraw* sub);

    profile::GpuTimer& timer_;
    Shading shading_;
    profile::PassId clear_pass_, floor_pass_, tank_pass_, particles_pass_, surface_pass_{}, spray_pass_{}, paddle_pass_{};
    shader::Program floor_, tank_, impostor_, surface_, impostor_levels_, spray_, impostor_sphere_;
    gl::VertexArray empty_vao_, particle_vao_, mesh_vao_, mesh_position_vao_, parent_vao_;
    gl::Buffer frame_ubo_;
    gpu::FrameParams frame_{};
    // The water mode's passes, programs and targets (docs/RENDERING.md). The scene cache: lit_color_
    // (C_lit and q of (R13), RGBA16F) and scene_depth_, drawn when drawn_generation_ falls behind
    // generation_, which set_frame() and resize() advance.
    WaterOptions water_;
    profile::PassId shadow_pass_{}, sky_pass_{}, walls_pass_{}, thickness_pass_{}, compose_pass_{};
    // The compute passes within "shadow-map" and "liquid-thickness" (profile::GpuTimer::pass(name, within)):
    // fill_image.comp, size_raster.comp, rasterise_layers.comp and decode_raster.comp.
    struct RasterPasses {
        profile::PassId fill, size, rasterise, decode;
    };
    RasterPasses shadow_within_{}, thickness_within_{};
    shader::Program shadow_, sky_, tiles_floor_, tiles_walls_, thickness_prog_, compose_, fill_;
    gl::Texture2D shadow_near_, shadow_thickness_, lit_color_, scene_color_, scene_depth_, thickness_;
    gl::Framebuffer shadow_fbo_, scene_fbo_, thickness_fbo_;
    // The compute raster's programs (WaterOptions::Raster::compute), its indirect dispatch (uvec4:
    // workgroups, triangles) and its lists of large triangles (two uvec4 headers, the sun's and the
    // eye's, then RANRYU_RASTER_LARGE_CAPACITY indices each), written on the GPU every frame.
    shader::Program size_raster_, raster_shadow_, raster_thickness_, raster_shadow_large_, raster_thickness_large_, decode_shadow_,
        decode_thickness_;
    gl::Buffer raster_dispatch_, raster_large_;
    // The impostors' compute raster (R15): its programs (the first dispatch, its LARGE variant, both
    // again with RESOLVE; the shading), plain and (renderers built with sub-particles) BY_LEVEL, its
    // two targets and the list of large spheres (a uvec4 header, then ImpostorOptions::large_capacity
    // ids), its passes within "draw-particles".
    ImpostorOptions impostors_;
    struct ImpostorPrograms {
        shader::Program depth, depth_large, resolve, resolve_large, shade;
    };
    ImpostorPrograms impostor_raster_, impostor_raster_levels_;
    gl::Texture2D impostor_near_, impostor_id_;
    gl::Buffer impostor_large_;
    struct ImpostorPasses {
        profile::PassId fill, rasterise, resolve, shade;
    };
    ImpostorPasses impostor_within_{};
    std::uint64_t generation_ = 1, drawn_generation_ = 0;
};

}  // namespace ranryu::render
