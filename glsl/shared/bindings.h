// Binding points and parameter structs shared by C++ and GLSL.
//
// This file is compiled by both languages, so it keeps to what both understand: #define for binding
// points (GLSL 4.30 layout qualifiers take literals only), and structs of vec4/mat4 and groups of four
// 4-byte scalars, so that std140 (UBO) and std430 (SSBO) need no padding rules beyond the C++ ones.
// C++ checks each struct's size with static_assert; tests/gl/interop_test.cpp checks every member's
// std140 offset against the driver's and reads the values back through a compute shader.
#ifndef RANRYU_SHARED_BINDINGS_H
#define RANRYU_SHARED_BINDINGS_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace ranryu::gpu {
using uint = std::uint32_t;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define RANRYU_STRUCT(name) struct alignas(16) name
#define RANRYU_STRUCT_END(name, bytes) ; static_assert(sizeof(name) == (bytes), #name " size differs from its GLSL std140 size");
#else
#define RANRYU_STRUCT(name) struct name
#define RANRYU_STRUCT_END(name, bytes) ;
#endif

// ---- uniform buffer binding points (std140) ----
#define RANRYU_UBO_FRAME 0   // FrameParams: camera, light, viewport
#define RANRYU_UBO_SIM 1     // SimParams: integration and tank (ballistic model)
#define RANRYU_UBO_GRID 2    // GridParams: the uniform neighbour grid
#define RANRYU_UBO_SPH 3     // SphParams: the SPH model (docs/SPH.md)
#define RANRYU_UBO_PROBE 7   // tests only: LayoutProbe

// ---- shader storage binding points (std430); all below 32 (llvmpipe's limit) ----
#define RANRYU_SSBO_POSITION 0   // vec4[n]: xyz position (m), w unused
#define RANRYU_SSBO_VELOCITY 1   // vec4[n]: xyz velocity (m/s), w unused
// Sorting (engine/sim/sort.*): (key, value) pairs ping-pong between the two sets.
#define RANRYU_SSBO_SORT_KEYS 2        // uint[n]
#define RANRYU_SSBO_SORT_VALUES 3      // uint[n]
#define RANRYU_SSBO_SORT_KEYS_ALT 4    // uint[n]
#define RANRYU_SSBO_SORT_VALUES_ALT 5  // uint[n]
#define RANRYU_SSBO_SORT_HISTOGRAM 6   // uint[]: per-workgroup digit counts, then their prefix sums
#define RANRYU_SSBO_PROBE_OUT 7        // tests only
// Neighbour grid and SPH (engine/sim/): per-cell ranges and per-particle fields.
#define RANRYU_SSBO_CELL_START 8       // uint[cells]: first sorted index of the cell
#define RANRYU_SSBO_CELL_END 9         // uint[cells]: one past the last sorted index
#define RANRYU_SSBO_SORTED_POSITION 10 // vec4[n]
#define RANRYU_SSBO_SORTED_VELOCITY 11 // vec4[n]
#define RANRYU_SSBO_DENSITY 12         // vec4[n]: x density, y pressure, z pressure / density^2
#define RANRYU_SSBO_ACCEL 13           // vec4[n]: xyz acceleration
#define RANRYU_SSBO_NEIGHBOURS 14      // uint[2·runs·n]: the density pass's neighbour masks (compute_density.comp)
#define RANRYU_SSBO_BOUNDARY 15        // vec4[m]: boundary particles, xyz position, w volume psi
#define RANRYU_SSBO_STEP 16            // StepState: the adaptive time step, on the GPU
#define RANRYU_SSBO_SCRATCH 17         // uint[]: pass-local scratch
#define RANRYU_SSBO_BOUNDARY_CELL_START 18  // uint[cells]: boundary particles' cell ranges
#define RANRYU_SSBO_BOUNDARY_CELL_END 19
// vec4[]: the obstacles' shapes (sim/boundary.h obstacle_shapes()), read by integrate's last-resort
// projection (docs/SPH.md (8)); shares 17 with the start-up passes' scratch, which integrate never binds.
#define RANRYU_SSBO_OBSTACLES 17
// uint[keys]: 1 where the 27 cells around the cell hold a boundary particle (flag_boundary_cells.comp,
// once at start); the density pass walks the boundary runs only there. Shares 20 with the surface's
// SurfaceGrid: no SPH pass binds a surface buffer.
#define RANRYU_SSBO_BOUNDARY_NEAR 20
// vec2[n]: (rho_i, p_i / rho_i^2), the two density terms the forces pass gathers per pair, half the
// bytes of the density array. Shares 11 with the reorder's sorted velocities: no other pass binds it.
#define RANRYU_SSBO_PAIR_TERMS 11

