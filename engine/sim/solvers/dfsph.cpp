#include "sim/solvers/dfsph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/state_io.h"

namespace ranryu::sim {
namespace {

constexpr std::uint32_t kWarmWords = 2;   // the carried warm start: two words a particle
constexpr std::uint32_t kFramePressureWords = 2;   // the carried (sum p dt, sum dt) of the frame's steps
constexpr std::size_t kCorrectionBytes = 2 * sizeof(glm::vec4);   // (D11)'s L_i, glsl/sim/dfsph/dfsph.glsl
constexpr std::size_t kKappaFloats = 4;   // the Kappa block's (x_i, kappa_i) a particle, glsl/sim/dfsph/dfsph.glsl
// The rows' (kappa_b, kappa_v,b) after the fluid's, padded to whole vec4s (Dfsph::kappa_floats()).
std::size_t kappa_row_floats(std::size_t rows) { return (2 * rows + kKappaFloats - 1) / kKappaFloats * kKappaFloats; }
// The rows' first float: after count() particles' (x_i, kappa_i), one particle's when there is none (as the
// other per-particle arrays).
std::size_t kappa_rows_at(std::size_t count) { return kKappaFloats * std::max<std::size_t>(count, 1); }
// After a residual pass, which may have set the solve's indirect arguments (its deciding invocation),
// the next dispatch reads them; after an accelerate pass only its accelerations are read.
constexpr GLbitfield kAfterResidual = GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT;
constexpr GLbitfield kAfterAccelerate = GL_SHADER_STORAGE_BARRIER_BIT;

// The warm start before the first step: the density solve's kappa = p/rho^2 of each block at rest on
// the floor under its own weight (Scene::initial_pressures), so a resting column starts out held.
std::vector<std::uint32_t> initial_warm_start(const scene::Scene& scene) {
    const std::vector<float> p = scene.initial_pressures();
    std::vector<std::uint32_t> words(2 * p.size(), 0u);
    const float rho0 = scene.sph.rest_density;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const float kappa = p[i] / (rho0 * rho0);
        std::memcpy(&words[2 * i], &kappa, sizeof kappa);
    }
    return words;
}

// The boundary rows' kappa_b before the first step (docs/DFSPH.md (D9)): the pressure of the fluid at
// rest at the boundary particle's height, rho0 |g| (top - y_b), where a block resting on the tank's
// floor lies within a kernel support of it horizontally (its footprint grown by h), 0 elsewhere: the
// wall as fluid at rest, as initial_warm_start() starts the fluid.
std::vector<float> initial_boundary_kappa(const scene::Scene& scene, const std::vector<glm::vec4>& boundary) {
    std::vector<float> kappa(2 * boundary.size(), 0.0f);
    const float g = glm::length(scene.gravity), rho0 = scene.sph.rest_density, h = kernel_support(scene.spacing);
    for (std::size_t b = 0; b < boundary.size(); ++b) {
        float p = 0.0f;
        for (const scene::Block& block : scene.blocks) {
            const bool resting = block.min.y <= scene.tank_min.y + 1e-6f && glm::length(block.velocity) == 0.0f;
            const glm::vec3 x(boundary[b]);
            if (!resting || x.x < block.min.x - h || x.x > block.max.x + h || x.z < block.min.z - h || x.z > block.max.z + h) continue;
            p = std::max(p, rho0 * g * std::max(block.max.y - x.y, 0.0f));
        }
        kappa[2 * b] = p / (rho0 * rho0);
    }
    return kappa;
}

std::string defines(const Fluid& fluid, bool divergence, bool rows, bool correction) {
    return fluid.neighbour_defines() + (divergence ? "#define RANRYU_DIVERGENCE_SOLVE 1\n" : "") +
           (rows ? "#define RANRYU_BOUNDARY_ROWS 1\n" : "") + (correction ? "#define RANRYU_GRADIENT_CORRECTION 1\n" : "");
}

// (D13): the passes that solve the density solve's rows eliminated, when the scene sets it.
std::string eliminated(bool on) { return on ? "#define RANRYU_ELIMINATED_ROWS 1\n" : ""; }

// The residual pass's boundary term, sum_b psi_b a_i . gradW_ib = a_i . (sum_b psi_b gradW_ib) (docs/DFSPH.md
// (D6)), from the wall's gradient sum the density pass stores once a step, where nothing else of the residual
// pass visits the boundary: the divergence solve on (its density pass writes PressureAccel), neither (D12)
// nor (D13). Stored in PressureAccel after the accelerations (and (D11)'s L_i when on).
std::string wall_gradient(bool stored, bool correction) {
    if (!stored) return "";
    return std::string("#define RANRYU_WALL_GRADIENT_AT ") + (correction ? "3u" : "1u") + "\n";
}

// (D12): the passes that take part in the density solve's pressure stabilisation, when the scene sets one.
std::string stabilisation(const scene::Scene& scene) {
    return scene.sph.pressure_stabilisation > 0.0f ? "#define RANRYU_PRESSURE_STABILISATION 1\n" : "";
}

shader::Program rows_program(const shader::FileSource& shaders, const char* path, const Fluid& fluid, bool rows,
                             bool divergence = false, bool eliminated_rows = false) {
    return rows ? shader::Program::compute(shaders, path, defines(fluid, divergence, true, false) + eliminated(eliminated_rows)) : shader::Program{};
}

}  // namespace

