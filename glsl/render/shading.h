// Constants of the surface shading modes (glsl/render/surface_*.frag), shared by C++ and GLSL so that
// the CPU references in tests/gl/surface_shading_test.cpp use the very same numbers.
#ifndef RANRYU_RENDER_SHADING_H
#define RANRYU_RENDER_SHADING_H

// Refractive indices for the Fresnel mode: air outside, water (20 °C, 589 nm) inside.
#define RANRYU_IOR_AIR 1.0
#define RANRYU_IOR_WATER 1.333

// Mesh vertex attributes (gpu::MeshVertex: position at byte 0, normal at byte 16, stride 32).
#define RANRYU_ATTR_MESH_POSITION 0
#define RANRYU_ATTR_MESH_NORMAL 1

// Explicit uniform location of the Fresnel mode's absorption coefficients (rgb, 1/m): Beer-Lambert
// attenuation exp(-sigma * path) of the refracted light. Set once when the scene is set.
#define RANRYU_LOC_ABSORPTION 8

// Particles drawn by sub-particle level (impostor.vert and impostor.frag built with RANRYU_BY_LEVEL;
// renderer.h): the parents' levels word (uint, per instance; turbulence/subparticles.h) and the draw's
// source.
#define RANRYU_ATTR_LEVEL 2
#define RANRYU_LOC_IMPOSTOR_CHILDREN 9   // uint uniform: 0 parents (levels word), 1 sub-particles (level in position.w)
// Base colours (linear rgb) of level 0 (a particle not split) to 3; a level-E sphere has radius r/2^E.
#define RANRYU_LEVEL_COLOR_0 0.10, 0.35, 0.80
#define RANRYU_LEVEL_COLOR_1 0.10, 0.70, 0.45
#define RANRYU_LEVEL_COLOR_2 0.95, 0.70, 0.15
#define RANRYU_LEVEL_COLOR_3 0.90, 0.20, 0.25

#endif
