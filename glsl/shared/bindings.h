// Binding points and parameter structs shared by C++ and GLSL.
//
// This file is compiled by both languages, so it keeps to what both understand: #define for uniform
// binding points and locations (GLSL 4.30 layout qualifiers take literals only), and structs of vec4/mat4 and groups of four
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

// ---- shader storage blocks ----
// Storage blocks have no binding numbers here: each program gives its active blocks their own slots at
// link, and the engine binds its buffers by block name (engine/shader/program.h, StorageSet). The
// per-particle arrays are documented where they are declared (glsl/sim/fluid/*.glsl and each pass).

// ---- explicit uniform locations (small per-dispatch values; never looked up by name) ----
#define RANRYU_LOC_COUNT 0     // uint: number of items this dispatch covers
#define RANRYU_LOC_SHIFT 1     // uint: radix sort digit shift
#define RANRYU_LOC_STAGE 2     // uivec2 / uint: bitonic sort (block size k, stride j)
#define RANRYU_LOC_AUX 3       // uint or uvec2: pass-specific
#define RANRYU_LOC_EMIT_NOZZLE 4     // vec4: the emitter's nozzle centre (m), w: slots a side (glsl/sim/fluid/emit_particles.comp)
#define RANRYU_LOC_EMIT_VELOCITY 5   // vec4: xyz the poured particles' velocity (m/s), w: the spacing (m)

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

// The uniform grid of the neighbour search (docs/METHOD.md §1): cells of size h cover the domain.
RANRYU_STRUCT(GridParams) {
    vec4 origin;        // xyz: lower corner of cell (0,0,0) (m); w: cell size (m) = kernel support h
    uvec4 dims;         // xyz: cells per axis; w: number of keys (cells, or the Morton code range)
    uint count;         // particles to hash
    uint morton;        // 1: Morton (Z-order) keys; 0: linear keys i + j*nx + k*nx*ny (the talk's)
    uint key_max;       // largest key any particle can get
    uint pad0;
}
RANRYU_STRUCT_END(GridParams, 48)

// The SPH model's constants; docs/SPH.md gives every equation these enter.
RANRYU_STRUCT(SphParams) {
    vec4 gravity;         // xyz (m/s^2)
    vec4 domain_min;      // xyz: the guard's bounds; a fluid particle outside has escaped (m)
    vec4 domain_max;      // w: 1 when the tank is closed (a lid at the tank's top), else 0
    float h;              // kernel support (m), eq. (1)
    float mass;           // particle mass m = rho0 * dx^3 (kg)
    float rest_density;   // rho0 (kg/m^3)
    float stiffness;      // Tait B = rho0 c^2 / 7 (Pa), eq. (3)
    float viscosity;      // kinematic nu (m^2/s), eq. (5)
    float sound_speed;    // c (m/s) of the time step: WCSPH's sound speed, 0 for DFSPH
    float spacing;        // dx (m)
    float cfl;            // Courant number of eq. (7), 0.4
    float force_factor;   // factor of the force condition of eq. (7), 0.25
    float dt_max;         // largest substep (s): sph.max_time_step, at most the frame
    float dt_floor;       // guard: a substep below this has collapsed (s)
    float density_limit;  // guard: rho / rho0 above this is exploding
    float speed_limit;    // guard: |v| above this is exploding (m/s)
    uint particle_count;
    uint boundary_count;
    float front_band;     // surge front: particles below floor + this count (m)
    float artificial_viscosity;   // WCSPH: alpha of eq. (5a), Monaghan's on approaching pairs; 0: none
    // The kernel's constants, from h (sim::sph_params): 1/h, 8/(pi h^3) of W and 48/(pi h^4) of grad W
    // (eq. (1)). Read as operands in the neighbour walks (glsl/sim/fluid/fluid.glsl kernel_w(r),
    // kernel_grad(d, r)), where constants derived from h in the loop were recomputed every pair.
    float inv_h;
    float w_scale;
    float grad_scale;
}
RANRYU_STRUCT_END(SphParams, 128)

