#include "sim/fluid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "sim/boundary.h"

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
// (glsl/sim/fluid/fluid.glsl). RANRYU_NO_MERGE_ROWS=1 forces per-cell loops, for comparison.
bool merge_rows(const scene::Scene& s) {
    const char* off = std::getenv("RANRYU_NO_MERGE_ROWS");
    return !s.sph.morton && !(off && std::string(off) == "1");
}

}  // namespace

int Fluid::neighbour_runs(const scene::Scene& s) { return merge_rows(s) ? 9 : 27; }

namespace {

int layers_of(const scene::Scene& s) { return boundary_layers(s.spacing, kernel_support(s.spacing)); }
std::vector<glm::vec4> boundary_of(const scene::Scene& s) { return sample_boundary(s, layers_of(s)); }

// One vec4 a particle (at least one), the size of every state array.
std::size_t vec4_array_bytes(std::size_t count) { return std::max<std::size_t>(count, 1) * sizeof(glm::vec4); }
// (start, mask) per neighbour run and particle: the fluid's, and with `boundary` the boundary's.
std::size_t pair_bytes(const scene::Scene& s, std::size_t count, bool boundary) {
    return std::max<std::size_t>(count, 1) * (boundary ? 4 : 2) * std::size_t(Fluid::neighbour_runs(s)) * sizeof(std::uint32_t);
}
// PBF's corrections move the particles between its walks: its boundary masks hold the boundary
// particles within h plus a skin, read while a particle stays within the skin (glsl/sim/pbf/pbf.glsl).
bool boundary_skin(const scene::Scene& s, std::size_t count) {
    return Fluid::boundary_masks(s, count) && s.sph.solver == scene::Solver::pbf;
}
std::size_t mask_bytes(const scene::Scene& s, std::size_t count) { return pair_bytes(s, count, Fluid::boundary_masks(s, count)); }
// One sort serves the fluid every substep and the boundary once at start.
std::size_t sort_capacity(std::size_t count, std::size_t boundary) { return std::max({count, boundary, std::size_t(1)}); }

}  // namespace

std::size_t Fluid::boundary_count(const scene::Scene& s) { return sim::boundary_count(s, layers_of(s)); }

std::size_t Fluid::storage_block_bytes() {
    GLint64 block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
    const std::size_t words = std::size_t(0xFFFFFFFFull) * sizeof(std::uint32_t);
    return block > 0 ? std::min(std::size_t(block), words) : words;
}

void Fluid::require_one_block(const scene::Scene& s, const std::string& what, std::size_t bytes, const std::string& off) {
    if (bytes <= storage_block_bytes()) return;
    throw InputError("scene " + s.name + " (" + s.origin + "): " + what + " take " + std::to_string(bytes) +
                     " bytes, more than one storage block holds here (" + std::to_string(storage_block_bytes()) +
                     " bytes); set \"sph\": {\"" + off + "\": false} or use fewer particles");
}

bool Fluid::boundary_masks(const scene::Scene& s, std::size_t count) {
    return s.sph.neighbour_masks && pair_bytes(s, count, true) <= Fluid::storage_block_bytes();
}

std::size_t Fluid::carried_bytes(std::size_t count, std::uint32_t words) {
    return 2 * std::max<std::size_t>(count, 1) * words * sizeof(std::uint32_t);
}

// raw, zeros, zeros_sorted, weighted: start-up's, kept for the run with a paddle (bytes_for counts them then).
std::size_t Fluid::transient_bytes(std::size_t boundary) { return 4 * vec4_array_bytes(boundary); }

std::size_t Fluid::step_bytes(std::size_t count) {
    const std::size_t spans = (count + RANRYU_EXTREME_SPAN - 1) / RANRYU_EXTREME_SPAN;
    return sizeof(gpu::StepState) + 2 * spans * sizeof(gpu::FrameExtreme);
}

