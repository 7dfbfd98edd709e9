// Workgroup-wide exclusive prefix sum of one uvec4 per invocation (four sums at once), in the order
// of block_rank(): the invocation's place in the workgroup that the subgroup operations agree with
// (subgroup id, then lane) on the subgroup variants, gl_LocalInvocationIndex otherwise.
// Contract: include after subgroup.glsl; call in workgroup-uniform control flow; the local size is
// a multiple of SCAN_SEGMENT. Returns the sum over invocations ranked below; `total` gets the sum
// over all. Ends with a barrier, so shared memory read before the call may be overwritten after it.
#ifndef RANRYU_SORT_BLOCK_SCAN_GLSL
#define RANRYU_SORT_BLOCK_SCAN_GLSL

#ifdef SORT_SUBGROUP_ALGORITHM

uint block_rank() { return sg_id() * sg_size() + sg_lane(); }

shared uvec4 scan_subgroup_sum[SG_MAX_COUNT];

uvec4 block_exclusive_scan(uvec4 v, out uvec4 total) {
    uvec4 below = sg_exclusive_add(v);
    if (sg_lane() == sg_size() - 1u) scan_subgroup_sum[sg_id()] = below + v;
    memoryBarrierShared();
    barrier();
    uvec4 before = uvec4(0u);
    total = uvec4(0u);
    for (uint s = 0u; s < sg_count(); ++s) {
        uvec4 t = scan_subgroup_sum[s];
        if (s < sg_id()) before += t;
        total += t;
    }
    memoryBarrierShared();
    barrier();
    return before + below;
}

#else

uint block_rank() { return gl_LocalInvocationIndex; }

// Raking scan (Blelloch-style two levels, four barriers): SCAN_SEGMENTS invocations each scan a
// segment of SCAN_SEGMENT values serially, one invocation scans the segment sums.
const uint SCAN_SEGMENT = 16u;
const uint SCAN_SEGMENTS = gl_WorkGroupSize.x / SCAN_SEGMENT;
shared uvec4 scan_value[gl_WorkGroupSize.x];
shared uvec4 scan_segment[SCAN_SEGMENTS + 1u];

uvec4 block_exclusive_scan(uvec4 v, out uvec4 total) {
    uint i = gl_LocalInvocationIndex;
    scan_value[i] = v;
    memoryBarrierShared();
    barrier();
    if (i < SCAN_SEGMENTS) {
        uvec4 run = uvec4(0u);
        for (uint j = 0u; j < SCAN_SEGMENT; ++j) {
            uvec4 t = scan_value[i * SCAN_SEGMENT + j];
            scan_value[i * SCAN_SEGMENT + j] = run;
            run += t;
        }
        scan_segment[i] = run;
    }
    memoryBarrierShared();
    barrier();
    if (i == 0u) {
        uvec4 run = uvec4(0u);
        for (uint s = 0u; s < SCAN_SEGMENTS; ++s) {
            uvec4 t = scan_segment[s];
            scan_segment[s] = run;
            run += t;
        }
        scan_segment[SCAN_SEGMENTS] = run;
    }
    memoryBarrierShared();
    barrier();
    uvec4 before = scan_value[i] + scan_segment[i / SCAN_SEGMENT];
    total = scan_segment[SCAN_SEGMENTS];
    memoryBarrierShared();
    barrier();
    return before;
}

#endif
#endif
