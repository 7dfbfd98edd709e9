#include "surface/marching_cubes.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "surface/mc_tables.h"

namespace ranryu::surface {
namespace {

constexpr int kTriangles[4096] = {RANRYU_MC_TRIANGLES};
constexpr int kCorners[24] = {RANRYU_MC_CORNERS};
constexpr int kEdges[24] = {RANRYU_MC_EDGES};

// The cell passes dispatch 2-D (glsl/surface/dispatch_2d.glsl): rows of capacity.groups_x workgroups,
// at most 65535 rows (GL 4.3's guaranteed minimum per dimension); the last row pads up to a row.
std::string dispatch_defines(const MeshCapacity& c) {
    if (c.groups_x < 1 || c.groups_x > 65535) throw Error("marching cubes: groups_x must be in [1, 65535]");
    return "#define RANRYU_MC_GROUPS_X " + std::to_string(c.groups_x) + "u\n";
}

glm::ivec3 corner(int c) { return {kCorners[3 * c], kCorners[3 * c + 1], kCorners[3 * c + 2]}; }

float phi_clamped(const PhiGrid& g, glm::ivec3 n) { return g.at(glm::uvec3(glm::clamp(n, glm::ivec3(0), glm::ivec3(g.dims) - 1))); }

// ∇φ at a node, smoothed (docs/SURFACE.md (S8)), as gradient() in mc_emit.comp: the same stencil, sums
// and order.
glm::vec3 gradient(const PhiGrid& g, glm::ivec3 n) {
    constexpr float across[3] = {0.25f, 0.5f, 0.25f};
    glm::vec3 out;
    for (int a = 0; a < 3; ++a) {
        glm::ivec3 e(0), eb(0), ec(0);
        e[a] = 1;
        eb[(a + 1) % 3] = 1;
        ec[(a + 2) % 3] = 1;
        float sum = 0.0f;
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                const glm::ivec3 m = n + j * eb + k * ec;
                const float near = phi_clamped(g, m + e) - phi_clamped(g, m - e);
                const float far = phi_clamped(g, m + 2 * e) - phi_clamped(g, m - 2 * e);
                sum += across[j + 1] * across[k + 1] * (10.0f * near + far);
            }
        out[a] = sum / (24.0f * g.spacing);
    }
    return out;
}

void set_capacity(const shader::Program& p, std::size_t vertices, std::size_t active, std::size_t cells) {
    glProgramUniform4ui(p.id(), RANRYU_LOC_SURFACE_CAPACITY, GLuint(vertices), GLuint(active), GLuint(cells), 0u);
}

}  // namespace

std::span<const int, 4096> mc_triangle_table() { return std::span<const int, 4096>(kTriangles); }
std::span<const int, 24> mc_corner_table() { return std::span<const int, 24>(kCorners); }
std::span<const int, 24> mc_edge_table() { return std::span<const int, 24>(kEdges); }

std::size_t MeshCapacity::cells() const {
    const std::size_t all = std::size_t(max_dims.x - 1) * (max_dims.y - 1) * (max_dims.z - 1);
    return max_nodes > 0 ? std::min(all, max_nodes) : all;
}

std::size_t MarchingCubes::bytes_for(const MeshCapacity& capacity) {
    const std::size_t cells = capacity.cells(), active = std::min(cells, capacity.max_vertices / 3);
    const std::size_t blocks = (cells + 255) / 256 + capacity.groups_x;   // mc_classify.comp's local size, 256
    return sizeof(gpu::MeshState) + cells * sizeof(std::uint32_t) + blocks * sizeof(glm::uvec2) +
           std::max<std::size_t>(active, 1) * sizeof(glm::uvec2) + capacity.max_vertices * sizeof(gpu::MeshVertex) +
           sizeof kTriangles;
}

