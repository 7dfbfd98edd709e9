#version 430
// Opens a frame's record in StepState, one invocation: the frame must cover sph frame time plus
// whatever the last frame left (frame_left carries over), in `substeps` substeps.
#include "fluid.glsl"

layout(local_size_x = 1) in;
layout(location = RANRYU_LOC_COUNT) uniform uint substeps;
layout(location = RANRYU_LOC_AUX) uniform uint frame_index;
layout(location = RANRYU_LOC_SHIFT) uniform float frame_dt;

void main() {
    step.frame_left = max(step.frame_left, 0.0) + frame_dt;
    step.substeps_left = substeps;
    step.frame_max_speed = 0u;
    step.frame_max_density = 0u;
    step.frame_min_dt = uintBitsToFloat(0x7F800000u);   // +inf
    step.frame_substeps = 0u;
    step.nan_count = 0u;
    step.nan_index = 0xFFFFFFFFu;
    step.escaped_count = 0u;
    step.escaped_index = 0xFFFFFFFFu;
    step.speed_index = 0u;
    step.density_index = 0u;
    step.speed_position = vec4(0.0);
    step.density_position = vec4(0.0);
    step.front = 0u;
    step.frame = frame_index;
    step.iterations = uvec4(0u);
    step.unconverged = uvec4(0u);
    step.issued = 0u;
    step.issued_divergence = 0u;
    step.error = vec4(0.0);
    step.peak_error = 0u;
}