// The adaptive time step, the instability guard's findings and the pressure solver's iteration
// record, kept on the GPU (std430 storage block Step). Maxima of non-negative floats are kept as their
// bits: for x, y >= 0, floatBitsToUint orders like the floats, so atomicMax on uint finds the float maximum.
RANRYU_STRUCT(StepState) {
    float dt;                 // this substep's dt (s)
    float time;               // simulated time (s)
    float frame_left;         // simulated time this frame still has to cover (s)
    uint substeps_left;       // substeps issued for this frame that have not run yet
    uint max_speed;           // bits of max |v| over the last substep (input of the time step)
    uint max_accel;           // bits of max |a| over the last substep (WCSPH: all forces; DFSPH: non-pressure)
    uint frame_max_speed;     // bits of max |v| over this frame so far
    uint frame_max_density;   // bits of max rho/rho0 over this frame so far
    float frame_min_dt;       // smallest stable dt (CFL and force conditions) this frame (s)
    uint frame_substeps;      // substeps run this frame
    uint nan_count;           // particle updates with a non-finite value this frame
    uint nan_index;           // lowest index among them (sorted order), or 0xFFFFFFFF
    uint escaped_count;       // particles outside the domain this frame
    uint escaped_index;       // lowest index among them, or 0xFFFFFFFF
    uint speed_index;         // a particle at the frame's max speed (FrameExtreme: set at the frame's end)
    uint density_index;       // a particle at the frame's max density (likewise)
    uint front;               // bits of the surge front: max (x - domain_min.x) of particles within front_band of domain_min.y
    uint frame;               // frame number these findings belong to
    uint steps;               // substeps since the start
    uint live_count;          // particles not parked: the scene's, and those the emitter has poured in since
                              // (engine/sim/fluid.h); never more than particle_count
    // An iterative pressure solver's record of this frame (docs/DFSPH.md (D6); zero for WCSPH; PBF,
    // docs/PBF.md: its fixed iterations in x and z, the rest zero).
    // Solve 0 is the density solve, 1 the divergence solve.
    uvec4 iterations;         // xy: iterations this frame of solve 0, 1 (summed over its steps); zw: the most in one step
    uvec4 unconverged;        // xy: steps this frame whose solve 0, 1 stopped at the issued cap above its bound
    vec4 error;               // xy: the solves' last mean error, summed over this frame's steps (units of rho0);
                              // zw: the largest of them
    float stable_dt;          // this substep's stable dt: dt before the frame's remainder is spread (s)
    float iteration_dt;       // the step the density solve's iterations allow (docs/DFSPH.md (D8)): a bound
                              // on dt kept from step to step; sph.dt_max where no solve sets it (s)
    uint issued;              // DFSPH: density-solve iterations the CPU issued this frame (its caps), summed over
                              // its steps; iterations.x is what ran of them, the rest dispatched no work
    uint issued_divergence;   // the same for the divergence solve
    vec4 speed_position;      // xyz: where speed_index was when its speed was recorded (the end of its step, m)
    vec4 density_position;    // xyz: where density_index was when its density was computed (m)
    uint peak_error;          // DFSPH: bits of the largest particle error e_i/rho0 a density solve stopped with
                              // this frame (SolveState.peak of its last iteration; docs/DFSPH.md (D6))
    uint pad0, pad1, pad2;
}
RANRYU_STRUCT_END(StepState, 192)