// ---- explicit uniform locations (small per-dispatch values; never looked up by name) ----
#define RANRYU_LOC_COUNT 0     // uint: number of items this dispatch covers
#define RANRYU_LOC_SHIFT 1     // uint: radix sort digit shift
#define RANRYU_LOC_STAGE 2     // uivec2 / uint: bitonic sort (block size k, stride j)
#define RANRYU_LOC_AUX 3       // uint: pass-specific

// ---- vertex attribute locations ----
#define RANRYU_ATTR_POSITION 0   // per-instance particle position (impostors)
#define RANRYU_ATTR_VELOCITY 1   // per-instance particle velocity (impostors)

// Simulation parameters for one substep. Units: SI (m, s, m/s^2).
RANRYU_STRUCT(SimParams) {
    vec4 gravity;       // xyz: acceleration (m/s^2)
    vec4 domain_min;    // xyz: tank's inner lower corner (m)
    vec4 domain_max;    // xyz: tank's inner upper corner (m)
    float dt;           // substep (s)
    float restitution;  // wall bounce: normal velocity is multiplied by -restitution
    float particle_radius;  // (m): particles stop this far from a wall
    uint particle_count;
}
RANRYU_STRUCT_END(SimParams, 64)

// Per-frame view: camera, one directional light, Phong material terms.
RANRYU_STRUCT(FrameParams) {
    mat4 view;
    mat4 proj;
    mat4 view_proj;
    vec4 eye;             // xyz: camera position (world)
    vec4 light_dir;       // xyz: unit vector from the surface toward the light (world)
    vec4 light_color;     // rgb: light colour; a: ambient factor
    vec4 material;        // x: diffuse k_d, y: specular k_s, z: shininess, w: particle radius (m)
    vec4 viewport;        // xy: size in pixels, zw: 1/size
    vec4 speed_scale;     // x: speed (m/s) mapped to the top of the colour ramp
    vec4 tank_min;        // xyz: tank's inner lower corner (world); the floor is at tank_min.y
    vec4 tank_max;        // xyz: tank's inner upper corner (world)
}
RANRYU_STRUCT_END(FrameParams, 320)

// The uniform grid of the neighbour search (METHOD.md §1): cells of size h cover the domain.
RANRYU_STRUCT(GridParams) {
    vec4 origin;        // xyz: lower corner of cell (0,0,0) (m); w: cell size (m) = kernel support h
    uvec4 dims;         // xyz: cells per axis; w: number of keys (cells, or the Morton code range)
    uint count;         // particles to hash
    uint morton;        // 1: Morton (Z-order) keys; 0: linear keys i + j*nx + k*nx*ny (the seed's)
    uint key_max;       // largest key any particle can get
    uint pad0;
}
RANRYU_STRUCT_END(GridParams, 48)

// The SPH model's constants; docs/SPH.md gives every equation these enter.
RANRYU_STRUCT(SphParams) {
    vec4 gravity;         // xyz (m/s^2)
    vec4 domain_min;      // xyz: the guard's bounds; a fluid particle outside has escaped (m)
    vec4 domain_max;
    float h;              // kernel support (m), eq. (1)
    float mass;           // particle mass m = rho0 * dx^3 (kg)
    float rest_density;   // rho0 (kg/m^3)
    float stiffness;      // Tait B = rho0 c^2 / 7 (Pa), eq. (3)
    float viscosity;      // kinematic nu (m^2/s), eq. (5)
    float sound_speed;    // c (m/s)
    float spacing;        // dx (m)
    float cfl;            // Courant number of eq. (7), 0.4
    float force_factor;   // factor of the force condition of eq. (7), 0.25
    float dt_max;         // largest substep (s)
    float dt_floor;       // guard: a substep below this has collapsed (s)
    float density_limit;  // guard: rho / rho0 above this is exploding
    float speed_limit;    // guard: |v| above this is exploding (m/s)
    uint particle_count;
    uint boundary_count;
    float front_band;     // surge front: particles below floor + this count (m)
}
RANRYU_STRUCT_END(SphParams, 112)