std::size_t Fluid::bytes_for(const scene::Scene& s, std::size_t count, std::size_t boundary) {
    const GridLayout g = fluid_grid(s, kernel_support(s.spacing), layers_of(s));
    std::size_t b = 6 * vec4_array_bytes(count)                      // position, velocity (two each), density, accel
                    + (s.sph.neighbour_masks ? mask_bytes(s, count) : 0)
                    + vec4_array_bytes(boundary)                     // boundary
                    + std::size_t(g.key_count) * sizeof(std::uint32_t)   // boundary_near
                    + 2 * NeighbourGrid::ranges_bytes(g)             // fluid and boundary cell ranges
                    + NeighbourGrid::bytes_for(sort_capacity(count, boundary));
    b += sizeof(gpu::SphParams) + step_bytes(count) + obstacle_shapes(s).size() * sizeof(glm::vec4);
    if (s.paddle_radius > 0.0f) b += transient_bytes(boundary);
    if (s.particle_budget > 0) b += sizeof(std::uint32_t);   // the emitter's slot counter
    return b;
}

gpu::SphParams sph_params(const scene::Scene& s, std::size_t count, std::size_t boundary) {
    gpu::SphParams p{};
    const float dx = s.spacing, h = kernel_support(dx), rho0 = s.sph.rest_density, c = s.sound_speed();
    p.gravity = glm::vec4(s.gravity, 0.0f);
    // The guard's domain: the tank, a spacing of slack at the walls and floor, and at the lid of a
    // closed tank (domain_max.w = 1). Above an open top it reaches as high as a particle at the guard's
    // speed bound could fly: a splash that comes back down has not left, and one faster than that
    // breaks the speed criterion first.
    const float g = std::max(glm::length(s.gravity), 1e-3f), v = guard_limits(s).speed;
    p.domain_min = glm::vec4(s.tank_min - dx, 0.0f);
    p.domain_max = glm::vec4(s.tank_max.x + dx, s.tank_closed ? s.tank_max.y + dx : s.tank_max.y + v * v / (2.0f * g),
                             s.tank_max.z + dx, s.tank_closed ? 1.0f : 0.0f);
    p.h = h;
    // Eq. (1)'s constants, which the walks read instead of deriving them from h a pair (bindings.h)
    p.inv_h = 1.0f / h;
    p.w_scale = float(8.0 / std::numbers::pi) * p.inv_h * p.inv_h * p.inv_h;
    p.grad_scale = float(48.0 / std::numbers::pi) * p.inv_h * p.inv_h * p.inv_h * p.inv_h;
    p.mass = rho0 * dx * dx * dx;
    p.rest_density = rho0;
    p.stiffness = rho0 * c * c / 7.0f;
    p.viscosity = s.sph.viscosity;
    p.sound_speed = c;
    p.spacing = dx;
    p.cfl = s.sph.courant();   // (D8) DFSPH's own where the scene sets it, else eq. (7)'s
    p.force_factor = s.sph.force_factor;
    p.dt_max = std::min(s.sph.max_time_step, s.frame_dt);
    if (s.sph.solver == scene::Solver::pbf) {   // docs/PBF.md (P1): the fixed step, no CFL or force condition
        p.cfl = p.force_factor = 0.0f;
        p.dt_max = s.frame_dt / float(s.sph.pbf.substeps);
    }
    p.dt_floor = guard_limits(s).dt_floor;
    p.density_limit = s.sph.density_limit;
    p.speed_limit = guard_limits(s).speed;
    p.particle_count = std::uint32_t(count);
    p.boundary_count = std::uint32_t(boundary);
    p.artificial_viscosity = s.sph.solver == scene::Solver::wcsph ? s.sph.artificial_viscosity : 0.0f;
    p.front_band = 3.0f * dx;   // from domain_min.y = floor - dx: particles within 2 dx of the floor
    return p;
}

