#pragma once
// Marching cubes on the GPU (docs/METHOD.md §7; Lorensen & Cline, SIGGRAPH 1987), with the 256-case
// tables of Paul Bourke's "Polygonising a scalar field" kept in glsl/surface/mc_tables.h for GLSL and
// C++ alike.
//
// Input: any φ grid on the GPU, a float buffer and a SurfaceGrid buffer of which only origin and
// dims are read (the level set writes both; a test may upload them). Output: non-indexed triangles,
// gpu::MeshVertex (position vec4, outward unit normal vec4), counter-clockwise seen from outside,
// and glDrawArraysIndirect arguments, all written on the GPU:
//
//     glBindBuffer(GL_DRAW_INDIRECT_BUFFER, mc.state().id());
//     glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(MarchingCubes::draw_offset));
//     (vertices(): attribute 0 at offset 0, attribute 1 at offset 16, stride 32, or pulled as an SSBO)
//
// Passes (named in the GpuTimer):
//   "mc.classify"  mc_setup.comp        cell count -> indirect arguments of the cell passes (1 invocation)
//                  mc_classify.comp     case and vertex count of every cell; per-block totals
//   "mc.compact"   mc_scan_blocks.comp  exclusive scan of the block totals (one workgroup); emit and
//                                       draw arguments
//                  mc_compact.comp      in-block scan + block offset -> list of active cells with their
//                                       first vertex (order-preserving)
//   "mc.emit"      mc_emit.comp         triangles of each active cell, vertex normals from the smoothed ∇φ
//                                       (docs/SURFACE.md (S8))
// Ambiguous faces get the table's one fixed choice, the same from both cells that share the face,
// and vertices on shared edges are bit-identical: the mesh is watertight and consistently oriented
// (tests/unit/marching_cubes_table_test.cpp proves the table's part, tests/gl/surface_test.cpp checks
// meshes). polygonise() allocates, compiles and reads back nothing.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "surface/phi_grid.h"

namespace ranryu::surface {

struct MeshCapacity {
    glm::uvec3 max_dims{160u};                      // most φ-grid nodes per axis (cells: one fewer)
    std::size_t max_vertices = std::size_t(1) << 22;   // 3 per triangle; more are dropped (MeshState.totals.z)
    std::uint32_t groups_x = 32768;   // workgroups a row of the cell passes' 2-D dispatches (tests narrow it)
    std::size_t max_nodes = 0;        // the level set's node budget (cells fewer); 0: max_dims alone
    // Cells the buffers hold: (max_dims - 1)³, or fewer than max_nodes when that is smaller.
    std::size_t cells() const;
};

class MarchingCubes {
public:
    // Builds the programs and allocates every buffer. Throws ranryu::Error when a dispatch could not
    // cover the capacity (the cell passes dispatch in 2-D).
    MarchingCubes(const shader::FileSource& shaders, profile::GpuTimer& timer, const MeshCapacity& capacity);
    // Device memory the constructor allocates (frame/memory.h).
    static std::size_t bytes_for(const MeshCapacity& capacity);

    // Meshes the φ = 0 surface of `phi` (float[], layout of shared/bindings.h) on the grid described
    // by `grid` (SurfaceGrid: origin, dims). A grid with more cells than max_cells() gives an empty
    // mesh and MeshState.totals.w = 1. Runs inside a GpuTimer frame; earlier shader writes to phi and
    // grid must be made visible by the caller (LevelSet::compute does). Ends with the barriers that
    // let the mesh be drawn with glDrawArraysIndirect or read as a storage buffer.
    void polygonise(const gl::Buffer& phi, const gl::Buffer& grid);

    const gl::Buffer& vertices() const { return vertices_; }   // gpu::MeshVertex[max_vertices()]
    const gl::Buffer& state() const { return state_; }         // gpu::MeshState; the indirect buffer
    static constexpr std::size_t draw_offset = offsetof(gpu::MeshState, draw);

    std::size_t max_cells() const { return max_cells_; }
    std::size_t max_vertices() const { return max_vertices_; }
    std::size_t max_active() const { return max_active_; }

private:
    profile::GpuTimer& timer_;
    profile::PassId classify_pass_, compact_pass_, emit_pass_, setup_pass_, scan_pass_;   // setup within classify, scan within compact
    shader::Program setup_, classify_, scan_, compact_, emit_;
    std::size_t max_cells_, max_vertices_, max_active_, max_blocks_;
    gl::Buffer state_, cell_vertices_, blocks_, active_, vertices_, triangles_;
};

// The tables of glsl/surface/mc_tables.h.
std::span<const int, 4096> mc_triangle_table();   // 16 per case, -1 after the last triangle
std::span<const int, 24> mc_corner_table();       // corner c at offset (3c, 3c+1, 3c+2)
std::span<const int, 24> mc_edge_table();         // edge e from corner 2e to corner 2e+1 (lower first)

// CPU reference of the GPU passes: the same cases, the same arithmetic and the same order (cells in
// index order, triangles in table order), so its output matches the GPU's vertex for vertex.
std::vector<gpu::MeshVertex> polygonise_cpu(const PhiGrid& grid);

}  // namespace ranryu::surface
