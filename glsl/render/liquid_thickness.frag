#version 430
// The liquid's thickness along each view ray, every layer (no depth test, no culling; ADD blending
// into R32F): signed_eye_distance (water.glsl), −t on front faces, +t on back faces, t the eye
// distance clipped to the opaque scene's, min(|x − eye|, t_opaque) (R12). Over a closed mesh the sum
// is the length of the ray inside the liquid in front of the opaque scene. docs/RENDERING.md (R5).
// Drawn at 1/THICKNESS_DIVISOR of the frame's size (defined by the renderer; opaque_distance).
// rasterise_layers.comp computes the same sum without the raster hardware (R14).
#include "water.glsl"

in vec3 v_world;
layout(location = 0) out float out_thickness;

void main() { out_thickness = signed_eye_distance(v_world, gl_FragCoord.xy, gl_FrontFacing); }