EmitterShape emitter_for(const scene::Scene& s) {
    EmitterShape e;
    const glm::vec3 c = 0.5f * (s.tank_min + s.tank_max), extent = s.tank_max - s.tank_min;
    float y = s.tank_min.y + 0.85f * extent.y;
    if (s.tank_closed) y = std::min(y, s.tank_max.y - 2.0f * s.spacing);
    e.nozzle = glm::vec3(c.x, y, c.z);
    e.side = std::clamp(int(std::lround(0.15f * std::min(extent.x, extent.z) / s.spacing)), 2, 16);
    e.velocity = glm::vec3(0.0f, -s.spacing / s.frame_dt, 0.0f);
    return e;
}

std::vector<glm::vec4> parked_positions(const scene::Scene& s, std::size_t count) {
    // A lattice of pitch 3 h over the tank's footprint, layer under layer downwards from 1 m and 3 h
    // below the floor's boundary layers (the neighbour grid clamps them into its bottom cells, which
    // no fluid particle's walk reaches, and the walks skip parked particles).
    const float pitch = 6.0f * s.spacing;
    const glm::vec3 e = s.tank_max - s.tank_min;
    const std::size_t nx = std::max<std::size_t>(1, std::size_t(e.x / pitch)), nz = std::max<std::size_t>(1, std::size_t(e.z / pitch));
    const float top = s.tank_min.y - 1.0f - float(layers_of(s) + 6) * s.spacing;
    std::vector<glm::vec4> out;
    out.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t i = k % nx, j = (k / nx) % nz, layer = k / (nx * nz);
        out.emplace_back(s.tank_min.x + (float(i) + 0.5f) * pitch, top - float(layer) * pitch, s.tank_min.z + (float(j) + 0.5f) * pitch, -1.0f);
    }
    return out;
}

GuardLimits guard_limits(const scene::Scene& s) {
    GuardLimits g;
    g.density_ratio = s.sph.density_limit;
    g.speed = s.sph.speed_limit > 0.0f ? s.sph.speed_limit : 5.0f * s.speed_estimate();
    // A stable dt a hundred times below the CFL step at the expected speed means the run has blown up.
    g.dt_floor = 0.01f * s.sph.courant() * s.spacing / (s.sound_speed() + s.speed_estimate());
    return g;
}