IterationCapRule IterationCapRule::from_environment() {
    IterationCapRule rule;
    const char* v = std::getenv("RANRYU_DFSPH_CAP");
    if (!v) return rule;
    double factor = 0.0, margin = -1.0;
    char tail = 0;
    if (std::sscanf(v, "%lf,%lf%c", &factor, &margin, &tail) != 2 || !(factor >= 1.0 && factor <= 4.0) || !(margin >= 0.0 && margin <= 20.0) ||
        margin != std::floor(margin))
        throw InputError(std::string("RANRYU_DFSPH_CAP=") + v +
                         ": expected FACTOR,MARGIN with FACTOR in [1, 4] and MARGIN a whole number in [0, 20]");
    return IterationCapRule{factor, margin};
}

std::uint32_t next_iteration_cap(std::uint32_t needed, bool stopped, int least, int most, IterationCapRule rule) {
    // ceil less a hair: a factor that binary fractions hold inexactly (1.1 · 10 = 11.000000000000002)
    // rounds to the whole number it means.
    const double want = stopped ? double(most) : std::ceil(rule.factor * double(needed) - 1e-9) + rule.margin;
    return std::uint32_t(std::clamp(int(std::min(want, 1e6)), least, most));
}

std::uint32_t iterations_at_plan(std::uint32_t most, std::uint32_t record_substeps, int planned) {
    if (planned <= 0 || record_substeps <= std::uint32_t(planned)) return most;
    return std::uint32_t(std::min(std::ceil(double(most) * double(record_substeps) / double(planned)), 1e6));
}

float next_iteration_dt(float stable_dt, std::uint32_t iterations, std::uint32_t shrink_above, std::uint32_t grow_below, float least,
                        float most) {
    const float f = iterations > shrink_above ? 0.9f : iterations < grow_below ? 1.1f : 1.0f;
    return std::clamp(stable_dt * f, least, most);
}

