#include "frame/pipeline.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"
#include "gl/faults.h"
#include "sim/fluid.h"
#include "turbulence/force.h"

namespace ranryu::frame {

namespace {
render::Shading checked_shading(const scene::Scene& s, std::optional<render::Shading> shading) {
    const render::Shading sh = shading.value_or(render::default_shading(s));
    if (render::needs_surface(sh) && s.model != scene::Model::sph)
        throw InputError(std::string("--shading ") + render::shading_name(sh) + ": scene " + s.name +
                         " uses the ballistic model, which has no liquid surface; use --shading particles");
    return sh;
}

// The level set's settings (surface/level_set.h defaults with the scene's grid) and the mesh's capacity.
surface::LevelSetSettings level_set_settings(const scene::Scene& s) {
    surface::LevelSetSettings ls = surface::LevelSetSettings::for_spacing(s.spacing);
    ls.node_spacing = s.surface.node_spacing * s.spacing;
    ls.max_dims = glm::uvec3(std::uint32_t(s.surface.max_dims));
    ls.subparticle_levels = s.turbulence.subparticles.enabled() ? s.turbulence.subparticles.levels : 0;
    ls.max_nodes = std::uint32_t(s.surface.max_nodes);
    ls.anisotropic = s.surface.anisotropic;
    ls.particle_capacity = s.particle_capacity();   // the emitter's budget included
    return ls;
}
surface::MeshCapacity mesh_capacity(const scene::Scene& s) {
    surface::MeshCapacity c{glm::uvec3(std::uint32_t(s.surface.max_dims)), std::size_t(s.surface.max_vertices)};
    c.max_nodes = std::size_t(s.surface.max_nodes);
    return c;
}
}  // namespace

MemoryEstimate Pipeline::memory_estimate(const scene::Scene& s, const View& view) {
    MemoryEstimate e;
    e.particles = s.particle_capacity();
    e.extra = view.extra_bytes;
    const std::size_t n = e.particles;
    if (s.model == scene::Model::sph) {
        e.boundary = sim::Fluid::boundary_count(s);
        e.parts.push_back({"particles, boundary, grid and sort", sim::Fluid::bytes_for(s, n, e.boundary)});
        e.transient = sim::Fluid::transient_bytes(e.boundary);
        e.parts.push_back({std::string("solver ") + scene::solver_name(s.sph.solver),
                           sim::solver_bytes(s, n)});
        if (s.turbulence.enabled()) e.parts.push_back({"turbulence", turbulence::TurbulenceForce::bytes_for(n)});
        if (s.turbulence.subparticles.enabled())
            e.parts.push_back({"sub-particles", turbulence::Subparticles::bytes_for(s.turbulence.subparticles, n)});
        if (view.draw && render::needs_surface(view.shading.value_or(render::default_shading(s)))) {
            e.parts.push_back({"level set", surface::LevelSet::bytes_for(level_set_settings(s))});
            e.parts.push_back({"marching cubes", surface::MarchingCubes::bytes_for(mesh_capacity(s))});
        }
    } else {
        e.parts.push_back({"particles", sim::Particles::bytes_for(n)});
    }
    if (view.draw) e.parts.push_back({"render target", gl::RenderTarget::bytes_for(view.width, view.height)});
    const render::Shading shading = view.shading.value_or(render::default_shading(s));
    if (view.draw && shading == render::Shading::water)
        e.parts.push_back({"water shading targets",
                           render::Renderer::bytes_for(shading, view.width, view.height, render::WaterOptions::from_environment())});
    if (view.draw && shading == render::Shading::particles)
        if (const std::size_t b = render::Renderer::bytes_for(shading, view.width, view.height, {},
                                                              render::ImpostorOptions::from_environment()))
            e.parts.push_back({"impostor raster targets", b});
    if (view.draw && s.model == scene::Model::sph && s.paddle_radius > 0.0f) e.parts.push_back({"paddle's sphere", 2 * sizeof(glm::vec4)});
    return e;
}

Pipeline::Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, const View& view)
    : scene_(scene),
      // 6 query sets: two more than the deepest record readback of a fluid (sim::Fluid::record_depth()),
      // which bounds how far the CPU runs ahead (gl/readback.h), so a frame goes untimed (GpuTimer) only
      // when the GPU falls further behind.
      timer_(6, scene.model == scene::Model::sph ? 2048 : 64 + scene.substeps()),   // grows when a frame makes more
      shading_(checked_shading(scene, view.shading)),
      camera_(render::scene_camera(scene)),
      substeps_(scene.substeps()) {
    // Before anything is allocated.
    const std::uint64_t before = gl::allocated_bytes(), peak_before = gl::peak_allocated_bytes();
    memory_.device = device_memory();
    memory_.estimate = check_memory(scene_, view, memory_.device);
    const bool sph = scene_.model == scene::Model::sph;
    if (view.draw) {
        renderer_ = std::make_unique<render::Renderer>(shaders, timer_, shading_, sph && scene_.turbulence.subparticles.enabled(),
                                                       sph && scene_.paddle_radius > 0.0f, render::WaterOptions::from_environment(),
                                                       render::ImpostorOptions::from_environment());
        if (sph && scene_.paddle_radius > 0.0f) paddle_sphere_ = gl::Buffer(2 * sizeof(glm::vec4), GL_DYNAMIC_DRAW, nullptr, "paddle.sphere");
        target_ = gl::RenderTarget(view.width, view.height, "frame");
        renderer_->resize(view.width, view.height);
    }
    if (sph) {
        sph_ = std::make_unique<sim::Simulation>(shaders, timer_, scene_);
        if (scene_.turbulence.subparticles.enabled())
            sub_ = std::make_unique<turbulence::Subparticles>(shaders, timer_, scene_.turbulence, scene_.spacing, sph_->fluid().count(),
                                                              sph_->turbulence()->tiles(), sph_->turbulence()->noise());
        if (view.draw && render::needs_surface(shading_)) {
            level_set_ = std::make_unique<surface::LevelSet>(shaders, timer_, level_set_settings(scene_));
            mc_ = std::make_unique<surface::MarchingCubes>(shaders, timer_, mesh_capacity(scene_));
            renderer_->set_absorption(scene_.surface.absorption);
            if (sub_)   // spray.vert: the sub-particles' least energy, e_th·2^(−2β)
                renderer_->set_spray_energy(scene_.turbulence.subparticles.threshold * std::exp2(-2.0f * scene_.turbulence.beta));
        }
    } else {
        ballistic_ = std::make_unique<sim::Particles>(shaders, timer_);
        ballistic_->reset(scene_.initial_positions(), scene_.initial_velocities());
        ballistic_->set_params(sim::sim_params(scene_, ballistic_->count()));
    }
    if (renderer_) renderer_->set_frame(render::frame_params(scene_, camera_, view.width, view.height));
    memory_.allocated = gl::allocated_bytes() - before;
    memory_.peak = gl::peak_allocated_bytes() > peak_before ? gl::peak_allocated_bytes() - before : memory_.allocated;
    if (const char* at = std::getenv("RANRYU_FAULT_AT_FRAME")) {
        char* end = nullptr;
        const unsigned long long n = std::strtoull(at, &end, 10);
        if (!*at || *end) throw InputError(std::string("RANRYU_FAULT_AT_FRAME=") + at + ": expected a frame number");
        inject_fault_at_ = n;
        fault_pass_ = timer_.pass("fault-injection");
    }
}