Fluid::Fluid(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene)
    : timer_(timer),
      begin_pass_(timer.pass("begin-frame")),
      step_pass_(timer.pass("choose-time-step")),
      integrate_pass_(timer.pass("integrate")),
      extremes_pass_(timer.pass("record-extremes")),
      diag_pass_(timer.pass("diagnostics")),
      boundary_pass_(timer.pass("boundary-volume")),
      boundary_cells_pass_(timer.pass("boundary-cells")),
      emit_pass_(timer.pass("emit")),
      defines_(std::string(merge_rows(scene) ? "#define RANRYU_MERGE_ROWS 1\n" : "") +
               (scene.sph.neighbour_masks ? "#define RANRYU_NEIGHBOUR_MASKS 1\n" : "") +
               (boundary_masks(scene, scene.particle_capacity()) ? "#define RANRYU_BOUNDARY_MASKS 1\n" : "") +
               (boundary_skin(scene, scene.particle_capacity()) ? "#define RANRYU_BOUNDARY_SKIN 1\n" : "")),
      begin_(shader::Program::compute(shaders, "sim/fluid/begin_frame.comp")),
      choose_(shader::Program::compute(shaders, "sim/fluid/choose_time_step.comp")),
      integrate_(shader::Program::compute(shaders, "sim/fluid/integrate_particles.comp")),
      record_extremes_(shader::Program::compute(shaders, "sim/fluid/record_extremes.comp")),
      boundary_volume_(shader::Program::compute(shaders, "sim/boundary/compute_boundary_volume.comp", defines_)),
      flag_boundary_(shader::Program::compute(shaders, "sim/boundary/flag_boundary_cells.comp", defines_)),
      emit_(scene.particle_budget > 0 ? shader::Program::compute(shaders, "sim/fluid/emit_particles.comp") : shader::Program()),
      emitter_(emitter_for(scene)),
      guard_(guard_limits(scene)),
      frame_dt_(scene.frame_dt),
      max_substeps_(scene.sph.max_substeps),
      grid_(shaders, timer,
            fluid_grid(scene, kernel_support(scene.spacing), layers_of(scene)),
            sort_capacity(scene.particle_capacity(), boundary_count(scene)),
            scene.sph.sort == "bitonic" ? SortMethod::bitonic : SortMethod::radix),
      runs_(neighbour_runs(scene)),
      readback_(sizeof(gpu::StepState), record_depth(scene), "StepState.readback",
                [this](std::uint64_t opened, const void* bytes) { on_record(opened, bytes); }),
      plan_lag_(record_depth(scene) + 1) {
    std::vector<glm::vec4> x = scene.initial_positions(), v = scene.initial_velocities();
    scene_count_ = x.size();
    if (scene.particle_budget > x.size()) {   // the emitter's parked particles, at rest
        const std::vector<glm::vec4> parked = parked_positions(scene, scene.particle_budget - x.size());
        x.insert(x.end(), parked.begin(), parked.end());
        v.resize(x.size(), glm::vec4(0.0f));
    }
    if (scene.particle_budget > 0) emit_claimed_ = gl::Buffer(sizeof(std::uint32_t), GL_DYNAMIC_COPY, nullptr, "fluid.emit_claimed");
    const std::vector<glm::vec4> wall = boundary_of(scene);
    paddle_offsets_ = paddle_offsets(scene, layers_of(scene));
    paddle_placed_.resize(paddle_offsets_.size());
    paddle_first_ = wall.size() - paddle_offsets_.size();
    paddle_radius_ = scene.paddle_radius;
    paddle_park_ = paddle_at_ = paddle_park(scene);
    count_ = x.size();
    boundary_count_ = wall.size();
    params_ = sph_params(scene, count_, boundary_count_);
    params_ubo_ = gl::Buffer(sizeof(gpu::SphParams), GL_DYNAMIC_DRAW, &params_, "SphParams");
    obstacles_ = gl::Buffer::from<glm::vec4>(obstacle_shapes(scene), scene.paddle_radius > 0.0f ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW,
                                             "fluid.obstacles");

    const std::size_t bytes = vec4_array_bytes(count_);
    for (int k = 0; k < 2; ++k) {
        position_[k] = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "fluid.position." + std::to_string(k));
        velocity_[k] = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "fluid.velocity." + std::to_string(k));
    }
    position_[0].upload(x.data(), x.size() * sizeof(glm::vec4));
    velocity_[0].upload(v.data(), v.size() * sizeof(glm::vec4));
    density_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "fluid.density");
    accel_ = gl::Buffer(bytes, GL_DYNAMIC_COPY, nullptr, "fluid.accel");
    if (scene.sph.neighbour_masks) {
        // One storage block: the boundary's masks only where both fit (boundary_masks()), the fluid's
        // or none.
        const std::size_t mask = mask_bytes(scene, count_);
        require_one_block(scene, "the neighbour masks of " + std::to_string(count_) + " particles", mask, "neighbour_masks");
        neighbours_ = gl::Buffer(mask, GL_DYNAMIC_COPY, nullptr, "fluid.neighbour_masks");
    }
    ranges_ = grid_.make_ranges("fluid.cells");
    boundary_ranges_ = grid_.make_ranges("fluid.boundary_cells");

    gpu::StepState s{};
    float v0 = 0.0f;
    for (const glm::vec4& u : v) v0 = std::max(v0, glm::length(glm::vec3(u)));
    s.max_speed = bits(v0);
    s.max_accel = bits(glm::length(scene.gravity));
    s.frame_min_dt = frame_dt_;
    s.iteration_dt = params_.dt_max;   // DFSPH's (D8) lowers it from its solves' iterations
    s.nan_index = s.escaped_index = 0xFFFFFFFFu;
    s.live_count = std::uint32_t(scene_count_);
    // The record, then the FrameExtreme entries (zero: none kept yet).
    std::vector<char> initial(step_bytes(count_), 0);
    std::memcpy(initial.data(), &s, sizeof s);
    step_ = gl::Buffer(initial.size(), GL_DYNAMIC_COPY, initial.data(), "fluid.step");
    dt_estimate_ = std::min(params_.cfl * params_.spacing / (params_.sound_speed + scene.speed_estimate()), params_.dt_max);
    compute_boundary(wall);
}

