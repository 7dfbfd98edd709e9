// Constants of the surface shading modes (glsl/render/surface_*.frag and the water mode's passes,
// glsl/render/water.glsl), shared by C++ and GLSL so that the CPU references in
// tests/gl/surface_shading_test.cpp and tests/gl/water_test.cpp use the very same numbers.
// docs/RENDERING.md gives every equation these enter.
#ifndef RANRYU_RENDER_SHADING_H
#define RANRYU_RENDER_SHADING_H

// Refractive indices for the Fresnel mode: air outside, water (20 °C, 589 nm) inside.
#define RANRYU_IOR_AIR 1.0
#define RANRYU_IOR_WATER 1.333

// ---- The water mode (Shading::water, docs/RENDERING.md (R1)-(R12)) ----
// The sun is the scene's light (light.direction, FrameParams.light_dir, light_color).
// Absorption of pure water (1/m) at ~650, 550 and 450 nm, the red, green and blue channels' middles
// (Pope & Fry 1997: 0.340, 0.0565, 0.0092 at those wavelengths). The default surface.absorption is
// RANRYU_WATER_ABSORPTION_SCALE times it: a 0.5 m tank then tints as ~6 m of clear water would, the
// depth at which a pool or the sea reads as blue (docs/RENDERING.md (R6)).
#define RANRYU_WATER_ABSORPTION_PURE 0.340, 0.0565, 0.0092
#define RANRYU_WATER_ABSORPTION_SCALE 12.0
// The procedural sky (sky(), glsl/common/frame.glsl; (R2)), linear: horizon, zenith and ground
// colours, and the rate k (per unit of d_y) at which the ground below the horizon fades into its haze.
#define RANRYU_SKY_HORIZON 0.80, 0.86, 0.92
#define RANRYU_SKY_ZENITH 0.22, 0.42, 0.78
#define RANRYU_SKY_GROUND 0.30, 0.28, 0.26
#define RANRYU_SKY_HAZE 8.0
// Sun highlight on the water, Blinn-Phong: k_s (in units of the sun's colour) and exponent (R4).
#define RANRYU_WATER_SPECULAR 2.0
#define RANRYU_WATER_SHININESS 400.0
// Floor and walls (R9): square tiles of RANRYU_TILE_SIZE (m) with grout lines RANRYU_GROUT_WIDTH wide
// at each tile's lower edges, inside the tank; the ground beyond the tank's footprint is plain.
#define RANRYU_TILE_SIZE 0.05
#define RANRYU_GROUT_WIDTH 0.004
#define RANRYU_TILE_ALBEDO 0.70, 0.80, 0.82
#define RANRYU_GROUT_ALBEDO 0.38, 0.40, 0.42
#define RANRYU_GROUND_ALBEDO 0.42, 0.38, 0.33
// The sun's shadow map of the liquid (R10): texels per side, the depth bias (m) and the PCF radius
// in texels ((2r + 1)^2 taps).
#define RANRYU_SHADOW_MAP_SIZE 2048
#define RANRYU_SHADOW_BIAS 0.002
#define RANRYU_SHADOW_PCF_RADIUS 1
// Uniform locations of the water mode's programs: the sun's orthographic world-to-clip matrix (mat4)
// and the origin of the sun depth s(x) (vec4, xyz) of (R8).
#define RANRYU_LOC_SHADOW_MATRIX 10
#define RANRYU_LOC_SHADOW_ORIGIN 11
// Texture units (sampler bindings) of the water mode's passes.
#define RANRYU_TEX_SCENE_COLOR 0      // the opaque scene, linear rgb (RGBA16F)
#define RANRYU_TEX_SCENE_DEPTH 1      // its depth buffer
#define RANRYU_TEX_THICKNESS 2        // the liquid's thickness along each view ray (m, R32F)
#define RANRYU_TEX_SHADOW_NEAR 3      // the sun depth s of the liquid nearest the sun (m, R32F)
#define RANRYU_TEX_SHADOW_THICKNESS 4 // the liquid's thickness along the sunlight (m, R32F)
#define RANRYU_TEX_SCENE_LIT 5        // the scene cache: rgb the opaque scene lit with no liquid, C_lit; a its sun share q (R13; RGBA16F)
// Image units of the water mode's compute passes (fill_image.comp, compose.comp).
#define RANRYU_IMG_TARGET 0           // fill_image.comp: the R32F image it fills
#define RANRYU_IMG_SCENE 0            // compose.comp: the opaque scene with this frame's shadow, linear (RGBA16F)
#define RANRYU_IMG_FRAME 1            // compose.comp: the frame's colour, display-encoded (RGBA8)
// Uniform location of fill_image.comp's value (vec4; .r is stored).
#define RANRYU_LOC_FILL_VALUE 12

