#include "surface/level_set.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"

namespace ranryu::surface {

LevelSetSettings LevelSetSettings::for_spacing(float dx) {
    LevelSetSettings s;
    s.particle_spacing = dx;
    s.kernel_radius = 1.5f * dx;
    s.iso = iso_for_radius(dx, s.kernel_radius, 0.5f * dx);
    s.node_spacing = 0.5f * dx;
    s.max_dims = glm::uvec3(160u);
    s.search_margin = 0.5f * dx;
    s.anisotropy = AnisotropySettings::for_spacing(dx);
    return s;
}

double kernel_w(double r, double R) {   // glsl/sim/kernel.glsl, kernel_w
    const double pi = 3.14159265358979323846;
    const double q = r / R, k = 8.0 / (pi * R * R * R);
    if (q <= 0.5) return k * (6.0 * q * q * (q - 1.0) + 1.0);
    if (q <= 1.0) {
        const double t = 1.0 - q;
        return k * 2.0 * t * t * t;
    }
    return 0.0;
}

float iso_for_radius(float dx, float R, float r) { return float(double(dx) * dx * dx * kernel_w(r, R)); }

gpu::SurfaceParams surface_params(const LevelSetSettings& s, std::size_t particle_count) {
    gpu::SurfaceParams p{};
    p.max_dims = glm::uvec4(s.max_dims, 0u);
    p.node_spacing = s.node_spacing;
    p.kernel_radius = s.kernel_radius;
    p.volume = s.particle_spacing * s.particle_spacing * s.particle_spacing;
    p.iso = s.iso;
    p.particle_count = std::uint32_t(particle_count);
    p.search_margin = s.search_margin;
    p.bounds_margin = grid_margin(s);
    p.max_nodes = s.max_nodes;
    const AnisotropySettings& a = s.anisotropy;
    p.anisotropy = glm::vec4(a.radius, a.lambda, a.k_s, a.k_r);
    p.anisotropy_limits = glm::vec4(a.k_n, float(a.n_eps), a.max_stretch, 0.0f);
    return p;
}

float subparticle_kernel_radius(float R, int level, float h) {   // splat_subparticles.comp
    return level == 0 ? R : std::max(std::ldexp(R, -level), float(RANRYU_SUBPARTICLE_KERNEL_FLOOR) * h);
}

float subparticle_bounds_margin(const LevelSetSettings& s) {
    // Per axis a level-E child lies within (dx/2)(1 - 2^-E) (its lattice offset) + ½(dx/2^E)·4 (its
    // displacement at |ŷ_a| = 4) of its parent, and reaches R_E beyond (at the finest node spacing).
    constexpr float kDisplacement = 4.0f;
    const float dx = s.particle_spacing, R = s.kernel_radius;
    float margin = 0.0f;
    for (int E = 1; E <= s.subparticle_levels; ++E) {
        const float sub = std::ldexp(dx, -E);
        const float reach = 0.5f * (dx - sub) + 0.5f * sub * kDisplacement + subparticle_kernel_radius(R, E, s.node_spacing);
        margin = std::max(margin, reach - R);
    }
    return margin;
}

float grid_margin(const LevelSetSettings& s) {
    const float sub = subparticle_bounds_margin(s);
    return s.anisotropic ? std::max(sub, (s.anisotropy.max_stretch - 1.0f) * s.kernel_radius) : sub;
}

float grid_nodes(glm::vec3 lo, glm::vec3 hi, float h, glm::uvec3 max_dims) {   // place_grid.comp
    const glm::vec3 n = glm::min(glm::ceil((hi - h * glm::floor(lo / h)) / h) + 1.0f, glm::vec3(max_dims));
    return n.x * n.y * n.z;
}

std::uint32_t ordered_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float from_ordered_bits(std::uint32_t u) {
    u = (u & 0x80000000u) ? (u & 0x7FFFFFFFu) : ~u;
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

PhiGrid place_grid(glm::vec3 lo, glm::vec3 hi, const LevelSetSettings& s) {   // place_grid.comp
    const float reach = s.kernel_radius + grid_margin(s);
    lo -= reach;
    hi += reach;
    const glm::vec3 fit = (hi - lo) / (glm::vec3(s.max_dims) - 3.0f);
    float h = std::max(s.node_spacing, std::max(fit.x, std::max(fit.y, fit.z)));
    const float budget = float(s.max_nodes);
    if (s.max_nodes > 0 && grid_nodes(lo, hi, h, s.max_dims) > budget) {   // (S9)
        float small = h, big = 2.0f * h;
        for (int k = 0; k < 40 && grid_nodes(lo, hi, big, s.max_dims) > budget; ++k) big *= 2.0f;
        for (int k = 0; k < 20; ++k) {
            const float mid = 0.5f * (small + big);
            if (grid_nodes(lo, hi, mid, s.max_dims) > budget) small = mid;
            else big = mid;
        }
        h = big;
    }
    PhiGrid g;
    g.spacing = h;
    g.origin = h * glm::floor(lo / h);
    g.dims = glm::min(glm::uvec3(glm::ceil((hi - g.origin) / h)) + 1u, s.max_dims);
    return g;
}

void level_set_cpu(std::span<const glm::vec4> positions, const LevelSetSettings& s, PhiGrid& grid) {
    const double R = s.kernel_radius, V = double(s.particle_spacing) * s.particle_spacing * s.particle_spacing;
    grid.phi.assign(grid.nodes(), 0.0f);
    for (std::uint32_t k = 0; k < grid.dims.z; ++k)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t i = 0; i < grid.dims.x; ++i) {
                const glm::dvec3 x(grid.node({i, j, k}));
                double sum = 0.0;
                for (const glm::vec4& p : positions) {
                    const glm::dvec3 d = x - glm::dvec3(glm::vec3(p));
                    const double r2 = glm::dot(d, d);
                    if (r2 < R * R) sum += kernel_w(std::sqrt(r2), R);
                }
                grid.phi[grid.index({i, j, k})] = float(V * sum - s.iso);
            }
}

void level_set_cpu(std::span<const glm::vec4> positions, std::span<const std::uint32_t> levels,
                   std::span<const glm::vec4> children, const LevelSetSettings& s, PhiGrid& grid) {
    std::vector<glm::vec4> kept;
    for (std::size_t i = 0; i < positions.size(); ++i)
        if ((levels[i] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) == 0u) kept.push_back(positions[i]);
    level_set_cpu(kept, s, grid);
    const double V = double(s.particle_spacing) * s.particle_spacing * s.particle_spacing;
    std::vector<double> sum(grid.nodes(), 0.0);
    for (const glm::vec4& c : children) {
        const int E = int(c.w);
        const double R = subparticle_kernel_radius(s.kernel_radius, E, grid.spacing), w = std::ldexp(V, -3 * E);
        // The nodes of the box around the child's support, one node wider than needed on each side.
        const glm::dvec3 rel = (glm::dvec3(glm::vec3(c)) - glm::dvec3(grid.origin)) / double(grid.spacing);
        const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(rel - R / grid.spacing)) - 1, glm::ivec3(0));
        const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(rel + R / grid.spacing)) + 1, glm::ivec3(grid.dims) - 1);
        for (int k = lo.z; k <= hi.z; ++k)
            for (int j = lo.y; j <= hi.y; ++j)
                for (int i = lo.x; i <= hi.x; ++i) {
                    const glm::uvec3 n(i, j, k);
                    const glm::dvec3 d = glm::dvec3(grid.node(n)) - glm::dvec3(glm::vec3(c));
                    const double r2 = glm::dot(d, d);
                    if (r2 < R * R) sum[grid.index(n)] += w * kernel_w(std::sqrt(r2), R);
                }
    }
    for (std::size_t i = 0; i < sum.size(); ++i) grid.phi[i] = float(double(grid.phi[i]) + sum[i]);
}

