#version 430
// Tests only (tests/gl/interop_test.cpp). Declares the shared parameter structs as the engine's
// shaders do (std140 uniform blocks at their shared binding points; StepState, SubparticleState and
// SolveState and BoundaryRowsState std430 storage blocks, bound by name) and copies every member, as raw 32-bit words, into
// the storage block ProbeOut in the order below, followed by the values of the shared macros as GLSL
// sees them. The test builds the same sequence from the C++ structs and macros and compares bits.
//
// Output words, in order (a matrix is 16 words, column-major; a vec4/uvec4 is 4):
//   LayoutProbe:  m, v, u, f0, f1, u0, u1                                            28 words
//   SimParams:    gravity, domain_min, domain_max, dt, restitution, particle_radius,
//                 particle_count                                                     16 words
//   FrameParams:  view, proj, view_proj, eye, light_dir, light_color, material,
//                 viewport, speed_scale, tank_min, tank_max                          80 words
//   GridParams:   origin, dims, count, morton, key_max, pad0                         12 words
//   SphParams:    gravity, domain_min, domain_max, then its 20 scalars in order      32 words
//   StepState:    its 20 scalars, then iterations, unconverged, error, then its 4
//                 scalars, speed_position, density_position, peak_error and 3 pads  48 words
//   SubparticleParams: level_energy, energy_scale, then its 12 scalars in order      20 words
//   SubparticleState:  dispatch, draw, counts, offsets, limits (a std430 storage block) 20 words
//   DfsphParams:  its 20 scalars in order                                            20 words
//   SolveState:   dispatch, then its 16 scalars in order (std430)                    20 words
//   BoundaryRowsState: dispatch, rows, count, epoch, pad0 (std430)                 8 words
//   PbfParams:    its 8 scalars in order                                              8 words
//   kMacros:      the RANRYU_* macros, in the order of the array below               28 words
#include "../shared/bindings.h"

layout(local_size_x = 1) in;

layout(std140, binding = RANRYU_UBO_PROBE) uniform ProbeBlock { LayoutProbe probe; };
layout(std140, binding = RANRYU_UBO_SIM) uniform SimBlock { SimParams sim; };
layout(std140, binding = RANRYU_UBO_FRAME) uniform FrameBlock { FrameParams frame; };
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SPH) uniform SphBlock { SphParams sph; };
layout(std430) readonly buffer Step { StepState step; };
layout(std140, binding = RANRYU_UBO_SUBPARTICLES) uniform SubparticleBlock { SubparticleParams subp; };
layout(std430) readonly buffer SubparticleStateBlock { SubparticleState subs; };
layout(std140, binding = RANRYU_UBO_DFSPH) uniform DfsphBlock { DfsphParams dfsph; };
layout(std430) readonly buffer Solve { SolveState solve; };
layout(std430) readonly buffer BoundaryRows { BoundaryRowsState rows; };
layout(std140, binding = RANRYU_UBO_PBF) uniform PbfBlock { PbfParams pbf; };
layout(std430) buffer ProbeOut { uint words[]; };

const uint kMacros[28] = uint[28](
    RANRYU_UBO_FRAME, RANRYU_UBO_SIM, RANRYU_UBO_GRID, RANRYU_UBO_SPH, RANRYU_UBO_PROBE,
    RANRYU_UBO_SURFACE, RANRYU_UBO_NOISE,
    RANRYU_LOC_COUNT, RANRYU_LOC_SHIFT, RANRYU_LOC_STAGE, RANRYU_LOC_AUX,
    RANRYU_ATTR_POSITION, RANRYU_ATTR_VELOCITY,
    RANRYU_SORT_RADIX_BITS, RANRYU_SORT_RADIX_ITEMS_PER_THREAD, RANRYU_SORT_BITONIC_ITEMS_PER_THREAD,
    RANRYU_UBO_SUBPARTICLES, RANRYU_LOC_SUBPARTICLE_GROUP,
    RANRYU_SUBPARTICLE_MAX_LEVEL, RANRYU_SUBPARTICLE_SPLIT_SHIFT, uint(RANRYU_SUBPARTICLE_SPLAT_SCALE),
    RANRYU_UBO_DFSPH, RANRYU_DFSPH_SOLVE_STRIDE, RANRYU_UBO_PBF, floatBitsToUint(RANRYU_PBF_WARM_CAP),
    RANRYU_EXTREME_SPAN, RANRYU_EXTREME_SPEED, RANRYU_EXTREME_DENSITY);

