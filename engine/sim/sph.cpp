#include "sim/sph.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "sim/boundary.h"
#include "turbulence/force.h"

namespace ranryu::sim {
namespace {

std::uint32_t bits(float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

// The neighbour grid covers the tank and its boundary layers, and headroom above the open top for
// splashes (particles higher still share the top layer of cells: slower, never wrong).
GridLayout fluid_grid(const scene::Scene& s, float h, int layers) {
    const glm::vec3 pad(float(layers) * s.spacing + h);
    glm::vec3 hi = s.tank_max + pad;
    hi.y += 0.5f * (s.tank_max.y - s.tank_min.y);
    return GridLayout::covering(s.tank_min - pad, hi, h, s.sph.morton);
}

// Neighbour loops as 9 x-row runs where the keys allow it (linear keys), 27 cells otherwise
// (glsl/sim/sph/sph_common.glsl). RANRYU_NO_MERGE_ROWS=1 forces per-cell loops, for comparison.
std::string neighbour_defines(const scene::Scene& s) {
    const char* off = std::getenv("RANRYU_NO_MERGE_ROWS");
    if (s.sph.morton || (off && std::string(off) == "1")) return {};
    return "#define RANRYU_MERGE_ROWS 1\n";
}

// Runs a neighbour walk visits: 9 merged x-rows, or 27 cells (neighbour_defines()).
int runs_of(const scene::Scene& s) { return neighbour_defines(s).empty() ? 27 : 9; }

// Density records, per run, which candidates lie inside h, for forces to read instead of testing every
// candidate again (glsl/sim/sph/compute_density.comp, compute_forces.comp).
std::string list_defines(const scene::Scene& s) {
    if (!s.sph.neighbour_masks) return neighbour_defines(s);
    return neighbour_defines(s) + "#define RANRYU_NEIGHBOUR_MASKS 1\n";
}

}  // namespace

gpu::SphParams sph_params(const scene::Scene& s, std::size_t count, std::size_t boundary) {
    gpu::SphParams p{};
    const float dx = s.spacing, h = 2.0f * dx, rho0 = s.sph.rest_density, c = s.sound_speed();
    p.gravity = glm::vec4(s.gravity, 0.0f);
    // The guard's domain: the tank, a spacing of slack at the walls and floor, and room above the
    // open top for splashes to come back from.
    const float height = s.tank_max.y - s.tank_min.y;
    p.domain_min = glm::vec4(s.tank_min - dx, 0.0f);
    p.domain_max = glm::vec4(s.tank_max.x + dx, s.tank_max.y + 4.0f * height, s.tank_max.z + dx, 0.0f);
    p.h = h;
    p.mass = rho0 * dx * dx * dx;
    p.rest_density = rho0;
    p.stiffness = rho0 * c * c / 7.0f;
    p.viscosity = s.sph.viscosity;
    p.sound_speed = c;
    p.spacing = dx;
    p.cfl = s.sph.cfl;
    p.force_factor = s.sph.force_factor;
    p.dt_max = s.frame_dt;
    p.dt_floor = guard_limits(s).dt_floor;
    p.density_limit = s.sph.density_limit;
    p.speed_limit = guard_limits(s).speed;
    p.particle_count = std::uint32_t(count);
    p.boundary_count = std::uint32_t(boundary);
    p.front_band = 3.0f * dx;   // from domain_min.y = floor - dx: particles within 2 dx of the floor
    return p;
}

int timed_passes_per_substep(const scene::Scene& s) {
    // + "wavelet" and "turbulence-force" when the turbulence force is on.
    return (s.sph.sort == "bitonic" ? 110 : 24) + (s.turbulence.enabled() ? 2 : 0);
}

GuardLimits guard_limits(const scene::Scene& s) {
    GuardLimits g;
    g.density_ratio = s.sph.density_limit;
    g.speed = s.sph.speed_limit > 0.0f ? s.sph.speed_limit : 5.0f * s.speed_estimate();
    // A stable dt a hundred times below the CFL step at the expected speed means the run has blown up.
    g.dt_floor = 0.01f * s.sph.cfl * s.spacing / (s.sound_speed() + s.speed_estimate());
    return g;
}

Sph::Sph(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene)
    : timer_(timer),
      begin_pass_(timer.pass("begin-frame")),
      step_pass_(timer.pass("choose-time-step")),
      density_pass_(timer.pass("density")),
      forces_pass_(timer.pass("forces")),
      integrate_pass_(timer.pass("integrate")),
      diag_pass_(timer.pass("diagnostics")),
      boundary_pass_(timer.pass("boundary-volume")),
      boundary_cells_pass_(timer.pass("boundary-cells")),
      begin_(shader::Program::compute(shaders, "sim/sph/begin_frame.comp")),
      choose_(shader::Program::compute(shaders, "sim/sph/choose_time_step.comp")),
      density_prog_(shader::Program::compute(shaders, "sim/sph/compute_density.comp", list_defines(scene))),
      forces_(shader::Program::compute(shaders, "sim/sph/compute_forces.comp", list_defines(scene))),
      integrate_(shader::Program::compute(shaders, "sim/sph/integrate_particles.comp")),
      boundary_volume_(
          shader::Program::compute(shaders, "sim/boundary/compute_boundary_volume.comp", neighbour_defines(scene))),
      flag_boundary_(shader::Program::compute(shaders, "sim/boundary/flag_boundary_cells.comp", neighbour_defines(scene))),
      limits_(guard_limits(scene)),
      frame_dt_(scene.frame_dt),
      max_substeps_(scene.sph.max_substeps),
      grid_(shaders, timer,
            fluid_grid(scene, 2.0f * scene.spacing, boundary_layers(scene.spacing, 2.0f * scene.spacing)),
            // One sort serves the fluid every substep and the boundary once at start.
            std::max({scene.particle_count(),
                      sample_boundary(scene, boundary_layers(scene.spacing, 2.0f * scene.spacing)).size(), std::size_t(1)}),
            scene.sph.sort == "bitonic" ? SortMethod::bitonic : SortMethod::radix),
      readback_(sizeof(gpu::StepState), 4, "StepState.readback",
                [this](std::uint64_t frame, const void* bytes) { on_record(frame, bytes); }) {
    const std::vector<glm::vec4> x = scene.initial_positions(), v = scene.initial_velocities();
    const std::vector<glm::vec4> wall = sample_boundary(scene, boundary_layers(scene.spacing, 2.0f * scene.spacing));
    count_ = x.size();
    boundary_count_ = wall.size();
    params_ = sph_params(scene, count_, boundary_count_);
    params_ubo_ = gl::Buffer(sizeof(gpu::SphParams), GL_DYNAMIC_DRAW, &params_, "SphParams");
    obstacles_ = gl::Buffer::from<glm::vec4>(obstacle_shapes(scene), GL_STATIC_DRAW, "sph.obstacles");

    const std::size_t n = std::max<std::size_t>(count_, 1);
    for (int k = 0; k < 2; ++k) {
        position_[k] = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "sph.position." + std::to_string(k));
        velocity_[k] = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "sph.velocity." + std::to_string(k));
    }
    position_[0].upload(x.data(), x.size() * sizeof(glm::vec4));
    velocity_[0].upload(v.data(), v.size() * sizeof(glm::vec4));
    density_ = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "sph.density");
    accel_ = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "sph.accel");
    pair_terms_ = gl::Buffer(n * sizeof(glm::vec2), GL_DYNAMIC_COPY, nullptr, "sph.pair_terms");
    runs_ = runs_of(scene);
    if (scene.sph.neighbour_masks)   // (start, mask) per run and particle
        neighbours_ = gl::Buffer(n * 2 * std::size_t(runs_) * sizeof(std::uint32_t), GL_DYNAMIC_COPY, nullptr,
                                 "sph.neighbour_masks");
    ranges_ = grid_.make_ranges("sph.cells");
    boundary_ranges_ = grid_.make_ranges("sph.boundary_cells");

    gpu::StepState s{};
    float v0 = 0.0f;
    for (const glm::vec4& u : v) v0 = std::max(v0, glm::length(glm::vec3(u)));
    s.max_speed = bits(v0);
    s.max_accel = bits(glm::length(scene.gravity));
    s.frame_min_dt = frame_dt_;
    s.nan_index = s.escaped_index = 0xFFFFFFFFu;
    step_ = gl::Buffer(sizeof s, GL_DYNAMIC_COPY, &s, "sph.step");
    dt_estimate_ = std::min(params_.cfl * params_.spacing / (params_.sound_speed + scene.speed_estimate()), frame_dt_);

    // Boundary: sort by cell once, then psi_b from the sorted set (start-up, not the frame path).
    const std::size_t m = std::max<std::size_t>(boundary_count_, 1);
    gl::Buffer raw = gl::Buffer::from<glm::vec4>(wall, GL_STATIC_DRAW, "sph.boundary.raw");
    gl::Buffer zeros(m * sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "sph.boundary.zeros");
    gl::Buffer zeros_sorted(m * sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "sph.boundary.zeros_sorted");
    boundary_ = gl::Buffer(m * sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "sph.boundary");
    gl::Buffer weighted(m * sizeof(glm::vec4), GL_STATIC_DRAW, nullptr, "sph.boundary.weighted");
    timer_.begin_frame();
    if (boundary_count_ > 0) {
        grid_.build(raw, zeros, boundary_, zeros_sorted, boundary_ranges_, boundary_count_, /*clear=*/true);
        auto pass = timer_.scope(boundary_pass_);
        params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
        boundary_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY);
        boundary_ranges_.start.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_START);
        boundary_ranges_.end.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_END);
        weighted.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_SCRATCH);
        boundary_volume_.dispatch(boundary_count_);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        glBindBuffer(GL_COPY_READ_BUFFER, weighted.id());
        glBindBuffer(GL_COPY_WRITE_BUFFER, boundary_.id());
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(boundary_count_ * sizeof(glm::vec4)));
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    }
    {
        // Which cells have boundary particles around them (start-up; the boundary is static).
        const GridLayout& g = grid_.layout();
        boundary_near_ = gl::Buffer(std::size_t(g.key_count) * sizeof(std::uint32_t), GL_STATIC_DRAW, nullptr, "sph.boundary_near");
        const GLuint zero = 0;
        glBindBuffer(GL_COPY_WRITE_BUFFER, boundary_near_.id());
        glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);   // Morton keys between cells
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        auto pass = timer_.scope(boundary_cells_pass_);
        params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
        grid_.bind_params(boundary_count_);
        boundary_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY);
        boundary_ranges_.start.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_START);
        boundary_ranges_.end.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_END);
        boundary_near_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_NEAR);
        if (boundary_count_ > 0) flag_boundary_.dispatch(std::size_t(g.dims.x) * g.dims.y * g.dims.z);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    timer_.end_frame();
    timer_.drain();
    timer_.reset_samples();
    if (scene.turbulence.enabled()) {
        turbulence_ = std::make_unique<turbulence::TurbulenceForce>(shaders, timer_, scene.turbulence, params_.h, count_,
                                                                    neighbours_.id() ? runs_ : 0);
        const std::vector<gpu::NoiseSeed> unseeded(n, turbulence::unseeded_noise());
        for (int k = 0; k < 2; ++k)
            seed_[k] = gl::Buffer::from<gpu::NoiseSeed>(unseeded, GL_DYNAMIC_COPY, "sph.noise_seed." + std::to_string(k));
    }
}