void level_set_cpu(std::span<const ParticleAnisotropy> kernels, const LevelSetSettings& s, PhiGrid& grid) {
    const double R = s.kernel_radius, V = double(s.particle_spacing) * s.particle_spacing * s.particle_spacing;
    const double h = grid.spacing, floor_s = RANRYU_SUBPARTICLE_KERNEL_FLOOR * h / R;
    std::vector<double> sum(grid.nodes(), 0.0);
    for (const ParticleAnisotropy& k : kernels) {
        const glm::dvec3 st = glm::max(k.stretch, glm::dvec3(floor_s));
        const glm::dmat3 g = kernel_matrix(k.axes, k.stretch, floor_s);   // (S6)
        const double w = V / (st.x * st.y * st.z);
        // The nodes of the box around the ellipsoid (any box holding it gives the same sum), inner nodes only.
        const double reach = R * std::max(st.x, std::max(st.y, st.z));
        const glm::dvec3 rel = (k.centre - glm::dvec3(grid.origin)) / h;
        const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(rel - reach / h)) - 1, glm::ivec3(1));
        const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(rel + reach / h)) + 1, glm::ivec3(grid.dims) - 2);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) {
                    const glm::uvec3 n(x, y, z);
                    const double r = glm::length(g * (glm::dvec3(grid.node(n)) - k.centre));
                    if (r < R) sum[grid.index(n)] += w * kernel_w(r, R);   // (S7)
                }
    }
    grid.phi.resize(grid.nodes());
    for (std::size_t i = 0; i < sum.size(); ++i) grid.phi[i] = float(sum[i] - double(s.iso));
}