Dfsph::Dfsph(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene, Fluid& fluid)
    : timer_(timer),
      density_pass_(timer.pass("dfsph.density")),
      divergence_solve_(timer.pass("dfsph.divergence.solve")),
      divergence_finish_(timer.pass("dfsph.divergence.finish")),
      predict_pass_(timer.pass("dfsph.pressure.predict")),
      pressure_solve_(timer.pass("dfsph.pressure.solve")),
      integrate_pass_(timer.pass("dfsph.integrate")),
      prepare_pass_(scene.sph.boundary_rows ? timer.pass("dfsph.boundary.prepare") : profile::PassId{}),
      wall_pass_(scene.sph.boundary_rows ? timer.pass("dfsph.boundary.wall") : profile::PassId{}),
      divergence_(scene.sph.divergence_solve),
      rows_(scene.sph.boundary_rows && fluid.boundary_count() > 0),
      correction_(scene.sph.gradient_correction),
      eliminated_(rows_ && scene.sph.eliminate_boundary_rows),
      wall_gradient_(wall_gradient_stored(scene, fluid.boundary_count())),
      density_(shader::Program::compute(shaders, "sim/dfsph/compute_density.comp",
                                        defines(fluid, divergence_, rows_, correction_) + eliminated(eliminated_) + wall_gradient(wall_gradient_, correction_))),
      accelerate_(shader::Program::compute(shaders, "sim/dfsph/accelerate.comp", defines(fluid, false, rows_, correction_) + stabilisation(scene))),
      correct_(shader::Program::compute(shaders, "sim/dfsph/correct_pressure.comp",
                                        defines(fluid, false, rows_, false) + stabilisation(scene) + eliminated(eliminated_) +
                                            wall_gradient(wall_gradient_, correction_))),
      finish_(shader::Program::compute(shaders, "sim/dfsph/finish_divergence.comp", defines(fluid, divergence_, rows_, correction_))),
      predict_(shader::Program::compute(shaders, "sim/dfsph/predict_density.comp", defines(fluid, false, rows_, correction_) + stabilisation(scene))),
      integrate_(shader::Program::compute(shaders, "sim/dfsph/integrate_pressure.comp", defines(fluid, false, rows_, correction_))),
      size_rows_(rows_program(shaders, "sim/dfsph/size_boundary_rows.comp", fluid, rows_)),
      prepare_rows_(rows_program(shaders, "sim/dfsph/prepare_boundary_rows.comp", fluid, rows_, divergence_, eliminated_)),
      wall_density_(rows_program(shaders, "sim/dfsph/compute_wall_density.comp", fluid, rows_)),
      extend_rows_(rows_program(shaders, "sim/dfsph/extend_pressure.comp", fluid, eliminated_)),
      hand_off_rows_(rows_program(shaders, "sim/dfsph/hand_off_excess.comp", fluid, eliminated_)),
      least_(scene.sph.min_iterations),
      most_(scene.sph.max_iterations),
      most_divergence_(scene.sph.max_divergence_iterations),
      cap_rule_(IterationCapRule::from_environment()),
      fluid_(fluid),
      warm_(fluid.carry("Warm", kWarmWords, initial_warm_start(scene))),
      frame_pressure_(fluid.carry("FramePressure", kFramePressureWords, std::vector<std::uint32_t>(kFramePressureWords, 0u))) {
    accelerate_passes_[0] = timer.pass("dfsph.pressure.accelerate", pressure_solve_);
    correct_passes_[0] = timer.pass("dfsph.pressure.correct", pressure_solve_);
    if (divergence_) {
        accelerate_passes_[1] = timer.pass("dfsph.divergence.accelerate", divergence_solve_);
        correct_passes_[1] = timer.pass("dfsph.divergence.correct", divergence_solve_);
    }
    if (rows_) size_rows_pass_ = timer.pass("dfsph.boundary.size", density_pass_);
    if (eliminated_) {
        extend_pass_ = timer.pass("dfsph.pressure.extend", pressure_solve_);
        hand_off_pass_ = timer.pass("dfsph.pressure.hand-off", pressure_solve_);
    }
    if (accelerate_.local_size()[0] != correct_.local_size()[0])
        throw Error("DFSPH: the accelerate and correct passes must share a workgroup size (one indirect dispatch serves both)");
    const std::size_t n = std::max<std::size_t>(fluid.count(), 1);
    params_.eta = scene.sph.max_density_error;
    params_.eta_divergence = scene.sph.max_divergence_error;
    params_.eta_peak = scene.sph.max_particle_density_error;
    params_.relaxation = scene.sph.relaxation;
    params_.chebyshev = scene.sph.chebyshev;
    params_.complementarity_error = scene.sph.complementarity_error ? 1u : 0u;
    params_.stabilisation = scene.sph.pressure_stabilisation;
    params_.warm_start = scene.sph.warm_start;
    params_.warm_start_divergence = scene.sph.divergence_warm_start;
    params_.boundary_relaxation = scene.sph.boundary_relaxation;
    params_.min_iterations = std::uint32_t(least_);
    params_.min_divergence_iterations = 1;
    params_.issued = std::uint32_t(most_);   // until the first record: next_iteration_cap()
    params_.issued_divergence = std::uint32_t(most_divergence_);
    params_.error_scale = float(2147483648.0 / double(n));
    params_.deficient_neighbours = 20;
    params_.boundary_viscosity = scene.sph.boundary_viscosity;
    params_.groups = correct_.groups_for(fluid.count());
    params_.shrink_step_above = std::uint32_t(scene.sph.shrink_step_above);
    params_.grow_step_below = std::uint32_t(scene.sph.grow_step_below);
    // The least step the iterations may ask for: a 64th of the fluid's largest step (SphParams.dt_max:
    // sph.max_time_step, at most the frame), so a solve that cannot converge stops costing steps there.
    params_.iteration_dt_min = fluid.params().dt_max / 64.0f;
    params_ubo_ = gl::Buffer(sizeof params_, GL_DYNAMIC_DRAW, &params_, "DfsphParams");
    // A solve opens with its iterations' dispatch at full size, none run and no error summed.
    std::vector<std::uint8_t> opened(2 * RANRYU_DFSPH_SOLVE_STRIDE, 0);
    for (std::uint32_t k = 0; k < 2; ++k) {
        gpu::SolveState st{};
        st.dispatch = glm::uvec4(params_.groups, 1u, 1u, 0u);
        st.correct_groups = params_.groups, st.correct_y = 1u, st.correct_z = 1u;   // the rows' added by their prepare
        st.rows_groups = 0u, st.rows_y = 1u, st.rows_z = 1u;   // (D13): set by the density solve's prepare
        st.solve = k;
        // (D10)'s first weight, w = 2/(2 - rho_c^2) (glsl/sim/dfsph/dfsph.glsl); unread while it is off.
        st.weight = 2.0f / (2.0f - params_.chebyshev * params_.chebyshev);
        std::memcpy(opened.data() + k * RANRYU_DFSPH_SOLVE_STRIDE, &st, sizeof st);
    }
    solve_ = gl::Buffer(opened.size(), GL_DYNAMIC_COPY, opened.data(), "dfsph.solve");
    opened_ = gl::Buffer(opened.size(), GL_STATIC_DRAW, opened.data(), "dfsph.solve.opened");
    // The fluid's (x_i, kappa_i), then (D9)'s (kappa_b, kappa_v,b) per boundary particle: kappa_b from
    // initial_boundary_kappa() (the first step's density solve starts from it), kappa_v,b at 0.
    const std::size_t nb = rows_ ? fluid.boundary_count() : 0;
    std::vector<float> start(kappa_rows_at(fluid.count()), 0.0f);
    if (rows_) {
        const std::vector<float> kb = initial_boundary_kappa(scene, fluid.boundary().read<glm::vec4>(nb));
        start.insert(start.end(), kb.begin(), kb.end());
    }
    start.resize(kappa_floats(fluid.count(), nb), 0.0f);
    kappa_ = gl::Buffer(start.size() * sizeof(float), GL_DYNAMIC_COPY, start.data(), "dfsph.kappa");
    // (D11)'s L_i after the accelerations, two vec4 a particle, when on (glsl/sim/dfsph/dfsph.glsl).
    pressure_accel_ = gl::Buffer(n * (sizeof(glm::vec4) * (wall_gradient_ ? 2 : 1) + (correction_ ? kCorrectionBytes : 0)), GL_DYNAMIC_COPY, nullptr,
                                 "dfsph.pressure_accel");
    // (D10)'s previous iterates, the fluid's then (D9)'s rows' (kappa_b of the density solve, by
    // boundary particle); one float, bound but never read, when it is off.
    kappa_previous_ = gl::Buffer((params_.chebyshev > 0.0f ? n + nb : 1) * sizeof(float), GL_DYNAMIC_COPY, nullptr, "dfsph.kappa_previous");
    if (rows_) {
        if (prepare_rows_.local_size()[0] != 128 || correct_.local_size()[0] != 128 ||
            (eliminated_ && (extend_rows_.local_size()[0] != 128 || hand_off_rows_.local_size()[0] != 128)))
            throw Error("DFSPH: the boundary-row passes must have 128 invocations a workgroup (size_boundary_rows.comp's kRowGroup)");
        boundary_list_ = gl::Buffer(nb * sizeof(std::uint32_t), GL_DYNAMIC_COPY, nullptr, "dfsph.boundary_list");
        boundary_row_ = gl::Buffer(nb * sizeof(glm::vec2), GL_DYNAMIC_COPY, nullptr, "dfsph.boundary_row");
        // A (run start, mask) pair per run of the walk a row, recorded by the prepare pass
        // (glsl/sim/dfsph/boundary_rows.glsl).
        const std::size_t row_mask_bytes = nb * 2 * std::size_t(fluid.neighbour_runs()) * sizeof(std::uint32_t);
        Fluid::require_one_block(scene, "the boundary rows' neighbour masks of " + std::to_string(nb) + " boundary particles",
                                 row_mask_bytes, "boundary_rows");
        row_masks_ = gl::Buffer(row_mask_bytes, GL_DYNAMIC_COPY, nullptr, "dfsph.row_masks");
        boundary_wall_ = gl::Buffer(nb * sizeof(float), GL_DYNAMIC_COPY, nullptr, "dfsph.boundary_wall");
        // The BoundaryRowsState, then a mark per boundary particle (compute_density.comp).
        gpu::BoundaryRowsState opened_rows{};
        opened_rows.epoch = 1u;   // marks start at 0: "a row the step before", whose kappa_b is the initial 0
        std::vector<std::uint8_t> rows_state(sizeof opened_rows + nb * sizeof(std::uint32_t), 0);
        std::memcpy(rows_state.data(), &opened_rows, sizeof opened_rows);
        rows_state_ = gl::Buffer(rows_state.size(), GL_DYNAMIC_COPY, rows_state.data(), "dfsph.boundary_rows");
    }
}