// Start-up: the boundary sorted by cell, psi_b from the sorted set, and the cells that have boundary
// particles around them. The boundary is static but for the paddle (move_paddle() sorts it again).
void Fluid::compute_boundary(const std::vector<glm::vec4>& wall) {
    const std::size_t m = vec4_array_bytes(boundary_count_);   // transient_bytes(): raw, zeros, zeros_sorted, weighted
    raw_ = gl::Buffer(m, has_paddle() ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW, nullptr, "fluid.boundary.raw");
    if (!wall.empty()) raw_.upload(wall.data(), wall.size() * sizeof(glm::vec4));
    zeros_ = gl::Buffer(m, GL_STATIC_DRAW, nullptr, "fluid.boundary.zeros");
    zeros_sorted_ = gl::Buffer(m, GL_STATIC_DRAW, nullptr, "fluid.boundary.zeros_sorted");
    boundary_ = gl::Buffer(m, GL_STATIC_DRAW, nullptr, "fluid.boundary");
    weighted_ = gl::Buffer(m, GL_STATIC_DRAW, nullptr, "fluid.boundary.weighted");
    const GridLayout& g = grid_.layout();
    boundary_near_ = gl::Buffer(std::size_t(g.key_count) * sizeof(std::uint32_t), GL_STATIC_DRAW, nullptr, "fluid.boundary_near");
    timer_.begin_frame();
    rebuild_boundary();
    timer_.end_frame();
    timer_.drain();
    timer_.reset_samples();
    if (!has_paddle()) raw_ = gl::Buffer(), zeros_ = gl::Buffer(), zeros_sorted_ = gl::Buffer(), weighted_ = gl::Buffer();
}

void Fluid::rebuild_boundary() {
    const GridLayout& g = grid_.layout();
    const GLuint zero = 0;
    glBindBuffer(GL_COPY_WRITE_BUFFER, boundary_near_.id());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);   // Morton keys between cells
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const shader::StorageSet buffers = bind_state().with("Weighted", weighted_);
    if (boundary_count_ > 0) {
        grid_.build(raw_, zeros_, boundary_, zeros_sorted_, boundary_ranges_, boundary_count_, /*clear=*/true);
        auto pass = timer_.scope(boundary_pass_);
        params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
        boundary_volume_.bind(buffers).dispatch(boundary_count_);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        glBindBuffer(GL_COPY_READ_BUFFER, weighted_.id());
        glBindBuffer(GL_COPY_WRITE_BUFFER, boundary_.id());
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(boundary_count_ * sizeof(glm::vec4)));
        glBindBuffer(GL_COPY_READ_BUFFER, 0);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(boundary_cells_pass_);
        params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
        grid_.bind_params(boundary_count_);
        if (boundary_count_ > 0) flag_boundary_.bind(buffers).dispatch(std::size_t(g.dims.x) * g.dims.y * g.dims.z);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void Fluid::move_paddle(glm::vec3 center, glm::vec3 velocity, bool on, float scale) {
    if (!has_paddle()) throw Error("Fluid::move_paddle: the scene has no paddle (scene.paddle_radius is 0)");
    const glm::vec3 at = on ? center : paddle_park_;
    // Its entry is the last of obstacle_shapes(): (center, 2), (radius, velocity); radius 0 when parked.
    if (!on) scale = 1.0f;
    const glm::vec4 entry[2] = {glm::vec4(at, 2.0f), on ? glm::vec4(scale * paddle_radius_, velocity) : glm::vec4(0.0f)};
    obstacles_.upload(entry, sizeof entry, obstacles_.size() - sizeof entry);
    if (at == paddle_at_ && scale == paddle_scale_) return;   // only its velocity changed: the boundary stands
    ++boundary_generation_;
    paddle_at_ = at, paddle_scale_ = scale;
    for (std::size_t k = 0; k < paddle_offsets_.size(); ++k)
        paddle_placed_[k] = glm::vec4(at + scale * glm::vec3(paddle_offsets_[k]), scale * scale * scale * paddle_offsets_[k].w);
    raw_.upload(paddle_placed_.data(), paddle_placed_.size() * sizeof(glm::vec4), paddle_first_ * sizeof(glm::vec4));
    rebuild_boundary();
}