std::string SkippedStage::text() const {
    std::string out;
    for (const std::string& p : passes) out += (out.empty() ? "" : ", ") + p;
    return whose.empty() ? out : out + ": " + whose;
}

bool SkippedStage::names(std::string_view pass) const {
    for (const std::string& n : passes)
        if (n == pass || (n.ends_with('*') && pass.starts_with(std::string_view(n).substr(0, n.size() - 1)))) return true;
    return false;
}

std::vector<SkippedStage> Pipeline::skipped_stages() const {
    std::vector<SkippedStage> out;
    if (!sph_) {
        out.push_back({{"hash", "sort.*", "reorder", "density", "forces", "integrate", "dfsph.*", "pbf.*"}, "the SPH model's",
                       "the scene uses the ballistic model, no SPH"});
    } else {
        const std::string solver = std::string("the solver is ") + scene::solver_name(scene_.sph.solver);
        if (scene_.sph.solver != scene::Solver::wcsph) out.push_back({{"density", "forces", "integrate"}, "WCSPH's", solver});
        if (scene_.sph.solver != scene::Solver::dfsph) out.push_back({{"dfsph.*"}, "", solver});
        if (scene_.sph.solver != scene::Solver::pbf) out.push_back({{"pbf.*"}, "", solver});
        else if (scene_.sph.pbf.vorticity <= 0.0f) out.push_back({{"pbf.vorticity"}, "", "sph.pbf.vorticity is 0"});
        if (scene_.sph.sort == "radix") out.push_back({{"sort.bitonic_local", "sort.bitonic_global", "sort.bitonic_merge_local"}, "", "sph.sort is radix"});
        else out.push_back({{"sort.count", "sort.scan", "sort.scatter"}, "", "sph.sort is bitonic"});
        if (!sph_->turbulence()) out.push_back({{"wavelet", "turbulence-force"}, "", "turbulence.amplitude is 0"});
        if (!sub_) out.push_back({{"subparticles.*"}, "", sph_->turbulence() ? "turbulence.subparticles is off" : "turbulence is off"});
        if (!level_set_)
            out.push_back({{"surface.anisotropy", "surface.bounds", "level-set.splat", "level-set", "mc.*", "draw-surface"}, "",
                           renderer_ ? "the shading draws particles" : "nothing is drawn"});
        else if (!scene_.surface.anisotropic)
            out.push_back({{"surface.anisotropy", "level-set.splat"}, "", "surface.anisotropic is false"});
    }
    if (!renderer_) out.push_back({{"clear", "draw-*"}, "", "nothing is drawn: a validation run"});
    else if (level_set_) out.push_back({{"draw-particles"}, "", std::string("the shading draws the surface: ") + render::shading_name(shading_)});
    return out;
}

