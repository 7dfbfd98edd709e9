// The frame's fastest and densest particles (shared/bindings.h FrameExtreme): a recording pass keeps
// its workgroup's largest value, a particle that has it and that particle's position in the entry its
// workgroup owns; record_extremes.comp folds the entries at the frame's end.
//
// Needs fluid.glsl and the pass's local size declared before it. Entry 2 s + kind belongs to the
// workgroup whose first particle is s · RANRYU_EXTREME_SPAN, and the Step block holds the entries of
// ceil(particle_count / RANRYU_EXTREME_SPAN) spans (engine/sim/fluid.cpp Fluid::step_bytes): so a
// recording pass dispatches one-dimensional workgroups over the particle count (Program::dispatch)
// with a local size that the span divides, which the declaration below checks when it compiles.
uint extreme_span_check_[gl_WorkGroupSize.x % uint(RANRYU_EXTREME_SPAN) == 0u ? 1 : -1];

// Invocation 0 of the workgroup, with the workgroup's maximum (bits, particle index: workgroup_max())
// and that particle's position. The frame's value itself is also raised in StepState by an atomicMax
// (frame_max_speed, frame_max_density), so that the record holds the maximum so far between passes
// (tests read it there); the particle and its position are kept in the entry only. A later step's value replaces the
// entry only when larger, so the entry ends the frame with its workgroups' largest, recorded at the
// first step that reached it.
void keep_extreme(uint kind, uvec2 m, vec3 x) {
    if (kind == RANRYU_EXTREME_SPEED) atomicMax(step.frame_max_speed, m.x);
    else atomicMax(step.frame_max_density, m.x);
    uint e = 2u * (gl_WorkGroupID.x * gl_WorkGroupSize.x / uint(RANRYU_EXTREME_SPAN)) + kind;
    if (m.x > extreme[e].bits) {
        extreme[e].bits = m.x;
        extreme[e].index = m.y;
        extreme[e].position = vec4(x, 0.0);
    }
}
