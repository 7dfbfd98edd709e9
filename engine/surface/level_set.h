#pragma once
// The liquid's level set on a grid, from the particles, on the GPU (docs/METHOD.md §7):
//
//     φ(x) = V · Σ_i W(|x - x_i|, R) - iso          φ > 0 inside, φ = 0 on the surface
//
// W is the SPH cubic spline of glsl/sim/kernel.glsl (Monaghan 1992) with support R, and V = dx^3 the
// volume of one particle (dx the particle spacing), so c(x) = V·ΣW is a smoothed volume fraction:
// ≈ 1 inside liquid at rest, 0 farther than R from every particle.
//
// The defaults (LevelSetSettings::for_spacing) put the surface about a particle radius r = dx/2 from
// the outermost particle centres, both for a lone particle and for a flat free surface:
//   - iso = V·W(r, R), so a lone particle's surface is the sphere of radius r exactly;
//   - R = 1.5 dx, the support for which a flat lattice surface, at the same iso, lies at r too.
//     For a block of particles on a cubic lattice, the 0-level lies 0.53 dx (above the middle of
//     four particles) to 0.57 dx (above a particle) over the top layer's centres; c is 1.09 at
//     particles and 0.91 at the centre of a lattice cube inside, well above iso = 0.419 (the inside
//     stays inside, no holes). The SPH kernel support h = 2 dx would need iso = 0.229 for the lone
//     particle and would then place a flat surface 0.86 dx above the top layer: R = 1.5 dx balances
//     the two. A smaller R makes the surface bumpy (c dips toward iso between particles).
// (Numbers: tests/gl/surface_test.cpp checks the lone particle and the flat slab.)
//
// Passes (named in the GpuTimer):
//   "surface.bounds"  find_bounds.comp   box of the particle centres: a workgroup reduction and
//                                        one uint atomicMin/Max per workgroup and axis (exact)
//                     place_grid.comp    origin and dims of the φ grid and the level set's
//                                        indirect dispatch arguments, on the GPU (1 invocation)
//   "level-set"       compute_level_set.comp   φ at every node: a gather over the neighbour
//                                        grid's cells, glDispatchComputeIndirect
// Nothing is read back; compute() allocates and compiles nothing.
//
// Sub-particles (turbulence/subparticles.h; docs/METHOD.md §7: each sub-particle adds a kernel sized
// to its level), when settings.subparticle_levels > 0:
//
//     φ(x) = V·Σ_{parents with E_i = 0} W(|x - x_i|, R) + Σ_children (V/8^E)·W(|x - x_c|, R_E) - iso
//     R_E = max(R/2^E, 2·h)        (h the φ grid's node spacing; RANRYU_SUBPARTICLE_KERNEL_FLOOR)
//
//   "subparticles.splat"  splat_subparticles.comp   between the two passes above: each child adds
//                                        its term to the nodes within R_E, in fixed point (2^-24
//                                        units, round to nearest) with atomicAdd: integer sums
//                                        commute, so φ is the same every run
//   "level-set"           compute_level_set.comp built with RANRYU_SUBPARTICLES: the gather skips
//                                        the split parents (E_i > 0 in the levels word the spawn
//                                        pass wrote, cell order) and adds the splat, resetting it
// V/8^E: the children share their parent's volume (W is normalised, so each keeps V/8^E at any R_E).
// R/2^E: with the iso of a lone particle of radius dx/2 (above), a lone child's surface is a sphere of
// radius dx/2^(E+1), its own particle radius. The floor: a kernel must be sampled by enough nodes to
// keep its volume wherever it sits between them, or the surface flickers as it moves. h³·Σ_nodes W
// (1 for the continuous kernel), over random positions of the centre, spans 0.9985-1.002 at R = 2h,
// 0.984-1.004 at 1.75h, 0.917-1.087 at 1.5h, 0.11-2.5 at 1h. So R_E >= 2h. At the default h = dx/2
// the floor is dx: every level is then as smooth as a kernel of support dx (R_1 = 0.75 dx already
// falls below it), and the levels differ in where their volume sits, not in sharpness; a finer
// scene surface.node_spacing (dx/8: R_E = R/2^E up to level 2) resolves them.
// The fixed point rounds each child's term at a node by at most 2^-25: k children within R_E of a
// node move its φ by at most k·2^-25 (k ≈ 2100 at level 3 with R_E = dx: 6e-5 at worst; as a random
// walk about 1e-6), against ≈1 inside the liquid.
// The grid's box grows by bounds_margin: children lie within dx/2 per axis (lattice) plus their
// displacement ½(dx/2^E)|ŷ_a| of their parent; the margin covers |ŷ_a| <= 4 (ŷ has unit rms, so a
// component's rms is about 0.58: 7 standard deviations); a child beyond adds to the nodes the grid has.
// Without sub-particles nothing of this is built and φ is bit for bit what it was.
//
// Anisotropic kernels (settings.anisotropic; docs/SURFACE.md, Yu & Turk 2013): each particle's kernel
// is centred on its smoothed centre and stretched along the principal axes of its neighbourhood
// (surface/anisotropy.h), and the kernels are splatted instead of gathered:
//   "surface.anisotropy"  compute_anisotropy.comp   centres and axes, before the bounds (which then
//                                        bound the centres, with a margin of (s_max - 1)·R more)
//   "level-set.splat"     splat_particles.comp      each particle's kernel onto the nodes it covers,
//                                        in the same fixed point as the sub-particles' splat
//   "level-set"           compute_level_set.comp built with RANRYU_SPLATTED: φ = sum - iso, reset
// In the bulk the kernel is the isotropic one above, so R, iso and the node spacing keep their meaning.
// Node budget (settings.max_nodes > 0; docs/SURFACE.md (S9)): the grid coarsens to at most that many
// nodes, so the passes' cost is bounded whatever the liquid's spread.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/grid.h"
#include "surface/anisotropy.h"
#include "surface/phi_grid.h"