uint k = 0u;
void put(float x) { words[k++] = floatBitsToUint(x); }
void put(uint x) { words[k++] = x; }
void put(int x) { words[k++] = uint(x); }
void put(vec4 x) { for (int i = 0; i < 4; ++i) put(x[i]); }
void put(uvec4 x) { for (int i = 0; i < 4; ++i) put(x[i]); }
void put(mat4 x) { for (int c = 0; c < 4; ++c) put(x[c]); }

void main() {
    put(probe.m); put(probe.v); put(probe.u); put(probe.f0); put(probe.f1); put(probe.u0); put(probe.u1);

    put(sim.gravity); put(sim.domain_min); put(sim.domain_max);
    put(sim.dt); put(sim.restitution); put(sim.particle_radius); put(sim.particle_count);

    put(frame.view); put(frame.proj); put(frame.view_proj);
    put(frame.eye); put(frame.light_dir); put(frame.light_color); put(frame.material);
    put(frame.viewport); put(frame.speed_scale); put(frame.tank_min); put(frame.tank_max);

    put(grid.origin); put(grid.dims); put(grid.count); put(grid.morton); put(grid.key_max); put(grid.pad0);

    put(sph.gravity); put(sph.domain_min); put(sph.domain_max);
    put(sph.h); put(sph.mass); put(sph.rest_density); put(sph.stiffness); put(sph.viscosity);
    put(sph.sound_speed); put(sph.spacing); put(sph.cfl); put(sph.force_factor); put(sph.dt_max);
    put(sph.dt_floor); put(sph.density_limit); put(sph.speed_limit); put(sph.particle_count);
    put(sph.boundary_count); put(sph.front_band); put(sph.artificial_viscosity);
    put(sph.inv_h); put(sph.w_scale); put(sph.grad_scale);

    put(step.dt); put(step.time); put(step.frame_left); put(step.substeps_left); put(step.max_speed);
    put(step.max_accel); put(step.frame_max_speed); put(step.frame_max_density); put(step.frame_min_dt);
    put(step.frame_substeps); put(step.nan_count); put(step.nan_index); put(step.escaped_count);
    put(step.escaped_index); put(step.speed_index); put(step.density_index); put(step.front);
    put(step.frame); put(step.steps); put(step.live_count);
    put(step.iterations); put(step.unconverged); put(step.error);
    put(step.stable_dt); put(step.iteration_dt); put(step.issued); put(step.issued_divergence);
    put(step.speed_position); put(step.density_position);
    put(step.peak_error); put(step.pad0); put(step.pad1); put(step.pad2);

    put(subp.level_energy); put(subp.energy_scale); put(subp.spacing); put(subp.beta); put(subp.coherence_time);
    put(subp.inv_sigma); put(subp.noise_lmax); put(subp.tile_size); put(subp.levels); put(subp.budget);
    put(subp.particle_count); put(subp.pad0); put(subp.pad1); put(subp.pad2);

    put(subs.dispatch); put(subs.draw); put(subs.counts); put(subs.offsets); put(subs.limits);

    put(dfsph.eta); put(dfsph.eta_divergence); put(dfsph.relaxation); put(dfsph.warm_start);
    put(dfsph.min_iterations); put(dfsph.min_divergence_iterations); put(dfsph.issued); put(dfsph.issued_divergence);
    put(dfsph.error_scale); put(dfsph.deficient_neighbours); put(dfsph.boundary_viscosity); put(dfsph.groups);
    put(dfsph.warm_start_divergence); put(dfsph.boundary_relaxation); put(dfsph.chebyshev); put(dfsph.complementarity_error);
    put(dfsph.shrink_step_above); put(dfsph.grow_step_below); put(dfsph.iteration_dt_min); put(dfsph.eta_peak);
    put(dfsph.stabilisation); put(dfsph.pad0); put(dfsph.pad1); put(dfsph.pad2);

    put(solve.dispatch); put(solve.iterations); put(solve.error_sum); put(solve.groups_done); put(solve.solve);
    put(solve.weight); put(solve.correct_groups); put(solve.correct_y); put(solve.correct_z);
    put(solve.error_peak); put(solve.peak); put(solve.rows_groups); put(solve.rows_y); put(solve.rows_z);
    put(solve.pad0); put(solve.pad1); put(solve.pad2);

    put(rows.dispatch); put(rows.rows); put(rows.count); put(rows.epoch); put(rows.pad0);
    put(pbf.epsilon); put(pbf.s_corr_scale); put(pbf.s_corr_n); put(pbf.inv_w_dq);
    put(pbf.xsph); put(pbf.vorticity); put(pbf.iterations); put(pbf.warm_start);

    for (int i = 0; i < kMacros.length(); ++i) put(kMacros[i]);
}