// The frame's fastest and densest particles, kept per span of RANRYU_EXTREME_SPAN particles after the
// StepState in the Step block (glsl/sim/fluid/fluid.glsl: Step.extreme[]): entry 2 s + kind (kind
// RANRYU_EXTREME_SPEED or RANRYU_EXTREME_DENSITY) holds the largest value this frame of the workgroups
// that begin at particle s · RANRYU_EXTREME_SPAN (its float's bits, as StepState keeps maxima), a
// particle that has it and where that particle was. Each entry has one writer, its workgroup's
// invocation 0, since every recording pass's local size is a multiple of the span
// (glsl/sim/fluid/extremes.glsl): no two workgroups race on an index or a position, which a
// maximum raised by atomicMax and the index written after it did. record_extremes.comp folds them
// into StepState's frame_max_*, *_index and *_position at the frame's end and clears them.
RANRYU_STRUCT(FrameExtreme) {
    uint bits;       // the largest value of the entry's workgroups this frame (0: none yet)
    uint index;      // a particle that has it (sorted index at its step)
    uint pad0, pad1;
    vec4 position;   // xyz: where that particle was when its value was recorded (m)
}
RANRYU_STRUCT_END(FrameExtreme, 32)
#define RANRYU_EXTREME_SPAN 128    // particles an entry covers; every recording pass's local size is a multiple
#define RANRYU_EXTREME_SPEED 0     // |v| at a step's end (the integrations, glsl/sim/fluid/motion.glsl)
#define RANRYU_EXTREME_DENSITY 1   // rho/rho0 (the density passes)

// ---- DFSPH (engine/sim/solvers/dfsph.h, glsl/sim/dfsph/; docs/DFSPH.md) ----
#define RANRYU_UBO_DFSPH 8   // DfsphParams

// The DFSPH passes' constants (std140), written at start and when the CPU changes its iteration caps.
RANRYU_STRUCT(DfsphParams) {
    float eta;                   // density solve: bound on the mean error, units of rho0 (D6)
    float eta_divergence;        // divergence solve: likewise for dt·Drho/Dt (D6)
    float relaxation;            // omega of (D6)
    float warm_start;            // w of (D6), the density solve's
    uint min_iterations;         // density solve
    uint min_divergence_iterations;
    uint issued;                 // iterations the CPU issues a density solve this frame (its cap)
    uint issued_divergence;      // likewise, divergence solve
    float error_scale;           // SolveState.error_sum units per unit of summed error: 2^31 / particle_count
    uint deficient_neighbours;   // (D5): fewer neighbours than this, no divergence correction
    float boundary_viscosity;    // nu_b of (D7) (m^2/s)
    uint groups;                 // workgroups of the iteration passes over every particle
    float warm_start_divergence; // w of (D6), the divergence solve's
    float boundary_relaxation;   // omega_b of (D9): the boundary rows' l1-Jacobi relaxation
    float chebyshev;             // rho of (D6)'s Chebyshev acceleration of the density solve; 0: off
    uint complementarity_error;  // 1: the density solve's error counts |r_i| where kappa_i > 0 (D6); 0: max(r_i, 0)
    uint shrink_step_above;      // (D8): a density solve of more iterations than this shrinks the step; 0: off
    uint grow_step_below;        // (D8): one of fewer lets it grow
    float iteration_dt_min;      // (D8): the least step the iterations may ask for (s)
    float eta_peak;              // density solve: bound on the largest particle's error e_i/rho0 (D6); 0: none
    float stabilisation;         // gamma of (D12): the density solve's blend of the compact Laplacian; 0: off
    uint pad0, pad1, pad2;
}
RANRYU_STRUCT_END(DfsphParams, 96)