namespace {
std::size_t node_capacity(const LevelSetSettings& s) {
    const std::size_t dims = std::size_t(s.max_dims.x) * s.max_dims.y * s.max_dims.z;
    return s.max_nodes > 0 ? std::min<std::size_t>(dims, s.max_nodes) : dims;
}
}  // namespace

std::size_t LevelSet::bytes_for(const LevelSetSettings& s) {
    const std::size_t nodes = node_capacity(s);
    return sizeof(gpu::SurfaceParams) + sizeof(gpu::SurfaceGrid) + nodes * sizeof(float) +
           (s.subparticle_levels > 0 || s.anisotropic ? nodes * sizeof(std::uint32_t) : 0) +   // phi, the splat grid
           (s.anisotropic ? 3 * s.particle_capacity * sizeof(glm::vec4) : 0);                   // centres, axes
}

LevelSet::LevelSet(const shader::FileSource& shaders, profile::GpuTimer& timer, const LevelSetSettings& settings)
    : timer_(timer),
      bounds_pass_(timer.pass("surface.bounds")),
      place_grid_pass_(timer.pass("surface.place-grid", bounds_pass_)),
      level_set_pass_(timer.pass("level-set")),
      find_bounds_(shader::Program::compute(shaders, "surface/find_bounds.comp")),
      place_grid_(shader::Program::compute(shaders, "surface/place_grid.comp")),
      compute_(shader::Program::compute(shaders, "surface/compute_level_set.comp",
                                        std::string(settings.subparticle_levels > 0 ? "#define RANRYU_SUBPARTICLES 1\n" : "") +
                                            (settings.anisotropic ? "#define RANRYU_SPLATTED 1\n" : ""))),
      settings_(settings),
      max_nodes_(node_capacity(settings)) {
    const auto& s = settings;
    if (!(s.particle_spacing > 0.0f) || !(s.kernel_radius > 0.0f) || !(s.node_spacing > 0.0f) || !std::isfinite(s.iso) ||
        !(s.search_margin >= 0.0f))
        throw InputError("surface: particle spacing, kernel radius and node spacing must be positive, iso finite, "
                         "search margin not negative");
    if (glm::any(glm::lessThan(s.max_dims, glm::uvec3(4u))) || max_nodes_ > (std::size_t(1) << 30))
        throw InputError("surface: the level set grid needs 4 to 1024^3 nodes in all, at least 4 per axis (max dims " +
                         std::to_string(s.max_dims.x) + "x" + std::to_string(s.max_dims.y) + "x" +
                         std::to_string(s.max_dims.z) + ")");
    if (s.max_nodes != 0 && s.max_nodes < 64) throw InputError("surface: a node budget needs at least 64 nodes");
    const AnisotropySettings& a = s.anisotropy;
    if (s.anisotropic && (s.particle_capacity == 0 || !(a.radius > 0.0f) || !(a.lambda >= 0.0f && a.lambda <= 1.0f) ||
                          !(a.k_s > 0.0f) || !(a.k_r >= 1.0f) || !(a.k_n > 0.0f) || !(a.max_stretch >= 1.0f)))
        throw InputError("surface: anisotropic kernels need a particle capacity, r > 0, λ in [0, 1], k_s > 0, k_r >= 1, "
                         "k_n > 0 and s_max >= 1");
    params_ = gl::Buffer(sizeof(gpu::SurfaceParams), GL_DYNAMIC_DRAW, nullptr, "SurfaceParams");
    const gpu::SurfaceGrid empty{};
    grid_ = gl::Buffer(sizeof(gpu::SurfaceGrid), GL_DYNAMIC_COPY, &empty, "surface.grid");
    phi_ = gl::Buffer(max_nodes_ * sizeof(float), GL_DYNAMIC_COPY, nullptr, "surface.phi");
    const auto group = compute_.local_size();
    glProgramUniform4ui(place_grid_.id(), RANRYU_LOC_SURFACE_GROUP, group[0], group[1], group[2], 0u);
    if (s.anisotropic) {
        anisotropy_pass_ = timer.pass("surface.anisotropy");
        particle_splat_pass_ = timer.pass("level-set.splat");
        anisotropy_ = shader::Program::compute(shaders, "surface/compute_anisotropy.comp");
        particle_splat_ = shader::Program::compute(shaders, "surface/splat_particles.comp",
                                                   s.subparticle_levels > 0 ? "#define RANRYU_SUBPARTICLES 1\n" : "");
        centres_ = gl::Buffer(s.particle_capacity * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "surface.centres");
        axes_ = gl::Buffer(2 * s.particle_capacity * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "surface.axes");
    }
    if (s.subparticle_levels > 0) {
        splat_pass_ = timer.pass("subparticles.splat");
        splat_ = shader::Program::compute(shaders, "surface/splat_subparticles.comp");
    }
    if (s.subparticle_levels > 0 || s.anisotropic) {
        // All zero from here on: the level-set pass sets every node it reads back to 0.
        const std::vector<std::uint32_t> zero(max_nodes_, 0u);
        splat_grid_ = gl::Buffer::from<std::uint32_t>(zero, GL_DYNAMIC_COPY, "surface.splat");
    }
}