// The adaptive time step and the instability guard's findings, kept on the GPU (std430 SSBO at
// RANRYU_SSBO_STEP). Maxima of non-negative floats are kept as their bits: for x, y >= 0,
// floatBitsToUint orders like the floats, so atomicMax on uint finds the float maximum.
RANRYU_STRUCT(StepState) {
    float dt;                 // this substep's dt (s)
    float time;               // simulated time (s)
    float frame_left;         // simulated time this frame still has to cover (s)
    uint substeps_left;       // substeps issued for this frame that have not run yet
    uint max_speed;           // bits of max |v| over the last substep (input of eq. (7))
    uint max_accel;           // bits of max |a| over the last substep
    uint frame_max_speed;     // bits of max |v| over this frame
    uint frame_max_density;   // bits of max rho/rho0 over this frame
    float frame_min_dt;       // smallest stable dt (CFL and force conditions) this frame (s)
    uint frame_substeps;      // substeps run this frame
    uint nan_count;           // particle updates with a non-finite value this frame
    uint nan_index;           // lowest index among them (sorted order), or 0xFFFFFFFF
    uint escaped_count;       // particles outside the domain this frame
    uint escaped_index;       // lowest index among them, or 0xFFFFFFFF
    uint speed_index;         // a particle at the frame's max speed
    uint density_index;       // a particle at the frame's max density
    uint front;               // bits of the surge front: max (x - domain_min.x) of particles within front_band of domain_min.y
    uint frame;               // frame number these findings belong to
    uint steps;               // substeps since the start
    uint pad0;
}
RANRYU_STRUCT_END(StepState, 80)

// Tests only: one of each member kind, to pin the layout rules both sides rely on.
RANRYU_STRUCT(LayoutProbe) {
    mat4 m;
    vec4 v;
    uvec4 u;
    float f0;
    float f1;
    uint u0;
    uint u1;
}
RANRYU_STRUCT_END(LayoutProbe, 112)

// ---- sort (engine/sim/sort.*, glsl/sim/sort/): the one place for the constants both sides use ----
// Workgroup sizes stay in GLSL; C++ reads them from the programs and multiplies by these.
#define RANRYU_SORT_RADIX_BITS 8              // bits per LSD radix digit: 256 buckets, 4 passes for 32 bits
#define RANRYU_SORT_RADIX_ITEMS_PER_THREAD 4  // radix tile = local_size_x * this; 4 measured 24 % faster than 8 at 1M pairs on an H100
#define RANRYU_SORT_BITONIC_ITEMS_PER_THREAD 8  // bitonic shared-memory tile = local_size_x * this
// ---- end sort

// ---- surface (engine/surface/, glsl/surface/): level set and marching cubes ----
// The φ grid: nodes x = origin + spacing·(i, j, k); φ[i + nx·(j + ny·k)], φ > 0 inside the liquid.
// Cells are the (nx-1)(ny-1)(nz-1) cubes between nodes, indexed the same way with (nx-1, ny-1).
#define RANRYU_UBO_SURFACE 4             // SurfaceParams: the level set's constants
#define RANRYU_SSBO_SURFACE_GRID 20      // SurfaceGrid: where the φ grid lies this frame (GPU-written)
#define RANRYU_SSBO_SURFACE_PHI 21       // float[nodes]: φ at the grid nodes
#define RANRYU_SSBO_MC_STATE 22          // MeshState: marching cubes' indirect arguments and totals
#define RANRYU_SSBO_MC_CELL_VERTICES 23  // uint[cells]: vertices each cell emits (0, 3, ..., 15)
#define RANRYU_SSBO_MC_BLOCKS 24         // uvec2[blocks]: (active cells, vertices) per classify workgroup, then their exclusive prefix sums
#define RANRYU_SSBO_MC_ACTIVE 25         // uvec2[]: compacted active cells: (cell index, first vertex)
#define RANRYU_SSBO_MC_VERTICES 26       // MeshVertex[]: the mesh, non-indexed triangles
#define RANRYU_SSBO_MC_TRIANGLES 27      // int[4096]: the triangle table (surface/mc_tables.h), uploaded once
#define RANRYU_LOC_SURFACE_CAPACITY 4    // uvec4 uniform: x vertices, y active cells, z cells (MC buffer capacities)
#define RANRYU_LOC_SURFACE_GROUP 5       // uvec4 uniform: workgroup size of the pass whose indirect arguments this pass writes