namespace ranryu::surface {

struct LevelSetSettings {
    float particle_spacing = 0.02f;   // dx (m): V = dx^3
    float kernel_radius = 0.03f;      // R (m): support of W
    float iso = 0.4192f;              // the level of V·ΣW that is the surface
    float node_spacing = 0.01f;       // finest node spacing of the φ grid (m)
    glm::uvec3 max_dims{160u};        // most nodes per axis (>= 4); a larger box coarsens the grid
    float search_margin = 0.01f;      // (m) how far particles may have moved since the neighbour grid
                                      // sorted them (the gather searches R + margin; exact for any value
                                      // at least the largest displacement, slower for larger ones)
    int subparticle_levels = 0;       // L_max of the sub-particles φ includes; 0: none (nothing built)
    std::uint32_t max_nodes = 0;      // node budget (S9): the grid coarsens to at most this many; 0: none
    bool anisotropic = false;         // anisotropic kernels (above); needs particle_capacity
    AnisotropySettings anisotropy;    // their constants (for_spacing: AnisotropySettings::for_spacing)
    std::size_t particle_capacity = 0;   // most particles compute() is given (anisotropic: buffers per particle)

    // R = 1.5 dx, iso = iso_for_radius(dx, R, dx/2), nodes dx/2 apart, at most 160 per axis, margin
    // dx/2: R + margin = 2 dx = h, one SPH cell, so the search spans at most 3 cells per axis as it
    // does with no margin, and covers a substep's displacement (CFL: |v| dt < 0.4 dx).
    static LevelSetSettings for_spacing(float dx);
};

// The sub-particles' inputs to compute(): Subparticles::levels(), positions(), state() (the indirect
// dispatch at dispatch_offset, workgroups dispatch_group wide).
struct SubparticleSurface {
    const gl::Buffer& levels;
    const gl::Buffer& positions;
    const gl::Buffer& state;
    std::size_t dispatch_offset;
    GLuint dispatch_group;
};

// W(r) with support R: the cubic spline of glsl/sim/kernel.glsl, in double.
double kernel_w(double r, double R);
// The iso at which one lone particle's surface is the sphere of radius r: V·W(r, R), V = dx^3.
float iso_for_radius(float dx, float R, float r);

gpu::SurfaceParams surface_params(const LevelSetSettings& s, std::size_t particle_count);
// R_E, the kernel radius of a level-E sub-particle on a grid of node spacing h (E = 0: R).
float subparticle_kernel_radius(float R, int level, float h);
// How far beyond R the grid must reach for sub-particles up to subparticle_levels (0 without; above).
float subparticle_bounds_margin(const LevelSetSettings& s);
// How far beyond R the grid reaches: the sub-particles' margin and, with anisotropic kernels, (s_max - 1)·R.
float grid_margin(const LevelSetSettings& s);
// Nodes of the grid of spacing h around [lo, hi] (place_grid's rule, in float as place_grid.comp).
float grid_nodes(glm::vec3 lo, glm::vec3 hi, float h, glm::uvec3 max_dims);

// Order-preserving float bits, as glsl/surface/ordered_float.glsl.
std::uint32_t ordered_bits(float f);
float from_ordered_bits(std::uint32_t u);

// CPU reference of place_grid.comp: the grid for particle centres in [lo, hi], phi left empty (with a
// node budget, h may differ from the GPU's by the float rounding of the bisection's steps).
PhiGrid place_grid(glm::vec3 lo, glm::vec3 hi, const LevelSetSettings& s);
// CPU reference of the level set: φ at every node of `grid` (already placed), a brute-force sum over
// all particles in double. Slow: tests only.
void level_set_cpu(std::span<const glm::vec4> positions, const LevelSetSettings& s, PhiGrid& grid);
// The same with sub-particles: parents whose levels word has E_i > 0 are left out, and every child
// (xyz, w = E) adds (V/8^E)·W(|x - x_c|, R_E) on the grid's node spacing.
void level_set_cpu(std::span<const glm::vec4> positions, std::span<const std::uint32_t> levels,
                   std::span<const glm::vec4> children, const LevelSetSettings& s, PhiGrid& grid);

// CPU reference of the anisotropic level set (S7): φ on `grid` (placed) of the given kernels, each
// V·det(G)·W(|G (x - x̄)|, R) with the stretches floored at 2h/R, summed in double on every node but
// the grid's outermost, as splat_particles.comp does. Slow: tests only.
void level_set_cpu(std::span<const ParticleAnisotropy> kernels, const LevelSetSettings& s, PhiGrid& grid);

class LevelSet {
public:
    // Builds the programs and allocates φ for max_dims nodes. Throws InputError on bad settings.
    LevelSet(const shader::FileSource& shaders, profile::GpuTimer& timer, const LevelSetSettings& settings);
    // Device memory the constructor allocates (frame/memory.h).
    static std::size_t bytes_for(const LevelSetSettings& settings);

