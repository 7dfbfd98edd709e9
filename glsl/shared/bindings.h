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
#define RANRYU_UBO_SIM 1     // SimParams: integration and tank
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
#define RANRYU_SSBO_DENSITY 12         // vec4[n]: x density, y pressure
#define RANRYU_SSBO_ACCEL 13           // vec4[n]: xyz acceleration
#define RANRYU_SSBO_REDUCE 14          // uint[]: reductions (max speed, max acceleration, guard)
#define RANRYU_SSBO_BOUNDARY 15        // vec4[m]: boundary particles, xyz position, w volume psi
#define RANRYU_SSBO_STEP 16            // StepState: the adaptive time step, on the GPU
#define RANRYU_SSBO_SCRATCH 17         // uint[]: pass-local scratch

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

#ifdef __cplusplus
}  // namespace ranryu::gpu
#endif
#endif