// Level set constants (METHOD.md §7): φ(x) = volume · Σ_i W(|x - x_i|, kernel_radius) - iso, with W the
// cubic spline of glsl/sim/kernel.glsl. engine/surface/level_set.h explains the defaults.
RANRYU_STRUCT(SurfaceParams) {
    uvec4 max_dims;        // xyz: most nodes per axis (the grid coarsens to fit); w: unused
    float node_spacing;    // finest node spacing (m)
    float kernel_radius;   // R: support of W (m)
    float volume;          // V: particle volume dx^3 (m^3); V·ΣW is ≈ 1 inside liquid at rest
    float iso;             // the level: φ = 0 where V·ΣW = iso
    uint particle_count;
    float search_margin;   // (m): the gather also searches cells this much beyond R (particles moved since the sort)
    float bounds_margin;   // (m): the grid reaches this much beyond R around the particles (sub-particles' reach; else 0)
    uint pad1;
}
RANRYU_STRUCT_END(SurfaceParams, 48)

// Where the φ grid lies (std430 SSBO). The level set writes it on the GPU each frame; any other
// producer of φ fills origin and dims, which is all marching cubes reads.
RANRYU_STRUCT(SurfaceGrid) {
    vec4 origin;         // xyz: node (0,0,0) (m); w: node spacing (m)
    uvec4 dims;          // xyz: nodes per axis (0 when there is nothing to mesh); w: nodes in all
    uvec4 bounds_min;    // xyz: the particles' lower corner as order-preserving bits (see surface/bounds.glsl)
    uvec4 bounds_max;    // xyz: upper corner, likewise
    uvec4 dispatch;      // xyz: glDispatchComputeIndirect groups of the level-set pass; w: 1 if coarsened to fit max_dims
}
RANRYU_STRUCT_END(SurfaceGrid, 80)

// Marching cubes' GPU-side state (std430 SSBO), written by its own passes; also the indirect
// argument buffer: cell_dispatch at byte 0, emit_dispatch at 16, draw at 32.
RANRYU_STRUCT(MeshState) {
    uvec4 cell_dispatch;   // xyz: classify/compact groups; w: cells in all
    uvec4 emit_dispatch;   // xyz: emit groups; w: active cells listed
    uvec4 draw;            // glDrawArraysIndirect: count, instanceCount, first, baseInstance
    uvec4 totals;          // x: active cells, y: vertices wanted, z: 1 if vertices were cut to capacity,
                           // w: 1 if the grid had more cells than the capacity (nothing meshed)
}
RANRYU_STRUCT_END(MeshState, 64)

// One mesh vertex; three consecutive vertices are a triangle, counter-clockwise seen from outside.
RANRYU_STRUCT(MeshVertex) {
    vec4 position;   // xyz (m), w = 1
    vec4 normal;     // xyz: unit outward normal (-∇φ/|∇φ|), w = 0
}
RANRYU_STRUCT_END(MeshVertex, 32)
// ---- end surface

// ---- turbulence (engine/turbulence/, glsl/turbulence/): METHOD.md §3, §4 ----
// Wavelet analysis (engine/turbulence/wavelet.h, glsl/turbulence/analyse_velocity.comp): 28, 29.
// Bindings 30, 31 of this section are the noise synthesis's.
#define RANRYU_SSBO_WAVELET_ENERGY 28   // vec4[particles]: xyz û_i, w ê_i = ½|û_i|², in the analysed (cell) order
#define RANRYU_SSBO_WAVELET_PARAMS 29   // WaveletParams (std430, read-only)