void LevelSet::compute(sim::NeighbourGrid& grid, const gl::Buffer& sorted_position, const sim::CellRanges& ranges,
                       std::size_t count, const SubparticleSurface* sub) {
    if ((settings_.subparticle_levels > 0) != (sub != nullptr))
        throw Error(sub ? "LevelSet::compute: sub-particles given to a level set built without them"
                        : "LevelSet::compute: this level set was built for sub-particles; pass them");
    if (sub && sub->dispatch_group != splat_.local_size()[0])
        throw Error("LevelSet::compute: splat_subparticles.comp must have the spawn pass's local size");
    if (params_count_ != count) {   // the settings are fixed; only the count changes
        params_.upload_value(surface_params(settings_, count));
        params_count_ = count;
    }
    grid.bind_params(count);
    params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SURFACE);
    shader::StorageSet buffers{{"Positions", &sorted_position},
                               {"SurfaceGridState", &grid_},
                               {"CellRange", &ranges.cells},
                               {"SortedKeys", &grid.sort().sorted_keys()},   // validates ranges
                               {"Phi", &phi_},
                               {"SplatGrid", &splat_grid_}};
    if (sub)
        buffers.add("Subparticles", sub->state).add("SubparticlePositions", sub->positions).add("SubparticleLevels", sub->levels);
    if (settings_.anisotropic) {
        if (count > settings_.particle_capacity)
            throw Error("LevelSet::compute: " + std::to_string(count) + " particles, more than the capacity " +
                        std::to_string(settings_.particle_capacity));
        buffers.add("SurfaceCentres", centres_).add("SurfaceAxes", axes_);
        auto pass = timer_.scope(anisotropy_pass_);
        anisotropy_.bind(buffers).dispatch(count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(bounds_pass_);
        // bounds_min = identity of min, bounds_max = identity of max (bytes 32..63 of SurfaceGrid).
        const GLuint all_ones = 0xFFFFFFFFu, zero = 0u;
        glBindBuffer(GL_COPY_WRITE_BUFFER, grid_.id());
        glClearBufferSubData(GL_COPY_WRITE_BUFFER, GL_R32UI, offsetof(gpu::SurfaceGrid, bounds_min),
                             sizeof(glm::uvec4), GL_RED_INTEGER, GL_UNSIGNED_INT, &all_ones);
        glClearBufferSubData(GL_COPY_WRITE_BUFFER, GL_R32UI, offsetof(gpu::SurfaceGrid, bounds_max),
                             sizeof(glm::uvec4), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        // With anisotropic kernels, the box of the smoothed centres (the kernels' centres).
        find_bounds_.bind(settings_.anisotropic ? buffers.with("Positions", centres_) : buffers).dispatch(count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        auto within = timer_.scope(place_grid_pass_);
        place_grid_.bind(buffers).use();
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
    if (sub) {
        auto pass = timer_.scope(splat_pass_);
        splat_.bind(buffers).use();
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, sub->state.id());
        glDispatchComputeIndirect(GLintptr(sub->dispatch_offset));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    if (settings_.anisotropic) {
        auto pass = timer_.scope(particle_splat_pass_);
        particle_splat_.bind(buffers).dispatch(count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(level_set_pass_);
        compute_.bind(buffers).use();
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, grid_.id());
        glDispatchComputeIndirect(GLintptr(offsetof(gpu::SurfaceGrid, dispatch)));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

}  // namespace ranryu::surface