// One solve's state on the GPU (std430 storage block Solve; one per solve, RANRYU_DFSPH_SOLVE_STRIDE
// bytes apart), also the indirect arguments of its iterations: the last workgroup of each residual
// pass sets dispatch.x, correct_groups and rows_groups to 0 once the solve has converged or reached its cap, so the
// iterations the CPU issued beyond that dispatch no work.
RANRYU_STRUCT(SolveState) {
    uvec4 dispatch;      // xyz: workgroups of the next iteration's accelerate pass; w: unused
    uint iterations;     // iterations run in this solve so far
    uint error_sum;      // this iteration's Σ_i min(max(r_i, 0)/rho0, 1), in units of 1/error_scale
    uint groups_done;    // workgroups of this iteration's residual pass that have added their part
    uint solve;          // 0: the density solve, 1: the divergence solve (its StepState fields)
    float weight;        // (D10): the Chebyshev weight w_k of this solve's next iteration k, once k >=
                         // kChebyshevStart (glsl/sim/dfsph/dfsph.glsl); opens at w = 2/(2 - rho_c^2)
    uint correct_groups; // with correct_y, correct_z: the indirect arguments of its residual pass: the
    uint correct_y;      // fluid's workgroups, then with the boundary rows of (D9) the rows' (set by the
    uint correct_z;      // solve's prepare pass)
    uint error_peak;     // this iteration's largest min(e_i/rho0, 1) over the particles, as its float's bits
                         // (atomicMax: non-negative floats order as their bits)
    float peak;          // the largest e_i/rho0 of the solve's last decided iteration
    uint rows_groups;    // with rows_y, rows_z: the indirect arguments of the eliminated rows' passes
    uint rows_y;         // (docs/DFSPH.md (D13)): the rows' workgroups in a density solve with
    uint rows_z;         // sph.eliminate_boundary_rows (set by its prepare pass), 0 once it has converged
    uint pad0, pad1, pad2;
}
RANRYU_STRUCT_END(SolveState, 80)
#define RANRYU_DFSPH_SOLVE_STRIDE 256   // bytes between the two SolveStates (a multiple of any offset alignment)

// The boundary particles that are rows of the solve this step (docs/DFSPH.md (D9); std430 block
// BoundaryRows, followed there by one mark a boundary particle): those within h of a fluid particle,
// listed by the density pass's walk (an atomic append to BoundaryList, each once: its mark takes the
// step's epoch), then sized for the indirect dispatch of the boundary passes by "size_boundary_rows",
// which also opens the next step's list.
RANRYU_STRUCT(BoundaryRowsState) {
    uvec4 dispatch;   // xyz: workgroups of the boundary passes over this step's rows; w: unused
    uint rows;        // rows this step (BoundaryList[0, rows))
    uint count;       // rows the density pass has listed so far (the next step's, once sized)
    uint epoch;       // the step's mark: a boundary particle listed with mark epoch − 1 was a row the step before
    uint pad0;
}
RANRYU_STRUCT_END(BoundaryRowsState, 32)
// ---- end DFSPH

// ---- PBF (engine/sim/solvers/pbf.h, glsl/sim/pbf/; docs/PBF.md) ----
#define RANRYU_UBO_PBF 9   // PbfParams
// (P10): the largest warm-start acceleration, in units of |g|. The warm start carries the weight of
// the fluid above a particle (|a^p| = |g| at rest), not the impulses of an impact, which the
// iterations answer (docs/PBF.md (P10)).
#define RANRYU_PBF_WARM_CAP 2.0

// The PBF passes' constants (std140), written once at start, in SI units.
RANRYU_STRUCT(PbfParams) {
    float epsilon;        // epsilon of (P4): the constraint's relaxation (1/m^2)
    float s_corr_scale;   // k dx^2 of (P5) (m^2)
    float s_corr_n;       // n of (P5)
    float inv_w_dq;       // 1 / W(|dq|) of (P5) (m^3)
    float xsph;           // c of (P7)
    float vorticity;      // epsilon of (P8) (m/s)
    uint iterations;      // constraint iterations a substep
    float warm_start;     // w of (P10); 0: no warm start
}
RANRYU_STRUCT_END(PbfParams, 32)
// ---- end PBF

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
// Storage blocks (bound by name): SurfaceGridState (SurfaceGrid: where the φ grid lies this frame,
// GPU-written), Phi (float[nodes]: φ at the grid nodes), Mesh (MeshState: marching cubes' indirect
// arguments and totals), CellVertices (uint[cells]: vertices each cell emits, 0, 3, ..., 15), McBlocks
// (uvec2[blocks]: active cells and vertices per classify workgroup, then their exclusive prefix sums),
// ActiveCells (uvec2[]: compacted active cells, cell index and first vertex), MeshVertices
// (MeshVertex[]: the mesh, non-indexed triangles), McTriangles (int[4096]: the triangle table of
// surface/mc_tables.h, uploaded once). With anisotropic kernels (docs/SURFACE.md): SurfaceCentres
// (vec4[particles], cell order: smoothed centre x̄_i, w the stretch s_3), SurfaceAxes (vec4[2·particles]:
// unit axis a_1 and s_1, then a_2 and s_2; a_3 = a_1 × a_2) and SplatGrid (uint[nodes]: the kernels'
// fixed-point sum).
#define RANRYU_UBO_SURFACE 4             // SurfaceParams: the level set's constants
#define RANRYU_LOC_SURFACE_CAPACITY 4    // uvec4 uniform: x vertices, y active cells, z cells (MC buffer capacities)
#define RANRYU_LOC_SURFACE_GROUP 5       // uvec4 uniform: workgroup size of the pass whose indirect arguments this pass writes

