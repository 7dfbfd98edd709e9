#pragma once
// The uniform-grid neighbour search (docs/METHOD.md §1; Green 2008): hash -> sort -> cell ranges ->
// reorder. After build(), the particles are in cell order and a cell's particles are the run
// cell_range[key] = [first, one past the last) of the sorted arrays. Passes: "hash", the sort's own, and
// "reorder", which finds the cell ranges and gathers the particles in one pass.
#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/sort.h"

namespace ranryu::sim {

// Cells of size `cell` covering [min, max]; keys linear (the talk's, docs/METHOD.md §1) or Morton.
struct GridLayout {
    glm::vec3 origin{0.0f};
    float cell = 1.0f;
    glm::uvec3 dims{1u};
    bool morton = false;
    std::uint32_t key_count = 1;   // cell_range entries
    static GridLayout covering(glm::vec3 min, glm::vec3 max, float cell, bool morton);
    gpu::GridParams params(std::uint32_t count) const;
};

// Morton keys: the low 10 bits of v spread to every third bit of 30 (glsl/sim/grid.glsl's spread_bits).
std::uint32_t spread_bits(std::uint32_t v);

// The cell ranges of one particle set: per key, the run (first sorted index, one past its last) as a
// uvec2, one storage block for the passes that walk the grid (GL's 16 a compute shader may bind).
struct CellRanges {
    gl::Buffer cells;
};

// A per-particle array that a reorder gathers along with the positions: `words` 32-bit words a
// particle, from `from` (the old order) into `to` (the new one).
struct CarriedArray {
    const gl::Buffer* from = nullptr;
    gl::Buffer* to = nullptr;
    std::uint32_t words = 0;
};

class NeighbourGrid {
public:
    NeighbourGrid(const shader::FileSource& shaders, profile::GpuTimer& timer, const GridLayout& layout,
                  std::size_t capacity, SortMethod method);

    // Device memory the constructor allocates (its sort's buffers and parameters), and one
    // make_ranges() of `layout` (frame/memory.h).
    static std::size_t bytes_for(std::size_t capacity);
    static std::size_t ranges_bytes(const GridLayout& layout);

    const GridLayout& layout() const { return layout_; }
    CellRanges make_ranges(std::string_view name) const;
    void set_method(SortMethod m) { method_ = m; }

    // Sorts `count` particles of `position`/`velocity` by cell into `sorted_position`/`sorted_velocity`
    // and fills `ranges` for the cells that have particles. With `clear`, every other cell reads as
    // the empty run 0, 0; without it (the per-substep case: clearing every cell costs more than the
    // sort), other cells keep stale entries, which readers reject by checking that the sorted key
    // at an entry's start is the cell's own (glsl/sim/fluid/fluid.glsl, fluid_run). Leaves
    // RANRYU_UBO_GRID bound to this grid. The reorder also gathers up to max_carried `carried` arrays
    // (the fluid's carried arrays, sim/fluid.h) in the same pass.
    static constexpr std::size_t max_carried = 3;
    void build(const gl::Buffer& position, const gl::Buffer& velocity, gl::Buffer& sorted_position,
               gl::Buffer& sorted_velocity, CellRanges& ranges, std::size_t count, bool clear,
               std::span<const CarriedArray> carried = {});

    const KeySort& sort() const { return sort_; }
    void bind_params(std::size_t count);

private:
    profile::GpuTimer& timer_;
    profile::PassId hash_pass_, reorder_pass_;
    shader::Program hash_;
    std::array<shader::Program, max_carried + 1> reorder_;   // by the number of carried arrays
    KeySort sort_;
    GridLayout layout_;
    SortMethod method_;
    gl::Buffer params_;
    std::uint32_t params_count_ = ~0u;
};

}  // namespace ranryu::sim
