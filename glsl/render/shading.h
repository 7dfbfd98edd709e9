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

#endif