bool Dfsph::wall_gradient_stored(const scene::Scene& scene, std::size_t boundary) {
    return scene.sph.divergence_solve && boundary > 0 && scene.sph.pressure_stabilisation <= 0.0f &&
           !(scene.sph.boundary_rows && scene.sph.eliminate_boundary_rows);
}

std::size_t Dfsph::bytes_for(std::size_t count, std::size_t boundary, bool rows, bool chebyshev, bool correction, int runs, bool wall) {
    const std::size_t n = std::max<std::size_t>(count, 1);   // as the constructor's kappa_, kappa_previous_ and pressure_accel_
    const std::size_t base = sizeof(gpu::DfsphParams) + 2 * 2 * RANRYU_DFSPH_SOLVE_STRIDE + n * (kKappaFloats * sizeof(float) + sizeof(glm::vec4) * (wall ? 2 : 1)) +
                             (chebyshev ? n : 1) * sizeof(float) + (correction ? n * kCorrectionBytes : 0) +
                             Fluid::carried_bytes(count, kWarmWords) + Fluid::carried_bytes(count, kFramePressureWords);
    if (!rows || boundary == 0) return base;
    // kappa_'s boundary part (padded), kappa_previous_'s with (D10), boundary_wall_, boundary_list_, row_masks_,
    // boundary_row_; rows_state_ and its marks
    return base + kappa_row_floats(boundary) * sizeof(float) +
           boundary * ((chebyshev ? 2 : 1) * sizeof(float) + (2 + 2 * std::size_t(runs)) * sizeof(std::uint32_t) + sizeof(glm::vec2)) +
           sizeof(gpu::BoundaryRowsState);
}