// The wavelet pass's constants (METHOD.md §3), written by WaveletAnalysis::analyse().
RANRYU_STRUCT(WaveletParams) {
    float scale;            // s (m): ψ is evaluated at (x_i - x_j)/s
    float truncation;       // R: neighbours with |x_i - x_j|/s < R are summed; R·s <= the grid's cell
    uint particle_count;    // particles analysed
    uint pad0;
}
RANRYU_STRUCT_END(WaveletParams, 16)
// Noise synthesis (engine/turbulence/noise.h, glsl/turbulence/curl_noise.glsl, sample_field.comp): 30, 31, UBO 5.
#define RANRYU_UBO_NOISE 5                // NoiseParams: the sampling grid and the octave sum
#define RANRYU_SSBO_NOISE_TILES 30        // float[3·n³]: the three wavelet-noise potential tiles, x + n·(y + n·z)
#define RANRYU_SSBO_NOISE_FIELD 31        // float[points·3]: sampled y, C order of shape (nx, ny, nz, 3)

// y(x) = Σ_{i=lmin}^{lmax} w(2^i x + o_i) · 2^(−β(i − lmin)) sampled at origin + spacing·(i, j, k).
RANRYU_STRUCT(NoiseParams) {
    vec4 origin;      // xyz: grid point (0,0,0) (m); w: grid spacing (m)
    uvec4 dims;       // xyz: points per axis; w: points in all
    int lmin;         // first octave
    int lmax;         // last octave (inclusive)
    float beta;       // amplitude falloff 2^(−β(i − lmin)); 1/3 gives E(k) ∝ k^(−5/3)
    uint tile_size;   // n: each tile holds n³ values
}
RANRYU_STRUCT_END(NoiseParams, 48)
// Turbulence force (engine/turbulence/force.h, glsl/turbulence/apply_turbulence_force.comp): reads
// 0, 13, 16, 28, 30, UBO 3 and 5 (NoiseParams: lmin, lmax, beta, tile_size), these uniforms, and
// reads and re-seeds the carried noise coordinates (31).
#define RANRYU_LOC_TURBULENCE_AMPLITUDE 1   // float: A (1/m), the force's amplitude
#define RANRYU_LOC_COHERENCE_TIME 2         // float: T (s), the carried noise's re-seeding period

// Carried noise (glsl/turbulence/carried_noise.glsl): per fluid particle, the positions at which its
// two noise phases were last seeded. Binding 31 is the noise field's too (export-field's sampling
// pass binds no seeds); the reorder pass gathers the seeds from 31 into SORTED_NOISE_SEED, which
// shares 4 with the sort's alternate keys (the reorder pass binds no sort keys but its values).
#define RANRYU_SSBO_NOISE_SEED 31          // NoiseSeed[particles], in the fluid's cell order
#define RANRYU_SSBO_SORTED_NOISE_SEED 4    // NoiseSeed[particles]: the reorder pass's output
RANRYU_STRUCT(NoiseSeed) {
    vec4 phase[2];   // xyz: where the phase was seeded (m); w: the epoch it was seeded in (float, -1: never)
    vec4 value[2];   // xyz: the phase's octave sum y(q_p), fixed for the epoch (carried_noise.glsl); w: 0
}
RANRYU_STRUCT_END(NoiseSeed, 64)