std::string Pipeline::untimed_passes() const {
    const std::vector<SkippedStage> skipped = skipped_stages();
    auto named = [&](const std::string& pass) {
        for (const SkippedStage& st : skipped)
            if (st.names(pass)) return true;
        return false;
    };
    std::string out;
    // A pass within another that ran untimed (GpuTimer::detail() off) is the report's, not this list's.
    const std::vector<std::uint64_t> untimed = timer_.untimed_calls();
    for (std::size_t k = 0; k < timer_.passes().size(); ++k) {
        const profile::PassSamples& p = timer_.passes()[k];
        if (p.ms.empty() && untimed[k] == 0 && !named(p.name)) out += (out.empty() ? "" : ", ") + p.name;
    }
    return out;
}

void Pipeline::simulate() {
    ++simulated_frames_;
    if (!sph_) {
        for (int s = 0; s < substeps_; ++s) ballistic_->integrate();
        return;
    }
    sim::Fluid& fluid = sph_->fluid();
    sph_->begin_frame(frames_);
    for (int s = 0; s < sph_->substeps_this_frame(); ++s) sph_->step();
    // The sub-particles of the last step's state: its cell order, ê and carried-noise seeds.
    if (sub_) sub_->generate(fluid, *sph_->turbulence(), frames_);
    if (level_set_) {
        // After the last step the positions are in the cell order of its grid build, moved by that
        // step's integration (within LevelSetSettings::search_margin).
        std::optional<surface::SubparticleSurface> with;
        if (sub_) with.emplace(surface::SubparticleSurface{sub_->levels(), sub_->positions(), sub_->state(),
                                                           turbulence::Subparticles::dispatch_offset, sub_->dispatch_group()});
        level_set_->compute(fluid.grid(), fluid.positions(), fluid.cell_ranges(), fluid.count(), with ? &*with : nullptr);
        mc_->polygonise(level_set_->phi(), level_set_->grid());
    }
    sph_->end_frame();
}

