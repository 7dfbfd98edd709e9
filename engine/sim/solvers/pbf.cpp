#include "sim/solvers/pbf.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "scene/scene.h"
#include "sim/state_io.h"

namespace ranryu::sim {
namespace {

constexpr std::uint32_t kStartWords = 4;   // the carried step start x_n: a vec4 a particle
constexpr std::uint32_t kWarmWords = 4;    // the carried warm start of (P10): a vec4 a particle

std::string defines(const Fluid& fluid, const char* extra = "") { return fluid.neighbour_defines() + extra; }
// The passes that read or write (P10)'s carried term declare it only when the scene warm-starts.
std::string warm_defines(const scene::Scene& scene) { return scene.sph.pbf.warm_start > 0.0f ? "#define RANRYU_PBF_WARM 1\n" : ""; }

// The cubic spline of docs/SPH.md (1) (glsl/sim/kernel.glsl), for (P5)'s W(|dq|).
double kernel_w(double r, double h) {
    const double q = r / h, k = 8.0 / (std::numbers::pi * h * h * h);
    if (q <= 0.5) return k * (6.0 * q * q * (q - 1.0) + 1.0);
    if (q <= 1.0) return k * 2.0 * (1.0 - q) * (1.0 - q) * (1.0 - q);
    return 0.0;
}

}  // namespace

gpu::PbfParams Pbf::params_for(const scene::Scene& scene) {
    const scene::PbfSettings& s = scene.sph.pbf;
    const double dx = scene.spacing, h = kernel_support(scene.spacing);
    gpu::PbfParams p{};
    p.epsilon = float(s.relaxation / (dx * dx));
    p.s_corr_scale = float(s.s_corr_k * dx * dx);
    p.s_corr_n = float(s.s_corr_n);
    p.inv_w_dq = float(1.0 / kernel_w(double(s.s_corr_dq) * h, h));
    p.xsph = s.xsph;
    p.vorticity = s.vorticity;
    p.iterations = std::uint32_t(s.iterations);
    p.warm_start = s.warm_start;
    return p;
}

Pbf::Pbf(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene, Fluid& fluid)
    : timer_(timer),
      predict_pass_(timer.pass("pbf.predict")),
      lambda_pass_(timer.pass("pbf.lambda")),
      correct_pass_(timer.pass("pbf.correct")),
      velocity_pass_(timer.pass("pbf.velocity")),
      viscosity_pass_(timer.pass("pbf.viscosity")),
      vorticity_pass_(timer.pass("pbf.vorticity")),
      vorticity_on_(scene.sph.pbf.vorticity > 0.0f),
      predict_(shader::Program::compute(shaders, "sim/pbf/predict_positions.comp", warm_defines(scene))),
      lambda_walk_(shader::Program::compute(shaders, "sim/pbf/compute_lambda.comp", defines(fluid, "#define RANRYU_PBF_WALK 1\n"))),
      lambda_program_(shader::Program::compute(shaders, "sim/pbf/compute_lambda.comp", defines(fluid))),
      correct_(shader::Program::compute(shaders, "sim/pbf/correct_positions.comp", defines(fluid))),
      velocity_update_(shader::Program::compute(shaders, "sim/pbf/update_velocities.comp", warm_defines(scene))),
      viscosity_(shader::Program::compute(shaders, "sim/pbf/apply_viscosity.comp",
                                          defines(fluid, vorticity_on_ ? "#define RANRYU_PBF_VORTICITY 1\n" : ""))),
      params_(params_for(scene)),
      fluid_(fluid),
      start_(fluid.carry("Start", kStartWords, std::vector<std::uint32_t>(kStartWords, 0u))),
      warm_(scene.sph.pbf.warm_start > 0.0f ? fluid.carry("PbfWarm", kWarmWords, std::vector<std::uint32_t>(kWarmWords, 0u)) : -1) {
    if (vorticity_on_) vorticity_confine_ = shader::Program::compute(shaders, "sim/pbf/confine_vorticity.comp", defines(fluid));
    const std::size_t n = std::max<std::size_t>(fluid.count(), 1);
    params_ubo_ = gl::Buffer(sizeof params_, GL_STATIC_DRAW, &params_, "PbfParams");
    lambda_ = gl::Buffer(n * sizeof(float), GL_DYNAMIC_COPY, nullptr, "pbf.lambda");
    velocity_ = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "pbf.velocity");
    if (vorticity_on_) vorticity_ = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "pbf.vorticity");
    if (Fluid::boundary_masks(scene, fluid.count())) mask_origins_ = gl::Buffer(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "pbf.mask_origins");
    // The first prediction's non-pressure accelerations: gravity (later ones: the first lambda pass's,
    // with the hooks' additions).
    const glm::vec4 g = fluid.params().gravity;
    glBindBuffer(GL_COPY_WRITE_BUFFER, fluid.accelerations().id());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, &g);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // (P1): the fixed step; the fluid plans exactly `substeps` of it a frame.
    fluid.set_fixed_dt(scene.frame_dt / float(scene.sph.pbf.substeps));
}

