#include "sim/grid.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace ranryu::sim {

std::uint32_t spread_bits(std::uint32_t v) {   // as in glsl/sim/grid.glsl
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

GridLayout GridLayout::covering(glm::vec3 min, glm::vec3 max, float cell, bool morton) {
    GridLayout g;
    g.origin = min;
    g.cell = cell;
    g.dims = glm::max(glm::uvec3(glm::ceil((max - min) / cell)), glm::uvec3(1u));
    g.morton = morton;
    if (morton) {
        if (glm::any(glm::greaterThan(g.dims, glm::uvec3(1024u))))
            throw InputError("neighbour grid of " + std::to_string(g.dims.x) + "x" + std::to_string(g.dims.y) + "x" +
                             std::to_string(g.dims.z) + " cells is too large for Morton keys (1024 per axis at most)");
        const glm::uvec3 top = g.dims - 1u;
        g.key_count = (spread_bits(top.x) | (spread_bits(top.y) << 1) | (spread_bits(top.z) << 2)) + 1u;
    } else {
        const double cells = double(g.dims.x) * g.dims.y * g.dims.z;
        if (cells > double(1u << 30))
            throw InputError("neighbour grid of " + std::to_string(cells) + " cells is too large (2^30 at most)");
        g.key_count = g.dims.x * g.dims.y * g.dims.z;
    }
    return g;
}

gpu::GridParams GridLayout::params(std::uint32_t count) const {
    gpu::GridParams p{};
    p.origin = glm::vec4(origin, cell);
    p.dims = glm::uvec4(dims, key_count);
    p.count = count;
    p.morton = morton ? 1u : 0u;
    p.key_max = key_count - 1u;
    return p;
}

NeighbourGrid::NeighbourGrid(const shader::FileSource& shaders, profile::GpuTimer& timer, const GridLayout& layout,
                             std::size_t capacity, SortMethod method)
    : timer_(timer),
      hash_pass_(timer.pass("hash")),
      reorder_pass_(timer.pass("reorder")),
      hash_(shader::Program::compute(shaders, "sim/grid/hash_particles.comp")),
      reorder_{shader::Program::compute(shaders, "sim/grid/reorder_particles.comp", "#define RANRYU_CARRIED_ARRAYS 0\n"),
               shader::Program::compute(shaders, "sim/grid/reorder_particles.comp", "#define RANRYU_CARRIED_ARRAYS 1\n"),
               shader::Program::compute(shaders, "sim/grid/reorder_particles.comp", "#define RANRYU_CARRIED_ARRAYS 2\n"),
               shader::Program::compute(shaders, "sim/grid/reorder_particles.comp", "#define RANRYU_CARRIED_ARRAYS 3\n")},
      sort_(shaders, timer, capacity),
      layout_(layout),
      method_(method),
      params_(sizeof(gpu::GridParams), GL_DYNAMIC_DRAW, nullptr, "GridParams") {}

std::size_t NeighbourGrid::bytes_for(std::size_t capacity) { return KeySort::bytes_for(capacity) + sizeof(gpu::GridParams); }
std::size_t NeighbourGrid::ranges_bytes(const GridLayout& layout) { return 2 * std::size_t(layout.key_count) * sizeof(std::uint32_t); }

CellRanges NeighbourGrid::make_ranges(std::string_view name) const {
    return CellRanges{gl::Buffer(ranges_bytes(layout_), GL_DYNAMIC_COPY, nullptr, std::string(name))};
}

void NeighbourGrid::bind_params(std::size_t count) {
    if (params_count_ != count) {   // a changed count only: the layout is fixed
        params_.upload_value(layout_.params(std::uint32_t(count)));
        params_count_ = std::uint32_t(count);
    }
    params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_GRID);
}

void NeighbourGrid::build(const gl::Buffer& position, const gl::Buffer& velocity, gl::Buffer& sorted_position,
                          gl::Buffer& sorted_velocity, CellRanges& ranges, std::size_t count, bool clear,
                          std::span<const CarriedArray> carried) {
    if (carried.size() > max_carried) throw Error("NeighbourGrid::build: more than 3 carried arrays");
    bind_params(count);
    {
        auto pass = timer_.scope(hash_pass_);
        hash_.bind({{"Positions", &position}, {"Keys", &sort_.keys()}, {"Values", &sort_.values()}}).dispatch(count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    sort_.sort(method_, count, layout_.key_count - 1u);
    params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_GRID);
    {
        // One pass per sorted index: the cell ranges (the runs of equal sorted keys) and the gather of
        // the particle arrays into sorted order (glsl/sim/grid/reorder_particles.comp). Fused: both
        // read the sort's output at the same index, and one launch fewer is 1 % of a 1M substep.
        auto pass = timer_.scope(reorder_pass_);
        if (clear) {
            const GLuint zero = 0;
            glBindBuffer(GL_COPY_WRITE_BUFFER, ranges.cells.id());
            glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        shader::StorageSet buffers{{"SortedKeys", &sort_.sorted_keys()}, {"SortedValues", &sort_.sorted_values()},
                                   {"CellRange", &ranges.cells},
                                   {"Positions", &position},              {"Velocities", &velocity},
                                   {"SortedPositions", &sorted_position}, {"SortedVelocities", &sorted_velocity}};
        static constexpr std::string_view from[] = {"Carried0", "Carried1", "Carried2"},
                                          to[] = {"SortedCarried0", "SortedCarried1", "SortedCarried2"};
        GLuint words[3] = {0, 0, 0};
        for (std::size_t a = 0; a < carried.size(); ++a) {
            buffers.add(from[a], *carried[a].from).add(to[a], *carried[a].to);
            words[a] = carried[a].words;
        }
        const shader::Program& reorder = reorder_[carried.size()];
        if (!carried.empty()) glProgramUniform3ui(reorder.id(), RANRYU_LOC_AUX, words[0], words[1], words[2]);
        reorder.bind(buffers).dispatch(count);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace ranryu::sim
