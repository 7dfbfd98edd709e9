#include "turbulence/subparticles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/error.h"
#include "sim/fluid.h"
#include "turbulence/force.h"

namespace ranryu::turbulence {
namespace {

// 3-point Gauss-Legendre on [-½, ½]: exact for polynomials of degree <= 5.
const double kGaussOffset[3] = {-0.5 * std::sqrt(0.6), 0.0, 0.5 * std::sqrt(0.6)};
constexpr double kGaussWeight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

// One axis of a tile's quadratic B-spline (curl_noise's weights) evaluated at the 3 Gauss points of
// each of its n pieces [k - ½, k + ½]: out[3k + g] = Σ_f in[k - 1 + f]·F_f(t), t = ½ - offset_g,
// F = W (the value) or D (the derivative). `in` and `out` are strided lines of a 3-D array.
void filter_line(const double* in, std::size_t in_stride, double* out, std::size_t out_stride, int n, bool derivative) {
    for (int k = 0; k < n; ++k)
        for (int g = 0; g < 3; ++g) {
            const double t = 0.5 - kGaussOffset[g];
            const double w0 = 0.5 * t * t, w2 = 0.5 * (1.0 - t) * (1.0 - t), w1 = 1.0 - w0 - w2;
            const double f[3] = {derivative ? -t : w0, derivative ? 2.0 * t - 1.0 : w1, derivative ? 1.0 - t : w2};
            double s = 0.0;
            for (int j = 0; j < 3; ++j) s += f[j] * in[std::size_t((k - 1 + j + n) % n) * in_stride];
            out[std::size_t(3 * k + g) * out_stride] = s;
        }
}

// ∂N/∂(axis) of one tile at every point of the (3n)³ Gauss lattice, index x + 3n·(y + 3n·z).
std::vector<double> derivative_on_gauss_lattice(const std::vector<float>& tile, int n, int axis) {
    const std::size_t N = std::size_t(n), M = 3 * N;
    std::vector<double> a(tile.begin(), tile.end()), b(M * N * N), c(M * M * N), d(M * M * M);
    for (std::size_t z = 0; z < N; ++z)   // x: (n, n, n) -> (3n, n, n)
        for (std::size_t y = 0; y < N; ++y) filter_line(&a[N * (y + N * z)], 1, &b[M * (y + N * z)], 1, n, axis == 0);
    for (std::size_t z = 0; z < N; ++z)   // y: -> (3n, 3n, n)
        for (std::size_t x = 0; x < M; ++x) filter_line(&b[x + M * N * z], M, &c[x + M * M * z], M, n, axis == 1);
    for (std::size_t y = 0; y < M; ++y)   // z: -> (3n, 3n, 3n)
        for (std::size_t x = 0; x < M; ++x) filter_line(&c[x + M * y], M * M, &d[x + M * y], M * M, n, axis == 2);
    return d;
}

}  // namespace

glm::vec4 level_energies(float threshold, float beta, int levels) {
    glm::vec4 e(std::numeric_limits<float>::infinity());
    for (int k = 0; k < std::min(levels, kMaxSubparticleLevel); ++k)
        e[k] = float(double(threshold) * std::exp2(2.0 * double(beta) * k));
    return e;
}

int raw_level(float e, const glm::vec4& level_energy, int levels) {
    const int L = int(e >= level_energy.x) + int(e >= level_energy.y) + int(e >= level_energy.z);
    return std::min(L, levels);
}

glm::vec4 energy_scales(float beta) {
    glm::vec4 s(0.0f);
    for (int E = 1; E <= kMaxSubparticleLevel; ++E) s[E - 1] = float(std::exp2(-2.0 * double(beta) * E));
    return s;
}

LevelCap choose_level_cap(const std::array<std::uint64_t, 3>& counts, int levels, std::uint64_t budget) {
    auto need = [&](int C) {
        std::uint64_t total = 0;
        for (int L = 1; L <= kMaxSubparticleLevel; ++L) total += counts[L - 1] << (3 * std::min(L, C));
        return total;
    };
    LevelCap r;
    for (int L = 1; L <= kMaxSubparticleLevel; ++L)
        if (counts[L - 1] > 0) r.finest = L;
    r.wanted = need(levels);
    for (int C = levels; C >= 1; --C)
        if (need(C) <= budget) {
            r.cap = C;
            r.total = need(C);
            break;
        }
    return r;
}

float octave_rms(const NoiseTiles& tiles) {
    // w = ∇×N = (∂y N3 - ∂z N2, ∂z N1 - ∂x N3, ∂x N2 - ∂y N1) (curl_noise). Within each piece of the
    // spline, w is a polynomial of degree <= 2 per axis, |w|² of degree <= 4: the 3-point Gauss rule
    // per axis integrates it exactly, so this is the rms over the whole (periodic) tile, exactly.
    const int n = tiles.n;
    const std::size_t points = std::size_t(27) * std::size_t(n) * n * n, M = 3 * std::size_t(n);
    const int pairs[3][4] = {{2, 1, 1, 2}, {0, 2, 2, 0}, {1, 0, 0, 1}};   // (tile, axis) - (tile, axis)
    double sum = 0.0;
    for (const auto& p : pairs) {
        const std::vector<double> a = derivative_on_gauss_lattice(tiles.tile[std::size_t(p[0])], n, p[1]);
        const std::vector<double> b = derivative_on_gauss_lattice(tiles.tile[std::size_t(p[2])], n, p[3]);
        for (std::size_t i = 0; i < points; ++i) {
            const std::size_t x = i % M, y = (i / M) % M, z = i / (M * M);
            const double d = a[i] - b[i];
            sum += kGaussWeight[x % 3] * kGaussWeight[y % 3] * kGaussWeight[z % 3] * d * d;
        }
    }
    return float(std::sqrt(sum / (double(n) * n * n)));
}

glm::vec3 lattice_offset(std::uint32_t child, int level, float dx) {
    // Keep in step with lattice_offset() in glsl/turbulence/subparticles/spawn_subparticles.comp.
    glm::vec3 o(0.0f);
    for (int l = 1; l <= level; ++l) {
        const std::uint32_t digit = (child >> (3 * (l - 1))) & 7u;
        const glm::vec3 b(float(digit & 1u), float((digit >> 1) & 1u), float((digit >> 2) & 1u));
        o += std::ldexp(dx, -l) * (b - 0.5f);
    }
    return o;
}

Subparticle spawn_subparticle(const NoiseTiles& tiles, const gpu::SubparticleParams& p, glm::vec3 x, glm::vec3 v, float e,
                              const gpu::NoiseSeed& seed, std::uint32_t child, int level, float t) {
    const float dx = p.spacing;
    const glm::vec3 o = lattice_offset(child, level, dx);
    const float eE = e * p.energy_scale[level - 1];
    const int octave = p.noise_lmax + level;
    const glm::vec3 y = carried_noise(tiles, seed, o, t, p.coherence_time, octave, octave, p.beta) * p.inv_sigma;
    return {glm::vec4(x + o + (0.5f * std::ldexp(dx, -level)) * y, float(level)), glm::vec4(v + std::sqrt(2.0f * eE) * y, eE)};
}

std::string budget_note(const SubparticleStats& s) {
    if (s.dropped_frames == 0) return "";
    return "sub-particles: budget " + std::to_string(s.budget) + " exceeded in " + std::to_string(s.dropped_frames) + " of " +
           std::to_string(s.frames) + " frames, finest level dropped to " + std::to_string(s.lowest_cap) + " (levels up to " +
           std::to_string(s.finest_wanted) + " wanted)";
}

std::size_t Subparticles::capacity_for(const scene::SubparticleSettings& s, std::size_t particles) {
    return std::min<std::size_t>(std::size_t(s.budget), particles << (3 * s.levels));
}

Subparticles::Sizes Subparticles::sizes(const scene::SubparticleSettings& s, std::size_t particles, std::size_t group) {
    const std::size_t n = std::max<std::size_t>(particles, 1), blocks = (particles + group - 1) / group;
    return Sizes{n * sizeof(std::uint32_t), std::max<std::size_t>(blocks, 1) * sizeof(glm::uvec4),
                 n * std::size_t(s.levels) * sizeof(std::uint32_t),
                 std::max<std::size_t>(capacity_for(s, particles), 1) * sizeof(glm::vec4)};
}

std::size_t Subparticles::bytes_for(const scene::SubparticleSettings& s, std::size_t particles) {
    // classify_particles.comp's local size (the constructor reads it from the program).
    const Sizes z = sizes(s, particles, 256);
    return sizeof(gpu::SubparticleParams) + sizeof(gpu::SubparticleState) + z.levels + z.blocks + z.lists + 2 * z.children;
}

Subparticles::Subparticles(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::TurbulenceSettings& settings,
                           float spacing, std::size_t particles, const NoiseTiles& tiles, const CurlNoise& noise)
    : timer_(timer),
      classify_pass_(timer.pass("subparticles.classify")),
      scan_pass_(timer.pass("subparticles.scan")),
      compact_pass_(timer.pass("subparticles.compact")),
      budget_pass_(timer.pass("subparticles.budget")),
      spawn_pass_(timer.pass("subparticles.spawn")),
      classify_(shader::Program::compute(shaders, "turbulence/subparticles/classify_particles.comp")),
      scan_(shader::Program::compute(shaders, "turbulence/subparticles/scan_level_counts.comp")),
      compact_(shader::Program::compute(shaders, "turbulence/subparticles/compact_split_particles.comp")),
      budget_(shader::Program::compute(shaders, "turbulence/subparticles/choose_level_cap.comp")),
      spawn_(shader::Program::compute(shaders, "turbulence/subparticles/spawn_subparticles.comp")),
      noise_(noise),
      max_particles_(particles),
      readback_(sizeof(gpu::SubparticleState), 4, "subparticles.readback",
                [this](std::uint64_t frame, const void* bytes) { on_record(frame, bytes); }) {
    const scene::SubparticleSettings& s = settings.subparticles;
    if (s.levels < 1 || s.levels > kMaxSubparticleLevel || !(spacing > 0.0f) || !(s.threshold > 0.0f) || s.budget < 1)
        throw InputError("sub-particles: levels must be 1.." + std::to_string(kMaxSubparticleLevel) +
                         ", the spacing and threshold positive and the budget at least 1");
    if (classify_.local_size()[0] != compact_.local_size()[0])
        throw Error("sub-particles: classify_particles.comp and compact_split_particles.comp must have the same local size");
    const std::size_t group = classify_.local_size()[0], blocks = (particles + group - 1) / group;
    // One-dimensional dispatches over the particles: at most 65,535 workgroups (GL 4.3's minimum).
    if (blocks > 65535 || particles >= (std::size_t(1) << 32) / std::size_t(s.levels))
        throw Error("sub-particles: " + std::to_string(particles) + " particles need more than 65,535 workgroups of " +
                    std::to_string(group));
    capacity_ = capacity_for(s, particles);

    params_.level_energy = level_energies(s.threshold, settings.beta, s.levels);
    params_.energy_scale = energy_scales(settings.beta);
    params_.spacing = spacing;
    params_.beta = settings.beta;
    params_.coherence_time = settings.coherence_time;
    params_.inv_sigma = 1.0f / octave_rms(tiles);
    params_.noise_lmax = settings.lmax;
    params_.tile_size = std::uint32_t(tiles.n);
    params_.levels = std::uint32_t(s.levels);
    params_.budget = std::uint32_t(capacity_);
    params_.particle_count = 0;

    params_ubo_ = gl::Buffer(sizeof params_, GL_DYNAMIC_DRAW, &params_, "SubparticleParams");
    const gpu::SubparticleState empty{};
    state_ = gl::Buffer(sizeof empty, GL_DYNAMIC_COPY, &empty, "subparticles.state");
    const Sizes z = sizes(s, particles, group);
    levels_ = gl::Buffer(z.levels, GL_DYNAMIC_COPY, nullptr, "subparticles.levels");
    blocks_ = gl::Buffer(z.blocks, GL_DYNAMIC_COPY, nullptr, "subparticles.blocks");
    lists_ = gl::Buffer(z.lists, GL_DYNAMIC_COPY, nullptr, "subparticles.lists");
    positions_ = gl::Buffer(z.children, GL_DYNAMIC_COPY, nullptr, "subparticles.position");
    velocities_ = gl::Buffer(z.children, GL_DYNAMIC_COPY, nullptr, "subparticles.velocity");
    stats_.budget = std::uint32_t(capacity_);

    const GLuint spawn_group = spawn_.local_size()[0];
    for (const shader::Program* p : {&scan_, &budget_})
        glProgramUniform4ui(p->id(), RANRYU_LOC_SUBPARTICLE_GROUP, GLuint(group), spawn_group, 1u, 0u);
}

void Subparticles::generate(const Inputs& in, std::uint64_t frame) {
    if (in.count > max_particles_)
        throw Error("Subparticles::generate: " + std::to_string(in.count) + " particles, built for " +
                    std::to_string(max_particles_));
    if (params_.particle_count != in.count) {   // the settings are fixed; only the count changes
        params_.particle_count = std::uint32_t(in.count);
        params_ubo_.upload_value(params_);
    }
    params_ubo_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SUBPARTICLES);
    const shader::StorageSet buffers{{"Positions", &in.positions},
                                     {"Velocities", &in.velocities},
                                     {"WaveletEnergy", &in.energy},
                                     {"NoiseSeeds", &in.seeds},
                                     {"Step", &in.step},
                                     {"NoiseTiles", &noise_.tiles()},
                                     {"Subparticles", &state_},
                                     {"SubparticleLevels", &levels_},
                                     {"SubparticleBlocks", &blocks_},
                                     {"SubparticleLists", &lists_},
                                     {"SubparticlePositions", &positions_},
                                     {"SubparticleVelocities", &velocities_}};
    {
        auto pass = timer_.scope(classify_pass_);
        classify_.bind(buffers).dispatch(in.count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(scan_pass_);
        scan_.bind(buffers).use();
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(compact_pass_);
        compact_.bind(buffers).dispatch(in.count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(budget_pass_);
        budget_.bind(buffers).use();
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        readback_.copy(state_, 0, frame);   // the stats, back frames late
    }
    {
        auto pass = timer_.scope(spawn_pass_);
        spawn_.bind(buffers).use();
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, state_.id());
        glDispatchComputeIndirect(GLintptr(dispatch_offset));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        // The level set's splat and gather, the impostor draw (vertex attributes and its indirect
        // arguments) read what this wrote.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
}

void Subparticles::generate(const sim::Fluid& fluid, const TurbulenceForce& force, std::uint64_t frame) {
    generate(Inputs{fluid.positions(), fluid.velocities(), force.wavelet().energy(), force.noise_seeds(), fluid.step_state(),
                    fluid.count()},
             frame);
}

void Subparticles::count_from(std::uint64_t frame) {
    count_from_ = frame;
    const std::uint32_t budget = stats_.budget;
    stats_ = SubparticleStats{};
    stats_.budget = budget;
}

void Subparticles::on_record(std::uint64_t frame, const void* bytes) {
    gpu::SubparticleState s;
    std::memcpy(&s, bytes, sizeof s);
    if (frame < count_from_) return;
    stats_.last = s;
    ++stats_.frames;
    stats_.most = std::max<std::uint64_t>(stats_.most, s.dispatch.w);
    const int cap = int(s.limits.x), finest = int(s.limits.y);
    if (cap < finest) {
        ++stats_.dropped_frames;
        stats_.lowest_cap = std::min(stats_.lowest_cap, cap);
        stats_.finest_wanted = std::max(stats_.finest_wanted, finest);
    }
}

}  // namespace ranryu::turbulence