Sph::~Sph() = default;

void Sph::set_fixed_dt(float dt) { fixed_dt_ = dt; }

// Tests: the next rebuild_grid() sorts these into cell order.
void Sph::upload_state(const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v) {
    if (x.size() != count_ || v.size() != count_) throw Error("Sph::upload_state: expected " + std::to_string(count_) + " particles");
    position_[current_].upload(x.data(), x.size() * sizeof(glm::vec4));
    velocity_[current_].upload(v.data(), v.size() * sizeof(glm::vec4));
    masks_current_ = false;
}

void Sph::begin_frame(std::uint64_t frame_index) {
    readback_.poll();
    // Enough substeps to cover the frame, and what the last seen frame left over, at the smallest
    // stable dt seen so far (records are frames late; the 0.9 absorbs growth in between).
    float need = frame_dt_, dt = dt_estimate_;
    if (last_) {
        dt = std::min(dt_estimate_, last_->frame_min_dt);
        need += std::max(last_->frame_left, 0.0f);
    }
    substeps_ = fixed_dt_ ? std::max(1, int(std::lround(frame_dt_ / *fixed_dt_)))
                          : std::clamp(int(std::ceil(need / (0.9f * std::max(dt, 1e-9f)))), 1, max_substeps_);
    auto pass = timer_.scope(begin_pass_);
    step_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_STEP);
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    glProgramUniform1ui(begin_.id(), RANRYU_LOC_COUNT, GLuint(substeps_));
    glProgramUniform1ui(begin_.id(), RANRYU_LOC_AUX, GLuint(frame_index));
    glProgramUniform1f(begin_.id(), RANRYU_LOC_SHIFT, fixed_dt_ ? *fixed_dt_ * float(substeps_) : frame_dt_);
    begin_.dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Sph::bind_fields() {
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    grid_.bind_params(count_);
    position_[current_].bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_POSITION);
    velocity_[current_].bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_VELOCITY);
    density_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_DENSITY);
    accel_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_ACCEL);
    step_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_STEP);
    ranges_.start.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_CELL_START);
    grid_.sort().sorted_keys().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_SORT_KEYS);   // validates ranges
    ranges_.end.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_CELL_END);
    boundary_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY);
    boundary_ranges_.start.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_START);
    boundary_ranges_.end.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_CELL_END);
    if (neighbours_.id()) neighbours_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_NEIGHBOURS);
    boundary_near_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_BOUNDARY_NEAR);
    pair_terms_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_PAIR_TERMS);
}