std::size_t Pbf::bytes_for(const scene::Scene& scene, std::size_t count) {
    const std::size_t n = std::max<std::size_t>(count, 1);   // as the constructor's buffers
    return sizeof(gpu::PbfParams) + n * (sizeof(float) + sizeof(glm::vec4)) +
           (scene.sph.pbf.vorticity > 0.0f ? n * sizeof(glm::vec4) : 0) + (Fluid::boundary_masks(scene, count) ? n * sizeof(glm::vec4) : 0) +
           Fluid::carried_bytes(count, kStartWords) +
           (scene.sph.pbf.warm_start > 0.0f ? Fluid::carried_bytes(count, kWarmWords) : 0);
}

shader::StorageSet Pbf::state(Fluid& fluid) const {
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_PBF);
    shader::StorageSet set = fluid.bind_state();
    set.add("Lambda", lambda_).add("PbfVelocity", velocity_);
    if (vorticity_on_) set.add("Vorticity", vorticity_);
    set.add("MaskOrigins", mask_origins_);   // none without the masks: add() skips it
    return set;
}

void Pbf::persist(StateIo& io) {
    // The step's start and the warm start (P10) are the fluid's carried arrays; these are rewritten
    // by each step before they are read, and saved so that nothing of a step is left out by mistake.
    io.buffer("pbf.lambda", lambda_);
    io.buffer("pbf.velocities", velocity_);
    io.buffer("pbf.vorticity", vorticity_);
}

void Pbf::step(Fluid& fluid, StepHooks& hooks) {
    fluid.choose_time_step();
    predict(fluid);
    fluid.rebuild_grid();
    for (int k = 0; k < iterations(); ++k) {
        compute_lambda(fluid, k == 0, k == iterations() - 1);
        if (k == 0) {
            hooks.after_density(fluid);
            hooks.add_accelerations(fluid);
        }
        correct_positions(fluid);
    }
    update_velocities(fluid);
    apply_viscosity(fluid);
}

void Pbf::predict(Fluid& fluid) {
    auto pass = timer_.scope(predict_pass_);
    predict_.bind(state(fluid)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Pbf::compute_lambda(Fluid& fluid, bool first, bool last) {
    auto pass = timer_.scope(lambda_pass_);
    const shader::Program& program = first ? lambda_walk_ : lambda_program_;
    glProgramUniform1ui(program.id(), RANRYU_LOC_AUX, last ? 1u : 0u);
    program.bind(state(fluid)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (first) fluid.set_neighbour_masks_current(true);
}

// The masks stay those of the first lambda pass: the cell order does not change within a step, and
// the later passes visit the neighbours the walk found at the moved positions (docs/PBF.md "A step").
void Pbf::correct_positions(Fluid& fluid) {
    {
        auto pass = timer_.scope(correct_pass_);
        shader::StorageSet set = state(fluid);
        set.add("NextPositions", fluid.next_positions());
        correct_.bind(set).dispatch(fluid.count());
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    fluid.swap_state();   // the velocities swap too: none is read until update_velocities() writes them
}

void Pbf::update_velocities(Fluid& fluid) {
    auto pass = timer_.scope(velocity_pass_);
    velocity_update_.bind(state(fluid)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void Pbf::apply_viscosity(Fluid& fluid) {
    {
        auto pass = timer_.scope(viscosity_pass_);
        viscosity_.bind(state(fluid)).dispatch(fluid.count());
        // The next step's prediction, the time step and the impostor draw read what this wrote.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    }
    if (!vorticity_on_) return;
    auto pass = timer_.scope(vorticity_pass_);
    vorticity_confine_.bind(state(fluid)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

}  // namespace ranryu::sim