int Fluid::carry(std::string block, std::uint32_t words, const std::vector<std::uint32_t>& fill) {
    if (carried_.size() == NeighbourGrid::max_carried)
        throw Error("Fluid::carry: at most " + std::to_string(NeighbourGrid::max_carried) + " carried arrays (adding " + block + ")");
    const std::size_t n = std::max<std::size_t>(count_, 1);   // as carried_bytes()
    // Every particle's: the scene's, in its initial order (parked ones, after them, start at zero).
    if (words == 0 || (fill.size() != words && fill.size() != count_ * words && fill.size() != scene_count_ * words))
        throw Error("Fluid::carry: " + block + " needs a fill of one particle's words or of every particle's");
    std::vector<std::uint32_t> all(n * words);
    if ((fill.size() == count_ * words || fill.size() == scene_count_ * words) && count_ > 0)
        std::copy(fill.begin(), fill.end(), all.begin());
    else for (std::size_t i = 0; i < n; ++i) std::copy(fill.begin(), fill.begin() + words, all.begin() + std::ptrdiff_t(i * words));
    Carried c{std::move(block), words, {}};
    for (int k = 0; k < 2; ++k)
        c.buffer[k] = gl::Buffer::from<std::uint32_t>(all, GL_DYNAMIC_COPY, "fluid.carried." + c.block + "." + std::to_string(k));
    carried_.push_back(std::move(c));
    return int(carried_.size() - 1);
}

// Tests: the next rebuild_grid() sorts these into cell order.
void Fluid::upload_state(const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v) {
    if (x.size() != count_ || v.size() != count_) throw Error("Fluid::upload_state: expected " + std::to_string(count_) + " particles");
    position_[current_].upload(x.data(), x.size() * sizeof(glm::vec4));
    velocity_[current_].upload(v.data(), v.size() * sizeof(glm::vec4));
    masks_current_ = false;
}

void Fluid::stop_particles() {
    const glm::vec4 zero(0.0f);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // after the shaders that wrote them
    glBindBuffer(GL_COPY_WRITE_BUFFER, velocity_[current_].id());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, &zero);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

std::string Fluid::neighbour_defines() const { return defines_; }

shader::StorageSet Fluid::bind_state() {
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    grid_.bind_params(count_);
    shader::StorageSet set{{"Positions", &position_[current_]},
                           {"Velocities", &velocity_[current_]},
                           {"Density", &density_},
                           {"Accelerations", &accel_},
                           {"Step", &step_},
                           {"CellRange", &ranges_.cells},
                           {"SortedKeys", &grid_.sort().sorted_keys()},   // validates ranges
                           {"Boundary", &boundary_},
                           {"BoundaryCellRange", &boundary_ranges_.cells},
                           {"BoundaryNear", &boundary_near_},
                           {"Obstacles", &obstacles_},
                           {"NeighbourMasks", &neighbours_}};
    for (const Carried& c : carried_) set.add(c.block, c.buffer[carried_current_]);
    return set;
}

