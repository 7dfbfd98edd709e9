#version 430
// The frame's fastest and densest particles, at its end, one workgroup ("record-extremes"): for each
// kind, the largest of the FrameExtreme entries the frame's steps kept (extremes.glsl), ties to the
// lowest entry, into StepState: frame_max_speed, speed_index, speed_position and frame_max_density,
// density_index, density_position (all 0 where no step recorded one). The maxima equal those the
// passes raised by atomicMax over the same values; written again here, the record's value and its
// particle come from one entry. Every entry read is cleared for the next frame. The entries are
// those of ceil(particle_count / RANRYU_EXTREME_SPAN) spans: the recording passes cover the particle
// count (extremes.glsl).
#include "fluid.glsl"

layout(local_size_x = 256) in;

shared uint best_bits_[256];
shared uint best_entry_[256];

// (bits, entry) a before b: the larger value, then the lower entry.
bool before(uint a_bits, uint a_entry, uint b_bits, uint b_entry) {
    return a_bits > b_bits || (a_bits == b_bits && a_entry < b_entry);
}

// The workgroup's largest entry of `kind`: its index in extreme[], or ~0u where every entry is 0.
uint largest(uint kind) {
    uint spans = (sph.particle_count + uint(RANRYU_EXTREME_SPAN) - 1u) / uint(RANRYU_EXTREME_SPAN);
    uint bits = 0u, entry = ~0u;
    for (uint s = gl_LocalInvocationIndex; s < spans; s += gl_WorkGroupSize.x) {
        uint e = 2u * s + kind;
        uint b = extreme[e].bits;
        if (b != 0u && before(b, e, bits, entry)) {
            bits = b;
            entry = e;
        }
    }
    best_bits_[gl_LocalInvocationIndex] = bits;
    best_entry_[gl_LocalInvocationIndex] = entry;
    barrier();
    for (uint half_ = gl_WorkGroupSize.x / 2u; half_ > 0u; half_ /= 2u) {
        if (gl_LocalInvocationIndex < half_) {
            uint o = gl_LocalInvocationIndex + half_;
            uint me = gl_LocalInvocationIndex;
            if (before(best_bits_[o], best_entry_[o], best_bits_[me], best_entry_[me])) {
                best_bits_[me] = best_bits_[o];
                best_entry_[me] = best_entry_[o];
            }
        }
        barrier();
    }
    uint r = best_entry_[0];
    barrier();   // best_*_ are reused by the next kind
    return r;
}

// Clears this invocation's entries of `kind` (after largest() has read them all: its barriers).
void clear(uint kind) {
    uint spans = (sph.particle_count + uint(RANRYU_EXTREME_SPAN) - 1u) / uint(RANRYU_EXTREME_SPAN);
    for (uint s = gl_LocalInvocationIndex; s < spans; s += gl_WorkGroupSize.x)
        extreme[2u * s + kind].bits = 0u;
}

void main() {
    uint fastest = largest(RANRYU_EXTREME_SPEED);
    uint densest = largest(RANRYU_EXTREME_DENSITY);
    if (gl_LocalInvocationIndex == 0u) {
        bool v = fastest != ~0u, d = densest != ~0u;
        step.frame_max_speed = v ? extreme[fastest].bits : 0u;
        step.speed_index = v ? extreme[fastest].index : 0u;
        step.speed_position = v ? extreme[fastest].position : vec4(0.0);
        step.frame_max_density = d ? extreme[densest].bits : 0u;
        step.density_index = d ? extreme[densest].index : 0u;
        step.density_position = d ? extreme[densest].position : vec4(0.0);
    }
    memoryBarrierBuffer();
    barrier();   // invocation 0 has read the two winners before they are cleared
    clear(RANRYU_EXTREME_SPEED);
    clear(RANRYU_EXTREME_DENSITY);
}