// Sub-particles (engine/turbulence/subparticles.h, glsl/turbulence/subparticles/): they share the
// marching cubes' bindings 22-27 (no pass binds both) and UBO 6; their section follows.
// The sub-particle passes run after the SPH substeps and before the level set; marching cubes runs
// after the level set and binds 22-27 afresh, so the aliasing is safe as long as no one program
// declares both sets (none does: the level set's splat and gather bind 22, 23, 24, 26 of this set,
// and no marching-cubes buffer). Binding 24 is the classify passes' block counts and, in the level
// set's passes, which bind no blocks, the fixed-point splat grid.
#define RANRYU_UBO_SUBPARTICLES 6                 // SubparticleParams
#define RANRYU_SSBO_SUBPARTICLE_STATE 22          // SubparticleState: counts, cap, indirect arguments (std430)
#define RANRYU_SSBO_SUBPARTICLE_LEVELS 23         // uint[particles]: L_i | E_i << RANRYU_SUBPARTICLE_SPLIT_SHIFT, in the fluid's cell order
#define RANRYU_SSBO_SUBPARTICLE_BLOCKS 24         // uvec4[classify workgroups]: xyz per-level counts, then their exclusive prefix sums
#define RANRYU_SSBO_SUBPARTICLE_SPLAT 24          // uint[φ nodes]: the sub-particles' V·ΣW in fixed point (level set only)
#define RANRYU_SSBO_SUBPARTICLE_LISTS 25          // uint[levels · particles]: level L's split parents at (L-1)·particles, in cell order
#define RANRYU_SSBO_SUBPARTICLE_POSITION 26       // vec4[capacity]: xyz (m); w: effective level E (1..3), as a float
#define RANRYU_SSBO_SUBPARTICLE_VELOCITY 27       // vec4[capacity]: xyz (m/s); w: e_E (m²/s²), the energy of level E
#define RANRYU_LOC_SUBPARTICLE_GROUP 6            // uvec4 uniform: x classify's local size, y spawn's local size
#define RANRYU_SUBPARTICLE_MAX_LEVEL 3            // L_max <= 3: 512 sub-particles a particle (scene.cpp checks)
#define RANRYU_SUBPARTICLE_SPLIT_SHIFT 8          // levels[i] >> this is E_i: 0 unless the spawn pass split particle i
// The splat grid's fixed point: one unit is 2^-24 of V·ΣW (≈ 1 inside liquid at rest), so a uint
// holds sums up to 256 and a sub-particle's term is rounded by at most 2^-25 (engine/surface/level_set.h).
#define RANRYU_SUBPARTICLE_SPLAT_SCALE 16777216.0
// The level set's kernel radius of a level-E sub-particle, R_E = max(R·2^-E, this · node spacing):
// a narrower kernel is sampled by too few nodes to keep its volume (engine/surface/level_set.h).
#define RANRYU_SUBPARTICLE_KERNEL_FLOOR 2.0

// The sub-particle passes' constants (std140), written once by Subparticles (and when the particle
// count changes). Level L_i = the number of k in [0, levels) with ê_i >= level_energy[k].
RANRYU_STRUCT(SubparticleParams) {
    vec4 level_energy;      // xyz: ê (m²/s²) at which L reaches 1, 2, 3: e_th·2^(2βk); +inf past `levels`
    vec4 energy_scale;      // xyz: e_E / ê at E = 1, 2, 3: 2^(-2βE)
    float spacing;          // dx (m): the parents' spacing
    float beta;             // the noise's octave falloff β
    float coherence_time;   // T (s) of the carried noise
    float inv_sigma;        // 1/σ, σ the rms of |w| over one octave of the curl noise
    int noise_lmax;         // the force's finest octave; level E samples octave noise_lmax + E
    uint tile_size;         // n: noise tiles of n³
    uint levels;            // L_max (1..3)
    uint budget;            // most sub-particles (<= the buffers' capacity)
    uint particle_count;    // parents
    uint pad0;
    uint pad1;
    uint pad2;
}
RANRYU_STRUCT_END(SubparticleParams, 80)

// The sub-particles' GPU-side state (std430 SSBO); also the indirect argument buffer: dispatch at
// byte 0 (glDispatchComputeIndirect of the spawn and splat passes), draw at 16 (glDrawArraysIndirect).
RANRYU_STRUCT(SubparticleState) {
    uvec4 dispatch;   // xyz: workgroups of the spawn and splat passes (rows, surface/dispatch_2d.glsl); w: sub-particles
    uvec4 draw;       // glDrawArraysIndirect: 4 vertices (an impostor quad), instances = sub-particles, 0, 0
    uvec4 counts;     // xyz: n_1, n_2, n_3, the particles whose raw level L_i is 1, 2, 3; w: their sum
    uvec4 offsets;    // xyz: first sub-particle of level list 1, 2, 3; w: particles split (0 when C = 0)
    uvec4 limits;     // x: the cap C; y: the raw finest level max L_i; z: sub-particles the raw levels
                      // would need (saturates at 2^32 - 1); w: the budget
}
RANRYU_STRUCT_END(SubparticleState, 80)
// ---- end turbulence

#ifdef __cplusplus
}  // namespace ranryu::gpu
#endif
#endif