int Fluid::record_depth(const scene::Scene& scene) { return scene.sph.solver == scene::Solver::pbf ? 4 : 1; }

bool Fluid::has_records_of_last_frames() const {
    for (std::uint64_t k = 1; k <= std::min<std::uint64_t>(opened_, std::uint64_t(plan_lag_)); ++k)
        if (history_opened_[std::size_t((opened_ - k) % most_plan_lag)] != opened_ - k) return false;
    return true;
}

void Fluid::begin_frame(std::uint64_t frame_index) {
    if (open_) throw Error("Fluid::begin_frame: the frame before was not ended (end_frame)");
    open_ = true;
    readback_.poll();
    const std::uint64_t n = opened_++;
    plan_.reset();
    if (n >= std::uint64_t(plan_lag_)) {
        const std::uint64_t from = n - std::uint64_t(plan_lag_);
        const std::size_t slot = std::size_t(from % most_plan_lag);
        // Always there (planning_record()): the ring's back-pressure handed it over.
        if (history_opened_[slot] != from)
            throw Error("Fluid::begin_frame: the record of the fluid's frame " + std::to_string(from) + " (of those it simulated) is not back at its frame " +
                        std::to_string(n));
        plan_ = history_[slot];
    }
    // Enough substeps to cover the frame, and what the planning record's frame left over, at its
    // smallest stable dt (the 0.9 absorbs growth since), or at the scene's estimate for the first
    // plan_lag() frames.
    float need = frame_dt_, dt = dt_estimate_;
    if (plan_ && plan_->frame_substeps > 0) {
        dt = plan_->frame_min_dt;
        need += std::max(plan_->frame_left, 0.0f);
    }
    substeps_ = fixed_dt_ ? std::max(1, int(std::lround(frame_dt_ / *fixed_dt_)))
                          : std::clamp(int(std::ceil(need / (0.9f * std::max(dt, 1e-9f)))), 1, max_substeps_);
    auto pass = timer_.scope(begin_pass_);
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    glProgramUniform1ui(begin_.id(), RANRYU_LOC_COUNT, GLuint(substeps_));
    glProgramUniform1ui(begin_.id(), RANRYU_LOC_AUX, GLuint(frame_index));
    glProgramUniform1f(begin_.id(), RANRYU_LOC_SHIFT, fixed_dt_ ? *fixed_dt_ * float(substeps_) : frame_dt_);
    begin_.bind(bind_state()).dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Fluid::choose_time_step() {
    auto pass = timer_.scope(step_pass_);
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    choose_.bind(bind_state()).dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Fluid::rebuild_grid() {
    masks_current_ = false;
    const int next = 1 - current_;
    CarriedArray moved[NeighbourGrid::max_carried];
    for (std::size_t a = 0; a < carried_.size(); ++a)
        moved[a] = CarriedArray{&carried_[a].buffer[carried_current_], &carried_[a].buffer[1 - carried_current_], carried_[a].words};
    grid_.build(position_[current_], velocity_[current_], position_[next], velocity_[next], ranges_, count_, /*clear=*/false,
                std::span<const CarriedArray>(moved, carried_.size()));
    current_ = next;
    carried_current_ = 1 - carried_current_;
}

void Fluid::integrate() {
    masks_current_ = false;
    auto pass = timer_.scope(integrate_pass_);
    integrate_.bind(bind_state()).dispatch(count_);
    // The next substep's hash, the time step and the impostor draw read what this wrote.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void Fluid::emit() {
    if (!has_budget()) throw Error("Fluid::emit: no particle budget beyond the scene's (scene.particle_budget)");
    auto pass = timer_.scope(emit_pass_);
    const GLuint zero = 0;
    glBindBuffer(GL_COPY_WRITE_BUFFER, emit_claimed_.id());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glProgramUniform4f(emit_.id(), RANRYU_LOC_EMIT_NOZZLE, emitter_.nozzle.x, emitter_.nozzle.y, emitter_.nozzle.z, float(emitter_.side));
    glProgramUniform4f(emit_.id(), RANRYU_LOC_EMIT_VELOCITY, emitter_.velocity.x, emitter_.velocity.y, emitter_.velocity.z,
                       params_.spacing);
    emit_.bind(bind_state().with("Emitter", emit_claimed_)).dispatch(count_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void Fluid::set_viscosity_and_cfl(float viscosity, float cfl) {
    if (params_.cfl == 0.0f) cfl = 0.0f;   // a fixed step (PBF, docs/PBF.md (P1)) stays fixed
    if (params_.viscosity == viscosity && params_.cfl == cfl) return;
    params_.viscosity = viscosity;
    params_.cfl = cfl;
    params_ubo_.upload_value(params_);
}

void Fluid::end_frame() {
    if (!open_) throw Error("Fluid::end_frame: no frame is open (begin_frame)");
    open_ = false;
    {
        auto pass = timer_.scope(extremes_pass_);
        params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
        record_extremes_.bind(bind_state()).dispatch(1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);   // the copy below reads it
    }
    auto pass = timer_.scope(diag_pass_);
    readback_.copy(step_, 0, opened_ - 1);
}

void Fluid::on_record(std::uint64_t opened, const void* bytes) {
    gpu::StepState r;
    std::memcpy(&r, bytes, sizeof r);
    last_ = r;
    history_[std::size_t(opened % most_plan_lag)] = r;
    history_opened_[std::size_t(opened % most_plan_lag)] = opened;
    if (sink_) sink_(r);
    if (!instability_)
        if (auto finding = guard_.observe(r)) instability_ = finding;
}

void Fluid::persist(StateIo& io) {
    if (boundary_generation_ != 0) io.refuse("the paddle has moved the boundary, and a run with the paddle cannot be saved");
    io.buffer("fluid.positions", position_[current_], count());
    io.buffer("fluid.velocities", velocity_[current_], count());
    io.buffer("fluid.densities", density_);
    io.buffer("fluid.accelerations", accel_);
    // The record only: the FrameExtreme entries after it are zero between frames (record_extremes.comp).
    gpu::StepState record{};
    if (!io.loading()) step_.read_bytes(&record, sizeof record);
    io.value("fluid.step", record);
    if (io.loading()) step_.upload_value(record);
    for (Carried& c : carried_) io.buffer("fluid.carried." + c.block, c.buffer[carried_current_]);
    if (emit_claimed_) io.buffer("fluid.emit_claimed", emit_claimed_);
    bool has_last = last_.has_value();
    gpu::StepState last = last_.value_or(gpu::StepState{});
    io.value("fluid.has_last_record", has_last);
    io.value("fluid.last_record", last);
    last_ = has_last ? std::optional<gpu::StepState>(last) : std::nullopt;
    // The records the next plan_lag() frames are planned from, so that a resumed run plans its frames
    // as the unstopped run did: all of them back (the run has drained them), and whole in a file read.
    if (!io.loading() && (open_ || !has_records_of_last_frames()))
        throw Error("Fluid::persist: a frame is open or its records are not back (drain them first)");
    io.value("fluid.frames_opened", opened_);
    io.value("fluid.planning_records", history_);
    io.value("fluid.planning_records_opened", history_opened_);
    if (io.loading() && !has_records_of_last_frames())
        io.refuse("its planning records do not cover the frames before its last (a damaged file)");
    io.value("fluid.dt_estimate", dt_estimate_);
}

}  // namespace ranryu::sim