void Sph::substep() {
    choose_time_step();
    rebuild_grid();
    compute_density();
    analyse_turbulence();
    compute_forces();
    apply_turbulence();
    integrate();
}

void Sph::analyse_turbulence() {
    if (turbulence_) turbulence_->analyse(*this);
}

void Sph::apply_turbulence() {
    if (!turbulence_) return;
    bind_fields();   // positions, accelerations, StepState, SphParams; the pass binds the rest
    turbulence_->apply(*this);
}

void Sph::choose_time_step() {
    auto pass = timer_.scope(step_pass_);
    step_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_STEP);
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    choose_.dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Sph::rebuild_grid() {
    masks_current_ = false;
    const int next = 1 - current_;
    grid_.build(position_[current_], velocity_[current_], position_[next], velocity_[next], ranges_, count_, /*clear=*/false,
                turbulence_ ? &seed_[current_] : nullptr, turbulence_ ? &seed_[next] : nullptr);
    current_ = next;
}

void Sph::compute_density() {
    auto pass = timer_.scope(density_pass_);
    bind_fields();
    density_prog_.dispatch(count_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    masks_current_ = neighbours_.id() != 0;
}

void Sph::compute_forces() {
    auto pass = timer_.scope(forces_pass_);
    bind_fields();
    forces_.dispatch(count_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Sph::integrate() {
    masks_current_ = false;
    auto pass = timer_.scope(integrate_pass_);
    bind_fields();
    obstacles_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_OBSTACLES);
    integrate_.dispatch(count_);
    // The next substep's hash, the time step and the impostor draw read what this wrote.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void Sph::end_frame() {
    auto pass = timer_.scope(diag_pass_);
    readback_.copy(step_, 0, 0);
}

void Sph::on_record(std::uint64_t, const void* bytes) {
    gpu::StepState r;
    std::memcpy(&r, bytes, sizeof r);
    last_ = r;
    if (sink_) sink_(r);
    if (!instability_)
        if (auto finding = check(r, limits_)) instability_ = finding;
}

}  // namespace ranryu::sim