// Level set constants (docs/METHOD.md §7): φ(x) = volume · Σ_i W(|x - x_i|, kernel_radius) - iso, with W
// the cubic spline of glsl/sim/kernel.glsl. engine/surface/level_set.h explains the defaults.
RANRYU_STRUCT(SurfaceParams) {
    uvec4 max_dims;        // xyz: most nodes per axis (the grid coarsens to fit); w: unused
    float node_spacing;    // finest node spacing (m)
    float kernel_radius;   // R: support of W (m)
    float volume;          // V: particle volume dx^3 (m^3); V·ΣW is ≈ 1 inside liquid at rest
    float iso;             // the level: φ = 0 where V·ΣW = iso
    uint particle_count;
    float search_margin;   // (m): the gather also searches cells this much beyond R (particles moved since the sort)
    float bounds_margin;   // (m): the grid reaches this much beyond R around the particles (sub-particles' reach; else 0)
    uint max_nodes;        // node budget of the grid (docs/SURFACE.md (S9)); 0: max_dims alone bound it
    // Anisotropic kernels (docs/SURFACE.md (S1)-(S8); used when the level set is built with them):
    vec4 anisotropy;       // x: r, the neighbourhood radius (m); y: λ, centre smoothing; z: k_s (1/m²); w: k_r
    vec4 anisotropy_limits;   // x: k_n; y: N_ε (neighbours, self included); z: s_max, the largest stretch; w: unused
}
RANRYU_STRUCT_END(SurfaceParams, 80)

// Where the φ grid lies (std430 SSBO). The level set writes it on the GPU each frame; any other
// producer of φ fills origin and dims, which is all marching cubes reads.
RANRYU_STRUCT(SurfaceGrid) {
    vec4 origin;         // xyz: node (0,0,0) (m); w: node spacing (m)
    uvec4 dims;          // xyz: nodes per axis (0 when there is nothing to mesh); w: nodes in all
    uvec4 bounds_min;    // xyz: the particles' lower corner as order-preserving bits (surface/ordered_float.glsl)
    uvec4 bounds_max;    // xyz: upper corner, likewise
    uvec4 dispatch;      // xyz: glDispatchComputeIndirect groups of the level-set pass; w: 1 if coarsened to fit max_dims
}
RANRYU_STRUCT_END(SurfaceGrid, 80)

// Marching cubes' edge vertices keep this part of a node spacing from the edge's nodes (t of
// mc_emit.comp clamped to [margin, 1 - margin]): a crossing at a node, where φ is zero or within a
// float of it, would otherwise put the vertices of every edge at that node on one point, and the mesh
// would have zero-area triangles and read as non-manifold once its vertices are welded by position
// (docs/SURFACE.md (S7)). Shared by the GPU pass and the CPU's surface::polygonise_cpu().
#define RANRYU_MC_EDGE_MARGIN 1e-3