void Pipeline::draw() {
    if (!renderer_) return;
    if (mc_) {
        const render::SurfaceMesh mesh{mc_->vertices(), mc_->state(), surface::MarchingCubes::draw_offset};
        renderer_->draw(target_, positions(), velocities(), particle_count(), &mesh);
        if (sub_)
            renderer_->draw_spray(target_, render::SubparticleDraw{sub_->levels(), sub_->positions(), sub_->velocities(),
                                                                   sub_->state(), turbulence::Subparticles::draw_offset});
    } else if (sub_) {
        const render::SubparticleDraw sub{sub_->levels(),
                                          sub_->positions(),
                                          sub_->velocities(),
                                          sub_->state(),
                                          turbulence::Subparticles::draw_offset,
                                          turbulence::Subparticles::dispatch_offset,
                                          sub_->dispatch_group()};
        renderer_->draw(target_, positions(), velocities(), particle_count(), nullptr, &sub);
    } else {
        renderer_->draw(target_, positions(), velocities(), particle_count());
    }
    if (paddle_sphere_.id() && sph_->paddle_on()) {
        const glm::vec4 sphere[2] = {glm::vec4(sph_->paddle_center(), sph_->paddle_scale() * sph_->fluid().paddle_radius()),
                                     glm::vec4(sph_->paddle_velocity(), 0.0f)};
        paddle_sphere_.upload(sphere, sizeof sphere);
        renderer_->draw_sphere(target_, paddle_sphere_);
    }
}

void Pipeline::end_frame() {
    if (inject_fault_at_ && frames_ == *inject_fault_at_) {
        auto pass = timer_.scope(*fault_pass_);
        glBindBuffer(GL_ARRAY_BUFFER, 0xFFFFFFF0u);   // a name never generated: GL_INVALID_OPERATION
    }
    timer_.end_frame();
    gl::check_faults(frames_);   // a GL error in a pass (with error checks on) or a lost context: exit 1
    ++frames_;
}

std::optional<std::uint64_t> Pipeline::poll() {
    if (!sph_) return frames_ ? std::optional<std::uint64_t>(frames_ - 1) : std::nullopt;
    sim::Fluid& fluid = sph_->fluid();
    fluid.poll_records();
    if (sub_) sub_->poll();
    if (fluid.instability()) return std::nullopt;
    return fluid.guard().sound_through();   // frames past a bound wait for the next to pass as a spike
}

const std::optional<sim::Instability>& Pipeline::instability() const {
    static const std::optional<sim::Instability> none;
    return sph_ ? sph_->fluid().instability() : none;
}

void Pipeline::drain() {
    timer_.drain();
    if (sph_) sph_->fluid().drain_records();
    if (sub_) sub_->drain();
}

std::optional<std::size_t> Pipeline::active_particles() const {
    if (!sph_) return ballistic_->count();
    const auto& last = sph_->fluid().last_record();
    return last ? std::optional<std::size_t>(last->live_count) : std::nullopt;
}

std::size_t Pipeline::particle_count() const { return sph_ ? sph_->fluid().count() : ballistic_->count(); }
const gl::Buffer& Pipeline::positions() const { return sph_ ? sph_->fluid().positions() : ballistic_->positions(); }
const gl::Buffer& Pipeline::velocities() const { return sph_ ? sph_->fluid().velocities() : ballistic_->velocities(); }

double Pipeline::simulated_time() const {
    if (sph_) return sph_->fluid().last_record() ? double(sph_->fluid().last_record()->time) : 0.0;
    return double(simulated_frames_) * double(ballistic_->params().dt) * substeps_;
}

std::optional<std::uint32_t> Pipeline::substeps_per_frame() const {
    if (!sph_) return std::uint32_t(substeps_);
    const auto& last = sph_->fluid().last_record();
    return last ? std::optional<std::uint32_t>(last->frame_substeps) : std::nullopt;
}

void Pipeline::set_camera(const render::Camera& cam) {
    camera_ = cam;
    if (renderer_) renderer_->set_frame(render::frame_params(scene_, camera_, target_.width(), target_.height()));
}

void Pipeline::persist(sim::StateIo& io) {
    io.value("pipeline.frames", frames_);
    io.value("pipeline.simulated_frames", simulated_frames_);
    if (io.loading()) first_frame_ = frames_;
    if (sph_) sph_->persist(io);
    else ballistic_->persist(io);
}

}  // namespace ranryu::frame