MarchingCubes::MarchingCubes(const shader::FileSource& shaders, profile::GpuTimer& timer, const MeshCapacity& capacity)
    : timer_(timer),
      classify_pass_(timer.pass("mc.classify")),
      compact_pass_(timer.pass("mc.compact")),
      emit_pass_(timer.pass("mc.emit")),
      setup_pass_(timer.pass("mc.setup", classify_pass_)),
      scan_pass_(timer.pass("mc.scan", compact_pass_)),
      setup_(shader::Program::compute(shaders, "surface/mc_setup.comp", dispatch_defines(capacity))),
      classify_(shader::Program::compute(shaders, "surface/mc_classify.comp", dispatch_defines(capacity))),
      scan_(shader::Program::compute(shaders, "surface/mc_scan_blocks.comp", dispatch_defines(capacity))),
      compact_(shader::Program::compute(shaders, "surface/mc_compact.comp", dispatch_defines(capacity))),
      emit_(shader::Program::compute(shaders, "surface/mc_emit.comp", dispatch_defines(capacity))) {
    const glm::uvec3 d = capacity.max_dims;
    if (glm::any(glm::lessThan(d, glm::uvec3(2u))) || capacity.max_vertices < 3)
        throw Error("marching cubes: capacity needs at least 2 nodes per axis and 3 vertices");
    max_cells_ = capacity.cells();
    max_vertices_ = capacity.max_vertices;
    max_active_ = std::min(max_cells_, max_vertices_ / 3);
    const std::size_t block = classify_.local_size()[0];
    if (compact_.local_size()[0] != block)
        throw Error("marching cubes: mc_classify.comp and mc_compact.comp must have the same local size");
    max_blocks_ = (max_cells_ + block - 1) / block + capacity.groups_x;   // with the last row's padding
    const std::size_t kMaxGroups = std::size_t(capacity.groups_x) * 65535;
    const std::size_t emit_group = emit_.local_size()[0];
    if (max_blocks_ > kMaxGroups || (max_active_ + emit_group - 1) / emit_group > kMaxGroups || max_cells_ >= (1u << 31))
        throw Error("marching cubes: " + std::to_string(max_cells_) + " cells or " + std::to_string(max_active_) +
                    " active cells need more workgroups than a dispatch holds; lower max_dims or max_vertices");

    state_ = gl::Buffer(sizeof(gpu::MeshState), GL_DYNAMIC_COPY, nullptr, "mc.state");
    cell_vertices_ = gl::Buffer(max_cells_ * sizeof(std::uint32_t), GL_DYNAMIC_COPY, nullptr, "mc.cell_vertices");
    blocks_ = gl::Buffer(max_blocks_ * sizeof(glm::uvec2), GL_DYNAMIC_COPY, nullptr, "mc.blocks");
    active_ = gl::Buffer(std::max<std::size_t>(max_active_, 1) * sizeof(glm::uvec2), GL_DYNAMIC_COPY, nullptr, "mc.active");
    vertices_ = gl::Buffer(max_vertices_ * sizeof(gpu::MeshVertex), GL_DYNAMIC_COPY, nullptr, "mc.vertices");
    triangles_ = gl::Buffer(sizeof kTriangles, GL_STATIC_DRAW, kTriangles, "mc.triangle_table");

    for (const shader::Program* p : {&setup_, &scan_, &compact_, &emit_}) set_capacity(*p, max_vertices_, max_active_, max_cells_);
    glProgramUniform4ui(setup_.id(), RANRYU_LOC_SURFACE_GROUP, GLuint(block), 1u, 1u, 0u);
    glProgramUniform4ui(scan_.id(), RANRYU_LOC_SURFACE_GROUP, GLuint(emit_group), 1u, 1u, 0u);
}

void MarchingCubes::polygonise(const gl::Buffer& phi, const gl::Buffer& grid) {
    const shader::StorageSet buffers{{"SurfaceGridState", &grid},         {"Phi", &phi},
                                     {"Mesh", &state_},         {"CellVertices", &cell_vertices_},
                                     {"McBlocks", &blocks_},         {"ActiveCells", &active_},
                                     {"MeshVertices", &vertices_},   {"McTriangles", &triangles_}};
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, state_.id());
    {
        auto pass = timer_.scope(classify_pass_);
        {
            auto within = timer_.scope(setup_pass_);
            setup_.bind(buffers).use();
            glDispatchCompute(1, 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        }
        classify_.bind(buffers).use();
        glDispatchComputeIndirect(GLintptr(offsetof(gpu::MeshState, cell_dispatch)));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(compact_pass_);
        {
            auto within = timer_.scope(scan_pass_);
            scan_.bind(buffers).use();
            glDispatchCompute(1, 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        }
        compact_.bind(buffers).use();
        glDispatchComputeIndirect(GLintptr(offsetof(gpu::MeshState, cell_dispatch)));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto pass = timer_.scope(emit_pass_);
        emit_.bind(buffers).use();
        glDispatchComputeIndirect(GLintptr(offsetof(gpu::MeshState, emit_dispatch)));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

std::vector<gpu::MeshVertex> polygonise_cpu(const PhiGrid& g) {
    std::vector<gpu::MeshVertex> out;
    if (glm::any(glm::lessThan(g.dims, glm::uvec3(2u)))) return out;
    const glm::uvec3 cells = g.dims - 1u;
    for (std::uint32_t k = 0; k < cells.z; ++k)
        for (std::uint32_t j = 0; j < cells.y; ++j)
            for (std::uint32_t i = 0; i < cells.x; ++i) {
                const glm::ivec3 cell(i, j, k);
                float f[8];
                int index = 0;
                for (int c = 0; c < 8; ++c) {
                    f[c] = g.at(glm::uvec3(cell + corner(c)));
                    if (f[c] < 0.0f) index |= 1 << c;
                }
                for (int t = 0; t < 5 && kTriangles[index * 16 + 3 * t] >= 0; ++t) {
                    glm::vec3 p[3], grad[3];
                    for (int v = 0; v < 3; ++v) {
                        const int e = kTriangles[index * 16 + 3 * t + v], a = kEdges[2 * e], b = kEdges[2 * e + 1];
                        const glm::ivec3 na = cell + corner(a), nb = cell + corner(b);
                        const float margin = float(RANRYU_MC_EDGE_MARGIN);   // as mc_emit.comp
                        const float s = std::clamp(f[a] / (f[a] - f[b]), margin, 1.0f - margin);
                        const glm::vec3 local = glm::vec3(na) + s * glm::vec3(nb - na);
                        p[v] = g.origin + g.spacing * local;
                        const glm::vec3 ga = gradient(g, na), gb = gradient(g, nb);
                        grad[v] = ga + s * (gb - ga);
                    }
                    const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
                    const glm::vec3 fallback = glm::dot(face, face) > 0.0f ? glm::normalize(face) : glm::vec3(0.0f);
                    for (int v = 0; v < 3; ++v) {
                        const glm::vec3 n = glm::dot(grad[v], grad[v]) > 0.0f ? -glm::normalize(grad[v]) : fallback;
                        out.push_back(gpu::MeshVertex{glm::vec4(p[v], 1.0f), glm::vec4(n, 0.0f)});
                    }
                }
            }
    return out;
}

}  // namespace ranryu::surface
