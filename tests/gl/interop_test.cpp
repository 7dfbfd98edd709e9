// glsl/shared/bindings.h is compiled by C++ and by GLSL. These cases hold the two readings equal:
// (a) every member the driver reports in the blocks (std140 uniform blocks; StepState a std430
//     storage block, as the SPH passes declare it, and SubparticleState and SolveState likewise) sits
//     at the C++ offsetof and has the C++ type, and each block is sizeof bytes; uniform blocks sit at
//     their shared binding points, storage blocks at the slot the program gave them (bound by name);
// (b) random values written through the C++ structs come back bit for bit through the shader;
// (c) the shared macros (uniform binding points, locations, sort, sub-particle and DFSPH constants)
//     agree in both languages.
// The probe shader is glsl/test/probe_layout.comp; its header comment gives the output order.
#include "support/gl_fixture.h"

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "gl/gl.h"
#include "gl/objects.h"
#include "shader/program.h"
#include "shared/bindings.h"

using ranryu::gl::Buffer;
using ranryu::shader::FileSource;
using ranryu::shader::Program;
namespace gpu = ranryu::gpu;

namespace {

// What C++ says about one member: its byte offset in the struct and the GLSL type it must have.
struct Member {
    std::size_t offset;
    GLenum type;
};

// Every member of the three shared structs, by the name the driver gives it (instance.member).
// offsetof on the glm-member structs is conditionally supported; GCC and Clang give the layout.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
const std::map<std::string, Member>& cpp_members() {
    static const std::map<std::string, Member> table = {
        {"probe.m", {offsetof(gpu::LayoutProbe, m), GL_FLOAT_MAT4}},
        {"probe.v", {offsetof(gpu::LayoutProbe, v), GL_FLOAT_VEC4}},
        {"probe.u", {offsetof(gpu::LayoutProbe, u), GL_UNSIGNED_INT_VEC4}},
        {"probe.f0", {offsetof(gpu::LayoutProbe, f0), GL_FLOAT}},
        {"probe.f1", {offsetof(gpu::LayoutProbe, f1), GL_FLOAT}},
        {"probe.u0", {offsetof(gpu::LayoutProbe, u0), GL_UNSIGNED_INT}},
        {"probe.u1", {offsetof(gpu::LayoutProbe, u1), GL_UNSIGNED_INT}},

        {"sim.gravity", {offsetof(gpu::SimParams, gravity), GL_FLOAT_VEC4}},
        {"sim.domain_min", {offsetof(gpu::SimParams, domain_min), GL_FLOAT_VEC4}},
        {"sim.domain_max", {offsetof(gpu::SimParams, domain_max), GL_FLOAT_VEC4}},
        {"sim.dt", {offsetof(gpu::SimParams, dt), GL_FLOAT}},
        {"sim.restitution", {offsetof(gpu::SimParams, restitution), GL_FLOAT}},
        {"sim.particle_radius", {offsetof(gpu::SimParams, particle_radius), GL_FLOAT}},
        {"sim.particle_count", {offsetof(gpu::SimParams, particle_count), GL_UNSIGNED_INT}},

        {"frame.view", {offsetof(gpu::FrameParams, view), GL_FLOAT_MAT4}},
        {"frame.proj", {offsetof(gpu::FrameParams, proj), GL_FLOAT_MAT4}},
        {"frame.view_proj", {offsetof(gpu::FrameParams, view_proj), GL_FLOAT_MAT4}},
        {"frame.eye", {offsetof(gpu::FrameParams, eye), GL_FLOAT_VEC4}},
        {"frame.light_dir", {offsetof(gpu::FrameParams, light_dir), GL_FLOAT_VEC4}},
        {"frame.light_color", {offsetof(gpu::FrameParams, light_color), GL_FLOAT_VEC4}},
        {"frame.material", {offsetof(gpu::FrameParams, material), GL_FLOAT_VEC4}},
        {"frame.viewport", {offsetof(gpu::FrameParams, viewport), GL_FLOAT_VEC4}},
        {"frame.speed_scale", {offsetof(gpu::FrameParams, speed_scale), GL_FLOAT_VEC4}},
        {"frame.tank_min", {offsetof(gpu::FrameParams, tank_min), GL_FLOAT_VEC4}},
        {"frame.tank_max", {offsetof(gpu::FrameParams, tank_max), GL_FLOAT_VEC4}},

        {"grid.origin", {offsetof(gpu::GridParams, origin), GL_FLOAT_VEC4}},
        {"grid.dims", {offsetof(gpu::GridParams, dims), GL_UNSIGNED_INT_VEC4}},
        {"grid.count", {offsetof(gpu::GridParams, count), GL_UNSIGNED_INT}},
        {"grid.morton", {offsetof(gpu::GridParams, morton), GL_UNSIGNED_INT}},
        {"grid.key_max", {offsetof(gpu::GridParams, key_max), GL_UNSIGNED_INT}},
        {"grid.pad0", {offsetof(gpu::GridParams, pad0), GL_UNSIGNED_INT}},

        {"sph.gravity", {offsetof(gpu::SphParams, gravity), GL_FLOAT_VEC4}},
        {"sph.domain_min", {offsetof(gpu::SphParams, domain_min), GL_FLOAT_VEC4}},
        {"sph.domain_max", {offsetof(gpu::SphParams, domain_max), GL_FLOAT_VEC4}},
        {"sph.h", {offsetof(gpu::SphParams, h), GL_FLOAT}},
        {"sph.mass", {offsetof(gpu::SphParams, mass), GL_FLOAT}},
        {"sph.rest_density", {offsetof(gpu::SphParams, rest_density), GL_FLOAT}},
        {"sph.stiffness", {offsetof(gpu::SphParams, stiffness), GL_FLOAT}},
        {"sph.viscosity", {offsetof(gpu::SphParams, viscosity), GL_FLOAT}},
        {"sph.sound_speed", {offsetof(gpu::SphParams, sound_speed), GL_FLOAT}},
        {"sph.spacing", {offsetof(gpu::SphParams, spacing), GL_FLOAT}},
        {"sph.cfl", {offsetof(gpu::SphParams, cfl), GL_FLOAT}},
        {"sph.force_factor", {offsetof(gpu::SphParams, force_factor), GL_FLOAT}},
        {"sph.dt_max", {offsetof(gpu::SphParams, dt_max), GL_FLOAT}},
        {"sph.dt_floor", {offsetof(gpu::SphParams, dt_floor), GL_FLOAT}},
        {"sph.density_limit", {offsetof(gpu::SphParams, density_limit), GL_FLOAT}},
        {"sph.speed_limit", {offsetof(gpu::SphParams, speed_limit), GL_FLOAT}},
        {"sph.particle_count", {offsetof(gpu::SphParams, particle_count), GL_UNSIGNED_INT}},
        {"sph.boundary_count", {offsetof(gpu::SphParams, boundary_count), GL_UNSIGNED_INT}},
        {"sph.front_band", {offsetof(gpu::SphParams, front_band), GL_FLOAT}},
        {"sph.artificial_viscosity", {offsetof(gpu::SphParams, artificial_viscosity), GL_FLOAT}},
        {"sph.inv_h", {offsetof(gpu::SphParams, inv_h), GL_FLOAT}},
        {"sph.w_scale", {offsetof(gpu::SphParams, w_scale), GL_FLOAT}},
        {"sph.grad_scale", {offsetof(gpu::SphParams, grad_scale), GL_FLOAT}},

        {"step.dt", {offsetof(gpu::StepState, dt), GL_FLOAT}},
        {"step.time", {offsetof(gpu::StepState, time), GL_FLOAT}},
        {"step.frame_left", {offsetof(gpu::StepState, frame_left), GL_FLOAT}},
        {"step.substeps_left", {offsetof(gpu::StepState, substeps_left), GL_UNSIGNED_INT}},
        {"step.max_speed", {offsetof(gpu::StepState, max_speed), GL_UNSIGNED_INT}},
        {"step.max_accel", {offsetof(gpu::StepState, max_accel), GL_UNSIGNED_INT}},
        {"step.frame_max_speed", {offsetof(gpu::StepState, frame_max_speed), GL_UNSIGNED_INT}},
        {"step.frame_max_density", {offsetof(gpu::StepState, frame_max_density), GL_UNSIGNED_INT}},
        {"step.frame_min_dt", {offsetof(gpu::StepState, frame_min_dt), GL_FLOAT}},
        {"step.frame_substeps", {offsetof(gpu::StepState, frame_substeps), GL_UNSIGNED_INT}},
        {"step.nan_count", {offsetof(gpu::StepState, nan_count), GL_UNSIGNED_INT}},
        {"step.nan_index", {offsetof(gpu::StepState, nan_index), GL_UNSIGNED_INT}},
        {"step.escaped_count", {offsetof(gpu::StepState, escaped_count), GL_UNSIGNED_INT}},
        {"step.escaped_index", {offsetof(gpu::StepState, escaped_index), GL_UNSIGNED_INT}},
        {"step.speed_index", {offsetof(gpu::StepState, speed_index), GL_UNSIGNED_INT}},
        {"step.density_index", {offsetof(gpu::StepState, density_index), GL_UNSIGNED_INT}},
        {"step.front", {offsetof(gpu::StepState, front), GL_UNSIGNED_INT}},
        {"step.frame", {offsetof(gpu::StepState, frame), GL_UNSIGNED_INT}},
        {"step.steps", {offsetof(gpu::StepState, steps), GL_UNSIGNED_INT}},
        {"step.live_count", {offsetof(gpu::StepState, live_count), GL_UNSIGNED_INT}},
        {"step.iterations", {offsetof(gpu::StepState, iterations), GL_UNSIGNED_INT_VEC4}},
        {"step.unconverged", {offsetof(gpu::StepState, unconverged), GL_UNSIGNED_INT_VEC4}},
        {"step.error", {offsetof(gpu::StepState, error), GL_FLOAT_VEC4}},
        {"step.stable_dt", {offsetof(gpu::StepState, stable_dt), GL_FLOAT}},
        {"step.iteration_dt", {offsetof(gpu::StepState, iteration_dt), GL_FLOAT}},
        {"step.issued", {offsetof(gpu::StepState, issued), GL_UNSIGNED_INT}},
        {"step.issued_divergence", {offsetof(gpu::StepState, issued_divergence), GL_UNSIGNED_INT}},
        {"step.speed_position", {offsetof(gpu::StepState, speed_position), GL_FLOAT_VEC4}},
        {"step.density_position", {offsetof(gpu::StepState, density_position), GL_FLOAT_VEC4}},
        {"step.peak_error", {offsetof(gpu::StepState, peak_error), GL_UNSIGNED_INT}},
        {"step.pad0", {offsetof(gpu::StepState, pad0), GL_UNSIGNED_INT}},
        {"step.pad1", {offsetof(gpu::StepState, pad1), GL_UNSIGNED_INT}},
        {"step.pad2", {offsetof(gpu::StepState, pad2), GL_UNSIGNED_INT}},

        {"subp.level_energy", {offsetof(gpu::SubparticleParams, level_energy), GL_FLOAT_VEC4}},
        {"subp.energy_scale", {offsetof(gpu::SubparticleParams, energy_scale), GL_FLOAT_VEC4}},
        {"subp.spacing", {offsetof(gpu::SubparticleParams, spacing), GL_FLOAT}},
        {"subp.beta", {offsetof(gpu::SubparticleParams, beta), GL_FLOAT}},
        {"subp.coherence_time", {offsetof(gpu::SubparticleParams, coherence_time), GL_FLOAT}},
        {"subp.inv_sigma", {offsetof(gpu::SubparticleParams, inv_sigma), GL_FLOAT}},
        {"subp.noise_lmax", {offsetof(gpu::SubparticleParams, noise_lmax), GL_INT}},
        {"subp.tile_size", {offsetof(gpu::SubparticleParams, tile_size), GL_UNSIGNED_INT}},
        {"subp.levels", {offsetof(gpu::SubparticleParams, levels), GL_UNSIGNED_INT}},
        {"subp.budget", {offsetof(gpu::SubparticleParams, budget), GL_UNSIGNED_INT}},
        {"subp.particle_count", {offsetof(gpu::SubparticleParams, particle_count), GL_UNSIGNED_INT}},
        {"subp.pad0", {offsetof(gpu::SubparticleParams, pad0), GL_UNSIGNED_INT}},
        {"subp.pad1", {offsetof(gpu::SubparticleParams, pad1), GL_UNSIGNED_INT}},
        {"subp.pad2", {offsetof(gpu::SubparticleParams, pad2), GL_UNSIGNED_INT}},

        {"subs.dispatch", {offsetof(gpu::SubparticleState, dispatch), GL_UNSIGNED_INT_VEC4}},
        {"subs.draw", {offsetof(gpu::SubparticleState, draw), GL_UNSIGNED_INT_VEC4}},
        {"subs.counts", {offsetof(gpu::SubparticleState, counts), GL_UNSIGNED_INT_VEC4}},
        {"subs.offsets", {offsetof(gpu::SubparticleState, offsets), GL_UNSIGNED_INT_VEC4}},
        {"subs.limits", {offsetof(gpu::SubparticleState, limits), GL_UNSIGNED_INT_VEC4}},

        {"dfsph.eta", {offsetof(gpu::DfsphParams, eta), GL_FLOAT}},
        {"dfsph.eta_divergence", {offsetof(gpu::DfsphParams, eta_divergence), GL_FLOAT}},
        {"dfsph.relaxation", {offsetof(gpu::DfsphParams, relaxation), GL_FLOAT}},
        {"dfsph.warm_start", {offsetof(gpu::DfsphParams, warm_start), GL_FLOAT}},
        {"dfsph.min_iterations", {offsetof(gpu::DfsphParams, min_iterations), GL_UNSIGNED_INT}},
        {"dfsph.min_divergence_iterations", {offsetof(gpu::DfsphParams, min_divergence_iterations), GL_UNSIGNED_INT}},
        {"dfsph.issued", {offsetof(gpu::DfsphParams, issued), GL_UNSIGNED_INT}},
        {"dfsph.issued_divergence", {offsetof(gpu::DfsphParams, issued_divergence), GL_UNSIGNED_INT}},
        {"dfsph.error_scale", {offsetof(gpu::DfsphParams, error_scale), GL_FLOAT}},
        {"dfsph.deficient_neighbours", {offsetof(gpu::DfsphParams, deficient_neighbours), GL_UNSIGNED_INT}},
        {"dfsph.boundary_viscosity", {offsetof(gpu::DfsphParams, boundary_viscosity), GL_FLOAT}},
        {"dfsph.groups", {offsetof(gpu::DfsphParams, groups), GL_UNSIGNED_INT}},
        {"dfsph.warm_start_divergence", {offsetof(gpu::DfsphParams, warm_start_divergence), GL_FLOAT}},
        {"dfsph.boundary_relaxation", {offsetof(gpu::DfsphParams, boundary_relaxation), GL_FLOAT}},
        {"dfsph.chebyshev", {offsetof(gpu::DfsphParams, chebyshev), GL_FLOAT}},
        {"dfsph.complementarity_error", {offsetof(gpu::DfsphParams, complementarity_error), GL_UNSIGNED_INT}},
        {"dfsph.shrink_step_above", {offsetof(gpu::DfsphParams, shrink_step_above), GL_UNSIGNED_INT}},
        {"dfsph.grow_step_below", {offsetof(gpu::DfsphParams, grow_step_below), GL_UNSIGNED_INT}},
        {"dfsph.iteration_dt_min", {offsetof(gpu::DfsphParams, iteration_dt_min), GL_FLOAT}},
        {"dfsph.eta_peak", {offsetof(gpu::DfsphParams, eta_peak), GL_FLOAT}},
        {"dfsph.stabilisation", {offsetof(gpu::DfsphParams, stabilisation), GL_FLOAT}},
        {"dfsph.pad0", {offsetof(gpu::DfsphParams, pad0), GL_UNSIGNED_INT}},
        {"dfsph.pad1", {offsetof(gpu::DfsphParams, pad1), GL_UNSIGNED_INT}},
        {"dfsph.pad2", {offsetof(gpu::DfsphParams, pad2), GL_UNSIGNED_INT}},

        {"solve.dispatch", {offsetof(gpu::SolveState, dispatch), GL_UNSIGNED_INT_VEC4}},
        {"solve.iterations", {offsetof(gpu::SolveState, iterations), GL_UNSIGNED_INT}},
        {"solve.error_sum", {offsetof(gpu::SolveState, error_sum), GL_UNSIGNED_INT}},
        {"solve.groups_done", {offsetof(gpu::SolveState, groups_done), GL_UNSIGNED_INT}},
        {"solve.solve", {offsetof(gpu::SolveState, solve), GL_UNSIGNED_INT}},
        {"solve.weight", {offsetof(gpu::SolveState, weight), GL_FLOAT}},
        {"solve.correct_groups", {offsetof(gpu::SolveState, correct_groups), GL_UNSIGNED_INT}},
        {"solve.correct_y", {offsetof(gpu::SolveState, correct_y), GL_UNSIGNED_INT}},
        {"solve.correct_z", {offsetof(gpu::SolveState, correct_z), GL_UNSIGNED_INT}},
        {"solve.error_peak", {offsetof(gpu::SolveState, error_peak), GL_UNSIGNED_INT}},
        {"solve.peak", {offsetof(gpu::SolveState, peak), GL_FLOAT}},
        {"solve.rows_groups", {offsetof(gpu::SolveState, rows_groups), GL_UNSIGNED_INT}},
        {"solve.rows_y", {offsetof(gpu::SolveState, rows_y), GL_UNSIGNED_INT}},
        {"solve.rows_z", {offsetof(gpu::SolveState, rows_z), GL_UNSIGNED_INT}},
        {"solve.pad0", {offsetof(gpu::SolveState, pad0), GL_UNSIGNED_INT}},
        {"solve.pad1", {offsetof(gpu::SolveState, pad1), GL_UNSIGNED_INT}},
        {"solve.pad2", {offsetof(gpu::SolveState, pad2), GL_UNSIGNED_INT}},

        {"rows.dispatch", {offsetof(gpu::BoundaryRowsState, dispatch), GL_UNSIGNED_INT_VEC4}},
        {"rows.rows", {offsetof(gpu::BoundaryRowsState, rows), GL_UNSIGNED_INT}},
        {"rows.count", {offsetof(gpu::BoundaryRowsState, count), GL_UNSIGNED_INT}},
        {"rows.epoch", {offsetof(gpu::BoundaryRowsState, epoch), GL_UNSIGNED_INT}},
        {"rows.pad0", {offsetof(gpu::BoundaryRowsState, pad0), GL_UNSIGNED_INT}},
        {"pbf.epsilon", {offsetof(gpu::PbfParams, epsilon), GL_FLOAT}},
        {"pbf.s_corr_scale", {offsetof(gpu::PbfParams, s_corr_scale), GL_FLOAT}},
        {"pbf.s_corr_n", {offsetof(gpu::PbfParams, s_corr_n), GL_FLOAT}},
        {"pbf.inv_w_dq", {offsetof(gpu::PbfParams, inv_w_dq), GL_FLOAT}},
        {"pbf.xsph", {offsetof(gpu::PbfParams, xsph), GL_FLOAT}},
        {"pbf.vorticity", {offsetof(gpu::PbfParams, vorticity), GL_FLOAT}},
        {"pbf.iterations", {offsetof(gpu::PbfParams, iterations), GL_UNSIGNED_INT}},
        {"pbf.warm_start", {offsetof(gpu::PbfParams, warm_start), GL_FLOAT}},
    };
    return table;
}
#pragma GCC diagnostic pop

// The probe's blocks: GLSL block name, instance prefix, C++ size, binding point (uniform blocks; a
// storage block's is the slot the program gave it, kByName), and the program interfaces of the block
// and of its members (uniform block or shader storage block).
constexpr GLuint kByName = ~0u;
struct Block {
    const char* name;
    const char* prefix;
    std::size_t size;
    GLuint binding;
    GLenum block_interface;
    GLenum member_interface;
};
const Block kBlocks[] = {
    {"ProbeBlock", "probe.", sizeof(gpu::LayoutProbe), RANRYU_UBO_PROBE, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"SimBlock", "sim.", sizeof(gpu::SimParams), RANRYU_UBO_SIM, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"FrameBlock", "frame.", sizeof(gpu::FrameParams), RANRYU_UBO_FRAME, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"GridBlock", "grid.", sizeof(gpu::GridParams), RANRYU_UBO_GRID, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"SphBlock", "sph.", sizeof(gpu::SphParams), RANRYU_UBO_SPH, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"Step", "step.", sizeof(gpu::StepState), kByName, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE},
    {"SubparticleBlock", "subp.", sizeof(gpu::SubparticleParams), RANRYU_UBO_SUBPARTICLES, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"SubparticleStateBlock", "subs.", sizeof(gpu::SubparticleState), kByName, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE},
    {"DfsphBlock", "dfsph.", sizeof(gpu::DfsphParams), RANRYU_UBO_DFSPH, GL_UNIFORM_BLOCK, GL_UNIFORM},
    {"Solve", "solve.", sizeof(gpu::SolveState), kByName, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE},
    {"BoundaryRows", "rows.", sizeof(gpu::BoundaryRowsState), kByName, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE},
    {"PbfBlock", "pbf.", sizeof(gpu::PbfParams), RANRYU_UBO_PBF, GL_UNIFORM_BLOCK, GL_UNIFORM},
};

// The shared macros in the order of kMacros in probe_layout.comp.
const std::vector<std::pair<const char*, std::uint32_t>> kMacros = {
    {"RANRYU_UBO_FRAME", RANRYU_UBO_FRAME},
    {"RANRYU_UBO_SIM", RANRYU_UBO_SIM},
    {"RANRYU_UBO_GRID", RANRYU_UBO_GRID},
    {"RANRYU_UBO_SPH", RANRYU_UBO_SPH},
    {"RANRYU_UBO_PROBE", RANRYU_UBO_PROBE},
    {"RANRYU_UBO_SURFACE", RANRYU_UBO_SURFACE},
    {"RANRYU_UBO_NOISE", RANRYU_UBO_NOISE},
    {"RANRYU_LOC_COUNT", RANRYU_LOC_COUNT},
    {"RANRYU_LOC_SHIFT", RANRYU_LOC_SHIFT},
    {"RANRYU_LOC_STAGE", RANRYU_LOC_STAGE},
    {"RANRYU_LOC_AUX", RANRYU_LOC_AUX},
    {"RANRYU_ATTR_POSITION", RANRYU_ATTR_POSITION},
    {"RANRYU_ATTR_VELOCITY", RANRYU_ATTR_VELOCITY},
    {"RANRYU_SORT_RADIX_BITS", RANRYU_SORT_RADIX_BITS},
    {"RANRYU_SORT_RADIX_ITEMS_PER_THREAD", RANRYU_SORT_RADIX_ITEMS_PER_THREAD},
    {"RANRYU_SORT_BITONIC_ITEMS_PER_THREAD", RANRYU_SORT_BITONIC_ITEMS_PER_THREAD},
    {"RANRYU_UBO_SUBPARTICLES", RANRYU_UBO_SUBPARTICLES},
    {"RANRYU_LOC_SUBPARTICLE_GROUP", RANRYU_LOC_SUBPARTICLE_GROUP},
    {"RANRYU_SUBPARTICLE_MAX_LEVEL", RANRYU_SUBPARTICLE_MAX_LEVEL},
    {"RANRYU_SUBPARTICLE_SPLIT_SHIFT", RANRYU_SUBPARTICLE_SPLIT_SHIFT},
    {"RANRYU_SUBPARTICLE_SPLAT_SCALE", std::uint32_t(RANRYU_SUBPARTICLE_SPLAT_SCALE)},
    {"RANRYU_UBO_DFSPH", RANRYU_UBO_DFSPH},
    {"RANRYU_DFSPH_SOLVE_STRIDE", RANRYU_DFSPH_SOLVE_STRIDE},
    {"RANRYU_UBO_PBF", RANRYU_UBO_PBF},
    {"RANRYU_PBF_WARM_CAP", std::bit_cast<std::uint32_t>(float(RANRYU_PBF_WARM_CAP))},
    {"RANRYU_EXTREME_SPAN", RANRYU_EXTREME_SPAN},
    {"RANRYU_EXTREME_SPEED", RANRYU_EXTREME_SPEED},
    {"RANRYU_EXTREME_DENSITY", RANRYU_EXTREME_DENSITY},
};

const Program& probe() {
    static const Program p = Program::compute(FileSource::embedded(), "test/probe_layout.comp");
    return p;
}

std::uint32_t bits(float x) {
    std::uint32_t u;
    std::memcpy(&u, &x, 4);
    return u;
}

// Distinct random values, so that a member read from a neighbour's slot cannot match by chance.
class Distinct {
public:
    explicit Distinct(ranryu::test::Random& r) : r_(r) {}
    float f() {   // a normal float of either sign, 1e-3 ≤ |x| < 1e3 (no denormals, NaNs or zeros)
        for (;;) {
            const float x = (r_.below(2) ? -1.0f : 1.0f) * std::exp2(r_.uniform(-9.9f, 9.9f));
            if (used_.insert(bits(x)).second) return x;
        }
    }
    std::uint32_t u() {
        for (;;) {
            const std::uint32_t x = std::uint32_t(r_.engine()());
            if (used_.insert(x).second) return x;
        }
    }
    glm::vec4 v4() { return {f(), f(), f(), f()}; }
    glm::uvec4 u4() { return {u(), u(), u(), u()}; }
    glm::mat4 m4() { return {v4(), v4(), v4(), v4()}; }

private:
    ranryu::test::Random& r_;
    std::set<std::uint32_t> used_;
};

// Appends the words of a value in the probe's order (matrices column-major, as glm stores them).
struct Words {
    std::vector<std::uint32_t> w;
    void put(float x) { w.push_back(bits(x)); }
    void put(std::uint32_t x) { w.push_back(x); }
    void put(std::int32_t x) { w.push_back(std::uint32_t(x)); }
    void put(const glm::vec4& x) { for (int i = 0; i < 4; ++i) put(x[i]); }
    void put(const glm::uvec4& x) { for (int i = 0; i < 4; ++i) put(x[i]); }
    void put(const glm::mat4& x) { for (int c = 0; c < 4; ++c) put(x[c]); }
};

GLint resource(GLuint program, GLenum interface, GLuint index, GLenum prop) {
    GLint v = -1;
    glGetProgramResourceiv(program, interface, index, 1, &prop, 1, nullptr, &v);
    return v;
}

std::string resource_name(GLuint program, GLenum interface, GLuint index) {
    char name[256] = {};
    GLsizei length = 0;
    glGetProgramResourceName(program, interface, index, GLsizei(sizeof name), &length, name);
    return std::string(name, std::size_t(length));
}

}  // namespace

