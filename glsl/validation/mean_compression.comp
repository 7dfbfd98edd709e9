#version 430
// The compression of the fluid summed over its particles, Σ_i max(ρ_i/ρ0 − 1, 0), for the sweep's
// scene cases (engine/validation/cases.h, CompressionMeter), in two dispatches with no atomics:
//   (no define)   `groups` workgroups; invocation t of group g sums every (groups·256)-th particle
//                 from g·256 + t, the group adds its 256 sums in shared memory, Partials[g] = its total
//   TOTAL         one workgroup adds Partials[0, groups) the same way into Total.sum
// In floats: each term is within an ulp of max(ρ/ρ0 − 1, 0) relative (ρ − ρ0 is exact near ρ0), and
// every addition is of two non-negative sums, so the total is within (terms a thread adds + 8 +
// log2(groups) + 1) ulp of the exact sum, relative: ≈ 2e-6 at a few million particles, inside the
// 1e-5 that the test (tests/gl/validation_test.cpp) allows.
#include "shared/bindings.h"

layout(local_size_x = 256) in;

layout(location = 0) uniform uint count;          // particles (pass 1) or partial sums (TOTAL)
layout(location = 1) uniform float rest_density;   // ρ0

#ifdef TOTAL
layout(std430) readonly buffer Partials { float partial[]; };
layout(std430) writeonly buffer Total { vec4 total; };   // x: the sum; yzw: 0
#else
layout(std430) readonly buffer Densities { vec4 density[]; };   // x: ρ
layout(std430) writeonly buffer Partials { float partial[]; };
#endif

shared float sums[256];

void main() {
    const uint t = gl_LocalInvocationID.x;
    const uint stride = gl_NumWorkGroups.x * 256u;
    float s = 0.0;
    for (uint i = gl_WorkGroupID.x * 256u + t; i < count; i += stride) {
#ifdef TOTAL
        s += partial[i];
#else
        s += max(density[i].x - rest_density, 0.0) / rest_density;   // ρ − ρ0 exact for ρ in [ρ0/2, 2ρ0]
#endif
    }
    sums[t] = s;
    barrier();
    for (uint half_ = 128u; half_ > 0u; half_ >>= 1) {
        if (t < half_) sums[t] += sums[t + half_];
        barrier();
    }
    if (t == 0u) {
#ifdef TOTAL
        total = vec4(sums[0], 0.0, 0.0, 0.0);
#else
        partial[gl_WorkGroupID.x] = sums[0];
#endif
    }
}