// The compute raster of the liquid's mesh (WaterOptions::Raster::compute, docs/RENDERING.md (R14)):
// size_raster.comp, rasterise_layers.comp and decode_raster.comp. The targets are the R32F textures
// the GL draws blend into, bound as 32-bit integer images (same size class), decoded in place.
#define RANRYU_RASTER_SUBPIXEL_BITS 8            // window coordinates snapped to 1/256 pixel
#define RANRYU_RASTER_FIXED_SCALE 1048576.0      // 2^20 steps a metre: the ±t and ±s sums (r32i); |sum| < 2^11 m
#define RANRYU_RASTER_GUARD 4.0                  // clip-space guard band |x|, |y| <= 4w: fixed-point products stay below 2^51
#define RANRYU_LOC_RASTER_GROUP 13               // uvec4: x rasterise_layers' local size, y the draw's vertex count's word in its buffer
#define RANRYU_IMG_RASTER_SUM 0                  // r32i: Σ ±t (eye) or Σ ±s (sun), fixed point
#define RANRYU_IMG_RASTER_NEAR 1                 // r32ui: the sun's view: min of ordered_bits(s) (glsl/surface/ordered_float.glsl)
// Triangles whose pixels (bounding box within the target) exceed RANRYU_RASTER_LARGE_PIXELS are left to
// a second dispatch, RANRYU_RASTER_LARGE_TILES workgroups each, listed (up to RANRYU_RASTER_LARGE_CAPACITY
// a view; more are done by their own invocation): one invocation never walks more than
// pixels / (tiles · local size) of one, and a thread of the first dispatch no more than 1024.
#define RANRYU_RASTER_LARGE_PIXELS 1024
#define RANRYU_RASTER_LARGE_TILES 64u
#define RANRYU_RASTER_LARGE_CAPACITY 16384u

// The compute raster of the particles' sphere impostors (ImpostorOptions::Raster::compute,
// docs/RENDERING.md (R15)): rasterise_impostors.comp and shade_impostors.frag. Two R32F textures of
// the frame's size bound as r32ui images: the nearest window depth's bits, then the id + 1 of the
// sphere there (0: none; a particle's index, or a sub-particle's with the top bit set). A particle whose silhouette's bounding box holds more than
// RANRYU_IMPOSTOR_LARGE_PIXELS pixels is listed (up to the capacity; more are done by their own
// invocation) for a second dispatch, RANRYU_IMPOSTOR_LARGE_TILES workgroups each.
#define RANRYU_IMG_IMPOSTOR_DEPTH 0
#define RANRYU_IMG_IMPOSTOR_ID 1
#define RANRYU_IMPOSTOR_LARGE_PIXELS 256
#define RANRYU_IMPOSTOR_LARGE_TILES 16u
#define RANRYU_IMPOSTOR_LARGE_CAPACITY 16384u   // ImpostorOptions::large_capacity's default

// Mesh vertex attributes (gpu::MeshVertex: position at byte 0, normal at byte 16, stride 32).
#define RANRYU_ATTR_MESH_POSITION 0
#define RANRYU_ATTR_MESH_NORMAL 1

// Explicit uniform location of the Fresnel and water modes' absorption coefficients (rgb, 1/m):
// Beer-Lambert attenuation exp(-sigma * path) of the refracted light. Set once when the scene is set.
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