TEST_CASE("every member of the shared structs sits where C++ puts it") {
    ranryu::test::context();
    const GLuint prog = probe().id();
    std::set<std::string> seen;
    for (const Block& b : kBlocks) {
        INFO("block " << b.name);
        const GLuint block = glGetProgramResourceIndex(prog, b.block_interface, b.name);
        REQUIRE(block != GL_INVALID_INDEX);
        CHECK(std::size_t(resource(prog, b.block_interface, block, GL_BUFFER_DATA_SIZE)) == b.size);
        const GLuint binding = b.binding == kByName ? GLuint(probe().storage_slot(b.name)) : b.binding;
        CHECK(GLuint(resource(prog, b.block_interface, block, GL_BUFFER_BINDING)) == binding);

        // All members GL reports, not just the ones C++ knows: a GLSL-only member fails the lookup.
        // (std140 blocks have every member active; the probe reads every member of the others.)
        const GLint count = resource(prog, b.block_interface, block, GL_NUM_ACTIVE_VARIABLES);
        REQUIRE(count > 0);
        std::vector<GLint> vars(std::size_t(count), -1);
        const GLenum prop = GL_ACTIVE_VARIABLES;
        glGetProgramResourceiv(prog, b.block_interface, block, 1, &prop, count, nullptr, vars.data());
        for (const GLint var : vars) {
            REQUIRE(var >= 0);
            const GLenum mi = b.member_interface;
            const std::string name = resource_name(prog, mi, GLuint(var));
            INFO("member " << name);
            CHECK(name.rfind(b.prefix, 0) == 0);
            const auto it = cpp_members().find(name);
            REQUIRE(it != cpp_members().end());
            seen.insert(name);
            CHECK(resource(prog, mi, GLuint(var), GL_BLOCK_INDEX) == GLint(block));
            CHECK(std::size_t(resource(prog, mi, GLuint(var), GL_OFFSET)) == it->second.offset);
            CHECK(GLenum(resource(prog, mi, GLuint(var), GL_TYPE)) == it->second.type);
            CHECK(resource(prog, mi, GLuint(var), GL_ARRAY_SIZE) == 1);
            if (it->second.type == GL_FLOAT_MAT4) {
                // glm::mat4: four column vec4s, packed.
                CHECK(resource(prog, mi, GLuint(var), GL_MATRIX_STRIDE) == GLint(sizeof(glm::vec4)));
                CHECK(resource(prog, mi, GLuint(var), GL_IS_ROW_MAJOR) == 0);
            }
        }
    }
    // And every member C++ knows was reported by GL.
    CHECK(seen.size() == cpp_members().size());
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("the FrameExtreme entries follow the StepState in the Step block as the passes declare it") {
    // shared/bindings.h: entry k of Step.extreme[] at sizeof(StepState) + k·sizeof(FrameExtreme), its
    // members at their offsetof; read from the program that folds them (every member it uses is active).
    ranryu::test::context();
    const Program p = Program::compute(FileSource::embedded(), "sim/fluid/record_extremes.comp");
    const std::pair<const char*, std::size_t> members[] = {{"extreme[0].bits", offsetof(gpu::FrameExtreme, bits)},
                                                           {"extreme[0].index", offsetof(gpu::FrameExtreme, index)},
                                                           {"extreme[0].position", offsetof(gpu::FrameExtreme, position)}};
    for (const auto& [name, offset] : members) {
        INFO(name);
        const GLuint var = glGetProgramResourceIndex(p.id(), GL_BUFFER_VARIABLE, name);
        REQUIRE(var != GL_INVALID_INDEX);
        CHECK(std::size_t(resource(p.id(), GL_BUFFER_VARIABLE, var, GL_OFFSET)) == sizeof(gpu::StepState) + offset);
        CHECK(std::size_t(resource(p.id(), GL_BUFFER_VARIABLE, var, GL_TOP_LEVEL_ARRAY_STRIDE)) == sizeof(gpu::FrameExtreme));
        const GLuint block = glGetProgramResourceIndex(p.id(), GL_SHADER_STORAGE_BLOCK, "Step");
        CHECK(resource(p.id(), GL_BUFFER_VARIABLE, var, GL_BLOCK_INDEX) == GLint(block));
    }
    CHECK(GLenum(resource(p.id(), GL_BUFFER_VARIABLE, glGetProgramResourceIndex(p.id(), GL_BUFFER_VARIABLE, "extreme[0].position"), GL_TYPE)) ==
          GL_FLOAT_VEC4);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("random values in the shared structs reach GLSL bit for bit, and the macros agree") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Distinct d(rng);

    gpu::LayoutProbe lp{};
    lp.m = d.m4();
    lp.v = d.v4();
    lp.u = d.u4();
    lp.f0 = d.f();
    lp.f1 = d.f();
    lp.u0 = d.u();
    lp.u1 = d.u();

    gpu::SimParams sp{};
    sp.gravity = d.v4();
    sp.domain_min = d.v4();
    sp.domain_max = d.v4();
    sp.dt = d.f();
    sp.restitution = d.f();
    sp.particle_radius = d.f();
    sp.particle_count = d.u();

    gpu::FrameParams fp{};
    fp.view = d.m4();
    fp.proj = d.m4();
    fp.view_proj = d.m4();
    fp.eye = d.v4();
    fp.light_dir = d.v4();
    fp.light_color = d.v4();
    fp.material = d.v4();
    fp.viewport = d.v4();
    fp.speed_scale = d.v4();
    fp.tank_min = d.v4();
    fp.tank_max = d.v4();

    gpu::GridParams gp{};
    gp.origin = d.v4();
    gp.dims = d.u4();
    gp.count = d.u();
    gp.morton = d.u();
    gp.key_max = d.u();
    gp.pad0 = d.u();

    gpu::SphParams hp{};
    hp.gravity = d.v4();
    hp.domain_min = d.v4();
    hp.domain_max = d.v4();
    for (float* f : {&hp.h, &hp.mass, &hp.rest_density, &hp.stiffness, &hp.viscosity, &hp.sound_speed, &hp.spacing,
                     &hp.cfl, &hp.force_factor, &hp.dt_max, &hp.dt_floor, &hp.density_limit, &hp.speed_limit})
        *f = d.f();
    hp.particle_count = d.u();
    hp.boundary_count = d.u();
    hp.front_band = d.f();
    hp.artificial_viscosity = d.f();
    hp.inv_h = d.f();
    hp.w_scale = d.f();
    hp.grad_scale = d.f();

    gpu::StepState st{};
    st.dt = d.f();
    st.time = d.f();
    st.frame_left = d.f();
    for (std::uint32_t* u : {&st.substeps_left, &st.max_speed, &st.max_accel, &st.frame_max_speed, &st.frame_max_density})
        *u = d.u();
    st.frame_min_dt = d.f();
    for (std::uint32_t* u : {&st.frame_substeps, &st.nan_count, &st.nan_index, &st.escaped_count, &st.escaped_index,
                             &st.speed_index, &st.density_index, &st.front, &st.frame, &st.steps, &st.live_count})
        *u = d.u();
    st.iterations = d.u4();
    st.unconverged = d.u4();
    st.error = d.v4();
    st.stable_dt = d.f();
    st.iteration_dt = d.f();
    st.issued = d.u();
    st.issued_divergence = d.u();
    st.speed_position = d.v4();
    st.density_position = d.v4();
    for (std::uint32_t* u : {&st.peak_error, &st.pad0, &st.pad1, &st.pad2}) *u = d.u();

    gpu::SubparticleParams pp{};
    pp.level_energy = d.v4();
    pp.energy_scale = d.v4();
    for (float* f : {&pp.spacing, &pp.beta, &pp.coherence_time, &pp.inv_sigma}) *f = d.f();
    pp.noise_lmax = std::int32_t(d.u());
    for (std::uint32_t* u : {&pp.tile_size, &pp.levels, &pp.budget, &pp.particle_count, &pp.pad0, &pp.pad1, &pp.pad2}) *u = d.u();

    gpu::SubparticleState ps{};
    for (glm::uvec4* u : {&ps.dispatch, &ps.draw, &ps.counts, &ps.offsets, &ps.limits}) *u = d.u4();

    gpu::DfsphParams dp{};
    for (float* f : {&dp.eta, &dp.eta_divergence, &dp.relaxation, &dp.warm_start}) *f = d.f();
    for (std::uint32_t* u : {&dp.min_iterations, &dp.min_divergence_iterations, &dp.issued, &dp.issued_divergence}) *u = d.u();
    dp.error_scale = d.f();
    dp.deficient_neighbours = d.u();
    dp.boundary_viscosity = d.f();
    dp.groups = d.u();
    dp.warm_start_divergence = d.f();
    dp.boundary_relaxation = d.f();
    dp.chebyshev = d.f();
    dp.complementarity_error = d.u();
    dp.shrink_step_above = d.u();
    dp.grow_step_below = d.u();
    dp.iteration_dt_min = d.f();
    dp.eta_peak = d.f();
    dp.stabilisation = d.f();
    for (std::uint32_t* u : {&dp.pad0, &dp.pad1, &dp.pad2}) *u = d.u();

    gpu::SolveState ss{};
    ss.dispatch = d.u4();
    for (std::uint32_t* u : {&ss.iterations, &ss.error_sum, &ss.groups_done, &ss.solve}) *u = d.u();
    ss.weight = d.f();
    for (std::uint32_t* u : {&ss.correct_groups, &ss.correct_y, &ss.correct_z, &ss.error_peak}) *u = d.u();
    ss.peak = d.f();
    for (std::uint32_t* u : {&ss.rows_groups, &ss.rows_y, &ss.rows_z, &ss.pad0, &ss.pad1, &ss.pad2}) *u = d.u();

    gpu::BoundaryRowsState rs{};
    rs.dispatch = d.u4();
    for (std::uint32_t* u : {&rs.rows, &rs.count, &rs.epoch, &rs.pad0}) *u = d.u();
    gpu::PbfParams bp{};
    for (float* f : {&bp.epsilon, &bp.s_corr_scale, &bp.s_corr_n, &bp.inv_w_dq, &bp.xsph, &bp.vorticity}) *f = d.f();
    bp.iterations = d.u();
    bp.warm_start = d.f();

    Words expect;
    expect.put(lp.m); expect.put(lp.v); expect.put(lp.u); expect.put(lp.f0); expect.put(lp.f1);
    expect.put(lp.u0); expect.put(lp.u1);
    const std::size_t probe_end = expect.w.size();
    expect.put(sp.gravity); expect.put(sp.domain_min); expect.put(sp.domain_max); expect.put(sp.dt);
    expect.put(sp.restitution); expect.put(sp.particle_radius); expect.put(sp.particle_count);
    const std::size_t sim_end = expect.w.size();
    expect.put(fp.view); expect.put(fp.proj); expect.put(fp.view_proj); expect.put(fp.eye);
    expect.put(fp.light_dir); expect.put(fp.light_color); expect.put(fp.material); expect.put(fp.viewport);
    expect.put(fp.speed_scale); expect.put(fp.tank_min); expect.put(fp.tank_max);
    const std::size_t frame_end = expect.w.size();
    expect.put(gp.origin); expect.put(gp.dims); expect.put(gp.count); expect.put(gp.morton); expect.put(gp.key_max);
    expect.put(gp.pad0);
    const std::size_t grid_end = expect.w.size();
    expect.put(hp.gravity); expect.put(hp.domain_min); expect.put(hp.domain_max); expect.put(hp.h); expect.put(hp.mass);
    expect.put(hp.rest_density); expect.put(hp.stiffness); expect.put(hp.viscosity); expect.put(hp.sound_speed);
    expect.put(hp.spacing); expect.put(hp.cfl); expect.put(hp.force_factor); expect.put(hp.dt_max);
    expect.put(hp.dt_floor); expect.put(hp.density_limit); expect.put(hp.speed_limit); expect.put(hp.particle_count);
    expect.put(hp.boundary_count); expect.put(hp.front_band); expect.put(hp.artificial_viscosity);
    expect.put(hp.inv_h); expect.put(hp.w_scale); expect.put(hp.grad_scale);
    const std::size_t sph_end = expect.w.size();
    expect.put(st.dt); expect.put(st.time); expect.put(st.frame_left); expect.put(st.substeps_left);
    expect.put(st.max_speed); expect.put(st.max_accel); expect.put(st.frame_max_speed); expect.put(st.frame_max_density);
    expect.put(st.frame_min_dt); expect.put(st.frame_substeps); expect.put(st.nan_count); expect.put(st.nan_index);
    expect.put(st.escaped_count); expect.put(st.escaped_index); expect.put(st.speed_index); expect.put(st.density_index);
    expect.put(st.front); expect.put(st.frame); expect.put(st.steps); expect.put(st.live_count);
    expect.put(st.iterations); expect.put(st.unconverged); expect.put(st.error);
    expect.put(st.stable_dt); expect.put(st.iteration_dt); expect.put(st.issued); expect.put(st.issued_divergence);
    expect.put(st.speed_position); expect.put(st.density_position);
    expect.put(st.peak_error); expect.put(st.pad0); expect.put(st.pad1); expect.put(st.pad2);
    const std::size_t step_end = expect.w.size();
    expect.put(pp.level_energy); expect.put(pp.energy_scale); expect.put(pp.spacing); expect.put(pp.beta);
    expect.put(pp.coherence_time); expect.put(pp.inv_sigma); expect.put(pp.noise_lmax); expect.put(pp.tile_size);
    expect.put(pp.levels); expect.put(pp.budget); expect.put(pp.particle_count); expect.put(pp.pad0); expect.put(pp.pad1);
    expect.put(pp.pad2);
    const std::size_t subp_end = expect.w.size();
    expect.put(ps.dispatch); expect.put(ps.draw); expect.put(ps.counts); expect.put(ps.offsets); expect.put(ps.limits);
    const std::size_t subs_end = expect.w.size();
    expect.put(dp.eta); expect.put(dp.eta_divergence); expect.put(dp.relaxation); expect.put(dp.warm_start);
    expect.put(dp.min_iterations); expect.put(dp.min_divergence_iterations); expect.put(dp.issued);
    expect.put(dp.issued_divergence); expect.put(dp.error_scale); expect.put(dp.deficient_neighbours);
    expect.put(dp.boundary_viscosity); expect.put(dp.groups); expect.put(dp.warm_start_divergence);
    expect.put(dp.boundary_relaxation); expect.put(dp.chebyshev); expect.put(dp.complementarity_error);
    expect.put(dp.shrink_step_above); expect.put(dp.grow_step_below); expect.put(dp.iteration_dt_min); expect.put(dp.eta_peak);
    expect.put(dp.stabilisation); expect.put(dp.pad0); expect.put(dp.pad1); expect.put(dp.pad2);
    const std::size_t dfsph_end = expect.w.size();
    expect.put(ss.dispatch); expect.put(ss.iterations); expect.put(ss.error_sum); expect.put(ss.groups_done);
    expect.put(ss.solve); expect.put(ss.weight); expect.put(ss.correct_groups); expect.put(ss.correct_y); expect.put(ss.correct_z);
    expect.put(ss.error_peak); expect.put(ss.peak); expect.put(ss.rows_groups); expect.put(ss.rows_y); expect.put(ss.rows_z);
    expect.put(ss.pad0); expect.put(ss.pad1); expect.put(ss.pad2);
    const std::size_t solve_end = expect.w.size();
    expect.put(rs.dispatch); expect.put(rs.rows); expect.put(rs.count); expect.put(rs.epoch); expect.put(rs.pad0);
    const std::size_t rows_end = expect.w.size();
    expect.put(bp.epsilon); expect.put(bp.s_corr_scale); expect.put(bp.s_corr_n); expect.put(bp.inv_w_dq);
    expect.put(bp.xsph); expect.put(bp.vorticity); expect.put(bp.iterations); expect.put(bp.warm_start);
    const std::size_t pbf_end = expect.w.size();
    for (const auto& [name, value] : kMacros) expect.put(value);
    // The word counts of probe_layout.comp's header: every member of each struct was put.
    REQUIRE(probe_end == 28);
    REQUIRE(sim_end - probe_end == sizeof(gpu::SimParams) / 4);
    REQUIRE(frame_end - sim_end == sizeof(gpu::FrameParams) / 4);
    REQUIRE(grid_end - frame_end == sizeof(gpu::GridParams) / 4);
    REQUIRE(sph_end - grid_end == sizeof(gpu::SphParams) / 4);
    REQUIRE(step_end - sph_end == sizeof(gpu::StepState) / 4);
    REQUIRE(subp_end - step_end == sizeof(gpu::SubparticleParams) / 4);
    REQUIRE(subs_end - subp_end == sizeof(gpu::SubparticleState) / 4);
    REQUIRE(dfsph_end - subs_end == sizeof(gpu::DfsphParams) / 4);
    REQUIRE(solve_end - dfsph_end == sizeof(gpu::SolveState) / 4);
    REQUIRE(rows_end - solve_end == sizeof(gpu::BoundaryRowsState) / 4);
    REQUIRE(pbf_end - rows_end == sizeof(gpu::PbfParams) / 4);

    // The output is pre-filled with a sentinel and is longer than the probe writes: the tail must
    // keep it, so the shader wrote exactly expect.w.size() words.
    constexpr std::uint32_t kSentinel = 0xDEADBEEFu;
    const std::size_t total = expect.w.size() + 8;
    const std::vector<std::uint32_t> fill(total, kSentinel);
    Buffer out = Buffer::from<std::uint32_t>(fill, GL_DYNAMIC_COPY, "probe.out");
    Buffer ubo_probe(sizeof lp, GL_DYNAMIC_DRAW, &lp, "probe.LayoutProbe");
    Buffer ubo_sim(sizeof sp, GL_DYNAMIC_DRAW, &sp, "probe.SimParams");
    Buffer ubo_frame(sizeof fp, GL_DYNAMIC_DRAW, &fp, "probe.FrameParams");
    Buffer ubo_grid(sizeof gp, GL_DYNAMIC_DRAW, &gp, "probe.GridParams");
    Buffer ubo_sph(sizeof hp, GL_DYNAMIC_DRAW, &hp, "probe.SphParams");
    Buffer ssbo_step(sizeof st, GL_DYNAMIC_DRAW, &st, "probe.StepState");
    Buffer ubo_subp(sizeof pp, GL_DYNAMIC_DRAW, &pp, "probe.SubparticleParams");
    Buffer ssbo_subs(sizeof ps, GL_DYNAMIC_DRAW, &ps, "probe.SubparticleState");
    Buffer ubo_dfsph(sizeof dp, GL_DYNAMIC_DRAW, &dp, "probe.DfsphParams");
    Buffer ssbo_solve(sizeof ss, GL_DYNAMIC_DRAW, &ss, "probe.SolveState");
    Buffer ssbo_rows(sizeof rs, GL_DYNAMIC_DRAW, &rs, "probe.BoundaryRowsState");
    Buffer ubo_pbf(sizeof bp, GL_DYNAMIC_DRAW, &bp, "probe.PbfParams");
    ubo_pbf.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_PBF);
    ubo_subp.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SUBPARTICLES);
    ubo_dfsph.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_DFSPH);
    ubo_probe.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_PROBE);
    ubo_sim.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SIM);
    ubo_frame.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_FRAME);
    ubo_grid.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_GRID);
    ubo_sph.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    probe().bind({{"Step", &ssbo_step}, {"SubparticleStateBlock", &ssbo_subs}, {"Solve", &ssbo_solve}, {"BoundaryRows", &ssbo_rows}, {"ProbeOut", &out}}).use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<std::uint32_t> got = out.read<std::uint32_t>(total);

    auto what = [&](std::size_t i) -> std::string {
        if (i < probe_end) return "LayoutProbe word " + std::to_string(i);
        if (i < sim_end) return "SimParams word " + std::to_string(i - probe_end);
        if (i < frame_end) return "FrameParams word " + std::to_string(i - sim_end);
        if (i < grid_end) return "GridParams word " + std::to_string(i - frame_end);
        if (i < sph_end) return "SphParams word " + std::to_string(i - grid_end);
        if (i < step_end) return "StepState word " + std::to_string(i - sph_end);
        if (i < subp_end) return "SubparticleParams word " + std::to_string(i - step_end);
        if (i < subs_end) return "SubparticleState word " + std::to_string(i - subp_end);
        if (i < dfsph_end) return "DfsphParams word " + std::to_string(i - subs_end);
        if (i < solve_end) return "SolveState word " + std::to_string(i - dfsph_end);
        if (i < rows_end) return "BoundaryRowsState word " + std::to_string(i - solve_end);
        if (i < pbf_end) return "PbfParams word " + std::to_string(i - rows_end);
        if (i < expect.w.size()) return kMacros[i - pbf_end].first;
        return "past the end, word " + std::to_string(i);
    };
    for (std::size_t i = 0; i < total; ++i) {
        INFO(what(i));
        CHECK(got[i] == (i < expect.w.size() ? expect.w[i] : kSentinel));
    }
    ranryu::test::require_no_gl_errors();
}