// DFSPH's kernel-gradient correction (docs/DFSPH.md (D11)): L_i = I where det M_i is at most
// RANRYU_CORRECTION_NONE, M_i^-1 from RANRYU_CORRECTION_FULL, linear between. Shared by the density
// pass (glsl/sim/dfsph/compute_density.comp) and the CPU reference (tests/reference/dfsph_reference.h).
#define RANRYU_CORRECTION_NONE 0.4
#define RANRYU_CORRECTION_FULL 0.7

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

// ---- turbulence (engine/turbulence/, glsl/turbulence/): docs/METHOD.md §3, §4 ----
// Wavelet analysis (engine/turbulence/wavelet.h, glsl/turbulence/analyse_velocity.comp), storage
// blocks WaveletEnergy (vec4[particles]: xyz û_i, w ê_i = ½|û_i|², in the analysed cell order) and
// WaveletConstants (WaveletParams, read-only).

// The wavelet pass's constants (docs/METHOD.md §3), written by WaveletAnalysis::analyse().
RANRYU_STRUCT(WaveletParams) {
    float scale;            // s (m): ψ is evaluated at (x_i - x_j)/s
    float truncation;       // R: neighbours with |x_i - x_j|/s < R are summed; R·s <= the grid's cell
    uint particle_count;    // particles analysed
    uint pad0;
}
RANRYU_STRUCT_END(WaveletParams, 16)
// Noise synthesis (engine/turbulence/noise.h, glsl/turbulence/curl_noise.glsl, sample_field.comp):
// storage blocks NoiseTiles (float[3·n³]: the three wavelet-noise potential tiles, x + n·(y + n·z)) and
// NoiseField (float[points·3]: sampled y, C order of shape (nx, ny, nz, 3)).
#define RANRYU_UBO_NOISE 5                // NoiseParams: the sampling grid and the octave sum

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
// the fluid's positions, accelerations and step, WaveletEnergy, NoiseTiles, UBO 3 and 5 (NoiseParams:
// lmin, lmax, beta, tile_size) and these uniforms, and reads and re-seeds the carried noise (NoiseSeeds).
#define RANRYU_LOC_TURBULENCE_AMPLITUDE 1   // float: A (1/m), the force's amplitude
#define RANRYU_LOC_COHERENCE_TIME 2         // float: T (s), the carried noise's re-seeding period

// Carried noise (glsl/turbulence/carried_noise.glsl): per fluid particle, the positions at which its
// two noise phases were last seeded, in the storage block NoiseSeeds (NoiseSeed[particles], in the
// fluid's cell order): a carried array of the fluid (engine/sim/fluid.h), which the reorder moves.
RANRYU_STRUCT(NoiseSeed) {
    vec4 phase[2];   // xyz: where the phase was seeded (m); w: the epoch it was seeded in (float, -1: never)
    vec4 value[2];   // xyz: the phase's octave sum y(q_p), fixed for the epoch (carried_noise.glsl); w: 0
}
RANRYU_STRUCT_END(NoiseSeed, 64)

// Sub-particles (engine/turbulence/subparticles.h, glsl/turbulence/subparticles/), storage blocks:
//   Subparticles           SubparticleState: counts, cap, indirect arguments (std430)
//   SubparticleLevels      uint[particles]: L_i | E_i << RANRYU_SUBPARTICLE_SPLIT_SHIFT, in the fluid's cell order
//   SubparticleBlocks      uvec4[classify workgroups]: xyz per-level counts, then their exclusive prefix sums
//   SplatGrid              uint[φ nodes]: the sub-particles' V·ΣW in fixed point (level set only)
//   SubparticleLists       uint[levels · particles]: level L's split parents at (L-1)·particles, in cell order
//   SubparticlePositions   vec4[capacity]: xyz (m); w: effective level E (1..3), as a float
//   SubparticleVelocities  vec4[capacity]: xyz (m/s); w: e_E (m²/s²), the energy of level E
#define RANRYU_UBO_SUBPARTICLES 6                 // SubparticleParams
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