std::size_t Dfsph::kappa_floats(std::size_t count, std::size_t rows) {
    return kappa_rows_at(count) + kappa_row_floats(rows);
}

std::vector<float> Dfsph::read_kappa() const {
    const std::size_t n = fluid_.count(), rows = rows_ ? 2 * fluid_.boundary_count() : 0;
    const std::size_t at = kappa_rows_at(n);
    const std::vector<float> all = kappa_.read<float>(kappa_.size() / sizeof(float));
    std::vector<float> out(n + rows);
    for (std::size_t i = 0; i < n; ++i) out[i] = all[kKappaFloats * i + 3];
    std::copy_n(all.begin() + std::ptrdiff_t(at), rows, out.begin() + std::ptrdiff_t(n));
    return out;
}

void Dfsph::forget_boundary_kappa() {
    if (!rows_) return;
    const float none = 0.0f;
    glBindBuffer(GL_COPY_WRITE_BUFFER, kappa_.id());
    glClearBufferSubData(GL_COPY_WRITE_BUFFER, GL_R32F, GLintptr(kappa_rows_at(fluid_.count()) * sizeof(float)),
                         GLsizeiptr(2 * fluid_.boundary_count() * sizeof(float)), GL_RED, GL_FLOAT, &none);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

std::vector<glm::vec3> Dfsph::read_kappa_positions() const {
    const std::vector<glm::vec4> all = kappa_.read<glm::vec4>(fluid_.count());
    return std::vector<glm::vec3>(all.begin(), all.end());
}

const gl::Buffer& Dfsph::warm_start() const { return fluid_.carried(warm_); }
const gl::Buffer& Dfsph::frame_pressure() const { return fluid_.carried(frame_pressure_); }

void Dfsph::upload_warm_start(const std::vector<glm::vec2>& kappa) {
    if (kappa.size() != fluid_.count()) throw Error("Dfsph::upload_warm_start: expected " + std::to_string(fluid_.count()) + " pairs");
    fluid_.carried(warm_).upload(kappa.data(), kappa.size() * sizeof(glm::vec2));
}

void Dfsph::set_issued_iterations(int density, int divergence) {
    fixed_caps_ = true;
    params_.issued = std::uint32_t(std::clamp(density, 1, most_));
    params_.issued_divergence = std::uint32_t(std::clamp(divergence, 1, most_divergence_));
    upload_params();
}

void Dfsph::upload_params() { params_ubo_.upload_value(params_); }

void Dfsph::persist(StateIo& io) {
    // kappa_ holds the rows' kappa_b kept from step to step after the fluid's, and rows_state_ the
    // rows' epoch and per-boundary marks; the rest is rebuilt by a step before it is read, and saved
    // so that nothing of a step is left out by mistake, but for the rows' neighbour masks: recorded
    // afresh by every step's first prepare pass, and as large as the rest of the rows' state together.
    io.buffer("dfsph.kappa", kappa_);
    io.buffer("dfsph.kappa_previous", kappa_previous_);
    io.buffer("dfsph.pressure_accelerations", pressure_accel_);
    io.buffer("dfsph.solve", solve_);
    io.buffer("dfsph.opened", opened_);
    io.buffer("dfsph.boundary_list", boundary_list_);
    io.buffer("dfsph.boundary_row", boundary_row_);
    io.buffer("dfsph.boundary_rows", rows_state_);
    // The iteration caps planned from the records (begin_frame).
    io.value("dfsph.params", params_);
    io.value("dfsph.recent", recent_);
    io.value("dfsph.recent_next", recent_next_);
    upload_params();
}

void Dfsph::begin_frame(Fluid& fluid) {
    // A new record each frame, plan_lag() frames back: the caps follow no timing.
    const auto& r = fluid.planning_record();
    if (fixed_caps_ || !r || r->frame_substeps == 0) return;
    recent_[recent_next_] = glm::uvec2(r->iterations.z, r->iterations.w);
    recent_next_ = (recent_next_ + 1) % recent_.size();
    // The newest record's need at this frame's steps (the window's older records as they were).
    const int planned = fluid.substeps_this_frame();
    glm::uvec2 needed(iterations_at_plan(r->iterations.z, r->frame_substeps, planned),
                      iterations_at_plan(r->iterations.w, r->frame_substeps, planned));
    for (const glm::uvec2& k : recent_) needed = glm::max(needed, k);
    const std::uint32_t cap = next_iteration_cap(needed.x, r->unconverged.x > 0, least_, most_, cap_rule_);
    const std::uint32_t cap_v = next_iteration_cap(needed.y, r->unconverged.y > 0, 1, most_divergence_, cap_rule_);
    if (cap != params_.issued || cap_v != params_.issued_divergence) {
        params_.issued = cap;
        params_.issued_divergence = cap_v;
        upload_params();
    }
}

shader::StorageSet Dfsph::state(Fluid& fluid, int solve) const {
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_DFSPH);
    shader::StorageSet set = fluid.bind_state();
    set.add("Kappa", kappa_).add("PressureAccel", pressure_accel_).add("KappaPrevious", kappa_previous_);
    set.range("Solve", solve_, std::size_t(solve) * RANRYU_DFSPH_SOLVE_STRIDE, sizeof(gpu::SolveState));
    if (rows_)
        set.add("BoundaryList", boundary_list_).add("BoundaryRow", boundary_row_).add("BoundaryRows", rows_state_)
            .add("BoundaryWall", boundary_wall_).add("RowMasks", row_masks_);
    return set;
}