    // φ of `count` particles whose positions are in cell order in `sorted_position`, with the
    // cell ranges `ranges` and the sorted keys of `grid`'s last build() (cleared or not); the
    // particles may have moved by up to search_margin since. Binds the grid's GridParams. Runs
    // inside a GpuTimer frame; ends with a shader-storage barrier, so marching cubes may read φ and
    // grid(). With sub-particles (settings().subparticle_levels > 0) `sub` is required, and their
    // passes must have run (Subparticles::generate, after the particles' last move).
    void compute(sim::NeighbourGrid& grid, const gl::Buffer& sorted_position, const sim::CellRanges& ranges,
                 std::size_t count, const SubparticleSurface* sub = nullptr);

    const gl::Buffer& phi() const { return phi_; }     // float[max nodes], first grid().dims.w used
    const gl::Buffer& grid() const { return grid_; }   // SurfaceGrid, written on the GPU
    const LevelSetSettings& settings() const { return settings_; }
    // Anisotropic kernels (else empty): SurfaceCentres and SurfaceAxes of shared/bindings.h.
    const gl::Buffer& centres() const { return centres_; }
    const gl::Buffer& axes() const { return axes_; }
    std::size_t max_nodes() const { return max_nodes_; }
    // compute_level_set.comp's workgroup size: nodes per workgroup along x, y, z (tests).
    std::array<GLuint, 3> node_group() const { return compute_.local_size(); }

private:
    profile::GpuTimer& timer_;
    profile::PassId bounds_pass_, place_grid_pass_, level_set_pass_, splat_pass_{}, anisotropy_pass_{}, particle_splat_pass_{};   // place_grid_pass_ within bounds_pass_
    shader::Program find_bounds_, place_grid_, compute_, splat_, anisotropy_, particle_splat_;
    LevelSetSettings settings_;
    std::size_t max_nodes_;
    gl::Buffer params_, grid_, phi_, splat_grid_, centres_, axes_;
    std::size_t params_count_ = ~std::size_t(0);
};

}  // namespace ranryu::surface
