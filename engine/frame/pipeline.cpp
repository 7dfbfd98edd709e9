#include "frame/pipeline.h"

#include "core/error.h"
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
}  // namespace

Pipeline::Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, int width, int height,
                   std::optional<render::Shading> shading)
    : scene_(scene),
      timer_(4, scene.model == scene::Model::sph ? 64 + sim::timed_passes_per_substep(scene) * 64 : 64 + scene.substeps()),
      renderer_(shaders, timer_, checked_shading(scene, shading),
                scene.model == scene::Model::sph && scene.turbulence.subparticles.enabled()),
      target_(width, height, "frame"),
      camera_(render::scene_camera(scene)),
      substeps_(scene.substeps()) {
    if (scene_.model == scene::Model::sph) {
        sph_ = std::make_unique<sim::Sph>(shaders, timer_, scene_);
        if (scene_.turbulence.subparticles.enabled())
            sub_ = std::make_unique<turbulence::Subparticles>(shaders, timer_, scene_.turbulence, scene_.spacing, sph_->count(),
                                                              sph_->turbulence()->tiles(), sph_->turbulence()->noise());
        if (render::needs_surface(renderer_.shading())) {
            // Level set defaults (surface/level_set.h) with the scene's grid; the mesh's capacity.
            surface::LevelSetSettings ls = surface::LevelSetSettings::for_spacing(scene_.spacing);
            ls.node_spacing = scene_.surface.node_spacing * scene_.spacing;
            ls.max_dims = glm::uvec3(std::uint32_t(scene_.surface.max_dims));
            ls.subparticle_levels = sub_ ? scene_.turbulence.subparticles.levels : 0;
            level_set_ = std::make_unique<surface::LevelSet>(shaders, timer_, ls);
            mc_ = std::make_unique<surface::MarchingCubes>(
                shaders, timer_, surface::MeshCapacity{ls.max_dims, std::size_t(scene_.surface.max_vertices)});
            renderer_.set_absorption(scene_.surface.absorption);
        }
    } else {
        ballistic_ = std::make_unique<sim::Particles>(shaders, timer_);
        ballistic_->reset(scene_.initial_positions(), scene_.initial_velocities());
        ballistic_->set_params(sim::sim_params(scene_, ballistic_->count()));
    }
    renderer_.set_frame(render::frame_params(scene_, camera_, width, height));
}

void Pipeline::simulate() {
    if (sph_) {
        sph_->begin_frame(frames_);
        for (int s = 0; s < sph_->substeps_this_frame(); ++s) sph_->substep();
        // The sub-particles of the last substep's state: its cell order, ê and carried-noise seeds.
        if (sub_) sub_->generate(*sph_, frames_);
        if (level_set_) {
            // After the last substep the positions are in the cell order of its grid build, moved
            // by that substep's integration (within LevelSetSettings::search_margin).
            std::optional<surface::SubparticleSurface> with;
            if (sub_) with.emplace(surface::SubparticleSurface{sub_->levels(), sub_->positions(), sub_->state(),
                                                               turbulence::Subparticles::dispatch_offset, sub_->dispatch_group()});
            level_set_->compute(sph_->grid(), sph_->positions(), sph_->cell_ranges(), sph_->count(), with ? &*with : nullptr);
            mc_->polygonise(level_set_->phi(), level_set_->grid());
        }
        sph_->end_frame();
        return;
    }
    for (int s = 0; s < substeps_; ++s) ballistic_->integrate();
}

void Pipeline::draw() {
    if (mc_) {
        const render::SurfaceMesh mesh{mc_->vertices(), mc_->state(), surface::MarchingCubes::draw_offset};
        renderer_.draw(target_, positions(), velocities(), particle_count(), &mesh);
    } else if (sub_) {
        const render::SubparticleDraw sub{sub_->levels(), sub_->positions(), sub_->velocities(), sub_->state(),
                                          turbulence::Subparticles::draw_offset};
        renderer_.draw(target_, positions(), velocities(), particle_count(), nullptr, &sub);
    } else {
        renderer_.draw(target_, positions(), velocities(), particle_count());
    }
}

void Pipeline::end_frame() {
    timer_.end_frame();
    ++frames_;
}

std::optional<std::uint64_t> Pipeline::poll() {
    if (!sph_) return frames_ ? std::optional<std::uint64_t>(frames_ - 1) : std::nullopt;
    sph_->poll_records();
    if (sub_) sub_->poll();
    if (!sph_->last_record() || sph_->instability()) return std::nullopt;
    return sph_->last_record()->frame;
}

const std::optional<sim::Instability>& Pipeline::instability() const {
    static const std::optional<sim::Instability> none;
    return sph_ ? sph_->instability() : none;
}

void Pipeline::drain() {
    timer_.drain();
    if (sph_) sph_->drain_records();
    if (sub_) sub_->drain();
}

std::size_t Pipeline::particle_count() const { return sph_ ? sph_->count() : ballistic_->count(); }
const gl::Buffer& Pipeline::positions() const { return sph_ ? sph_->positions() : ballistic_->positions(); }
const gl::Buffer& Pipeline::velocities() const { return sph_ ? sph_->velocities() : ballistic_->velocities(); }

double Pipeline::simulated_time() const {
    if (sph_) return sph_->last_record() ? double(sph_->last_record()->time) : 0.0;
    return double(frames_) * double(ballistic_->params().dt) * substeps_;
}

void Pipeline::set_camera(const render::Camera& cam) {
    camera_ = cam;
    renderer_.set_frame(render::frame_params(scene_, camera_, target_.width(), target_.height()));
}

}  // namespace ranryu::frame
