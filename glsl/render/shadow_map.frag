#version 430
// The sun's view of the liquid, every layer (no depth test, no culling), into two R32F targets:
//   0: s of the fragment, blended with MIN: the sun depth of the liquid nearest the sun, s_near;
//   1: signed_sun_depth (water.glsl), blended with ADD: over a closed mesh, the length of the
//      sunlight's path inside the liquid, d_sun.
// docs/RENDERING.md (R8), (R10); the mesh is counter-clockwise seen from outside (marching_cubes.h).
// rasterise_layers.comp built with SUN_VIEW computes the same two maps without the raster hardware (R14).
#include "water.glsl"

in vec3 v_world;
layout(location = 0) out float out_near;
layout(location = 1) out float out_thickness;

void main() {
    out_near = sun_depth(v_world);
    out_thickness = signed_sun_depth(v_world, gl_FrontFacing);
}