void Dfsph::step(Fluid& fluid, StepHooks& hooks) {
    if (rows_ && fluid.boundary_generation() != boundary_generation_) {
        // The boundary was re-sorted (the paddle moved): the kept kappa_b belong to other indices now.
        boundary_generation_ = fluid.boundary_generation();
        forget_boundary_kappa();
    }
    fluid.choose_time_step();
    fluid.rebuild_grid();
    compute_density(fluid);
    hooks.after_density(fluid);
    hooks.add_accelerations(fluid);
    solve_divergence(fluid);
    predict_density(fluid);
    solve_density(fluid);
    integrate(fluid);
}

// The solve's SolveState back to its opening state (a GPU copy: nothing waits), after the last
// iteration of the previous step wrote it.
void Dfsph::open_solve(int solve) {
    const auto offset = GLintptr(std::size_t(solve) * RANRYU_DFSPH_SOLVE_STRIDE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, opened_.id());
    glBindBuffer(GL_COPY_WRITE_BUFFER, solve_.id());
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, offset, offset, sizeof(gpu::SolveState));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void Dfsph::compute_density(Fluid& fluid) {
    if (rows_ && fluid.boundary_generation() != wall_generation_) {   // at start, and after the paddle moved
        wall_generation_ = fluid.boundary_generation();
        auto pass = timer_.scope(wall_pass_);
        wall_density_.bind(state(fluid, 1)).dispatch(fluid.boundary_count());
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    if (divergence_) open_solve(1);
    auto pass = timer_.scope(density_pass_);
    density_.bind(state(fluid, 1)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    fluid.set_neighbour_masks_current(true);
    if (rows_) {   // (D9): the rows the density pass listed become this step's
        auto within = timer_.scope(size_rows_pass_);
        size_rows_.bind(state(fluid, 1)).use();
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
}

void Dfsph::dispatch_rows(const shader::Program& program) {
    program.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, rows_state_.id());
    glDispatchComputeIndirect(GLintptr(offsetof(gpu::BoundaryRowsState, dispatch)));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

// (D9): the solve's boundary rows open (sources, diagonals, warm start) from the velocities it starts from.
void Dfsph::prepare_rows(Fluid& fluid, int solve) {
    if (!rows_) return;
    auto pass = timer_.scope(prepare_pass_);
    prepare_rows_.bind(state(fluid, solve));
    dispatch_rows(prepare_rows_);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);   // it sized the solve's residual pass
}

// A solve's (D6) iterations, timed as one pass (each dispatch also a pass within it, timed apart with
// profile --detail): the first "correct" (the pass before it computed the first accelerations), then
// `issued` − 1 pairs, all from the solve's indirect arguments, which the GPU sets to zero workgroups
// once it has converged. "correct" also updates the boundary rows (D9); with
// (D13) the density solve's rows instead hand their excess on before each "correct" and take the
// fluid's pressure before each "accelerate" and once after the last iteration.
void Dfsph::iterate(Fluid& fluid, int solve, int issued, profile::PassId pass_id) {
    const shader::StorageSet set = state(fluid, solve);
    auto pass = timer_.scope(pass_id);
    const auto at = GLintptr(std::size_t(solve) * RANRYU_DFSPH_SOLVE_STRIDE);
    const auto accelerate_args = at + GLintptr(offsetof(gpu::SolveState, dispatch)),
               correct_args = at + GLintptr(offsetof(gpu::SolveState, correct_groups)),
               rows_args = at + GLintptr(offsetof(gpu::SolveState, rows_groups));
    const bool eliminated = eliminated_ && solve == 0;
    // The rows' pass of (D13) ahead of `next`, from the rows' indirect arguments (zero once converged).
    auto rows_pass = [&](const shader::Program& program, profile::PassId within) {
        if (!eliminated) return;
        auto scope = timer_.scope(within);
        program.bind(set).use();
        glDispatchComputeIndirect(rows_args);
        glMemoryBarrier(kAfterAccelerate);
    };
    auto correct = [&] {
        auto scope = timer_.scope(correct_passes_[std::size_t(solve)]);
        correct_.bind(set).use();
        glDispatchComputeIndirect(correct_args);
        glMemoryBarrier(kAfterResidual);
    };
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, solve_.id());
    rows_pass(hand_off_rows_, hand_off_pass_);
    correct();
    for (int k = 1; k < issued; ++k) {
        rows_pass(extend_rows_, extend_pass_);
        {
            auto scope = timer_.scope(accelerate_passes_[std::size_t(solve)]);
            accelerate_.bind(set).use();
            glDispatchComputeIndirect(accelerate_args);
            glMemoryBarrier(kAfterAccelerate);
        }
        rows_pass(hand_off_rows_, hand_off_pass_);
        correct();
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    // (D13): the rows at the solve's final kappa, which the integration's accelerations and the next
    // step's warm start read (the in-loop passes stop with the solve, one iteration short of it).
    if (eliminated) {
        auto scope = timer_.scope(extend_pass_);
        extend_rows_.bind(set);
        dispatch_rows(extend_rows_);
    }
}

void Dfsph::solve_divergence(Fluid& fluid) {
    if (divergence_) {
        prepare_rows(fluid, 1);
        iterate(fluid, 1, int(params_.issued_divergence), divergence_solve_);
    }
    auto pass = timer_.scope(divergence_finish_);
    finish_.bind(state(fluid, 1)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Dfsph::predict_density(Fluid& fluid) {
    open_solve(0);
    prepare_rows(fluid, 0);
    auto pass = timer_.scope(predict_pass_);
    predict_.bind(state(fluid, 0)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Dfsph::solve_density(Fluid& fluid) { iterate(fluid, 0, int(params_.issued), pressure_solve_); }

void Dfsph::integrate(Fluid& fluid) {
    {
        auto pass = timer_.scope(integrate_pass_);
        shader::StorageSet set = state(fluid, 0);
        set.add("NextPositions", fluid.next_positions()).add("NextVelocities", fluid.next_velocities());
        integrate_.bind(set).dispatch(fluid.count());
        // The next step's hash, the time step and the impostor draw read what this wrote.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    }
    fluid.swap_state();
}

}  // namespace ranryu::sim
