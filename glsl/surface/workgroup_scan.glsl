// Workgroup-wide exclusive prefix sum of one uvec2 per invocation, in gl_LocalInvocationIndex order
// (Hillis & Steele 1986, double-buffered in shared memory: log2(size) steps).
// Contract: include after the layout(local_size...) declaration; every invocation of the workgroup
// calls it, in uniform control flow. Returns the sum over invocations with a lower index; `total`
// gets the sum over all. Ends with a barrier, so it may be called again right away.
// Example (4 invocations): v = (1,3) (0,0) (1,6) (1,3) -> returns (0,0) (1,3) (1,3) (2,9), total (3,12).
#ifndef RANRYU_SURFACE_WORKGROUP_SCAN_GLSL
#define RANRYU_SURFACE_WORKGROUP_SCAN_GLSL

const uint SCAN_SIZE = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
shared uvec2 scan_ping[SCAN_SIZE];
shared uvec2 scan_pong[SCAN_SIZE];

uvec2 workgroup_exclusive_scan(uvec2 v, out uvec2 total) {
    uint i = gl_LocalInvocationIndex;
    scan_ping[i] = v;
    memoryBarrierShared();
    barrier();
    bool in_ping = true;
    for (uint offset = 1u; offset < SCAN_SIZE; offset <<= 1u) {
        uvec2 t = in_ping ? scan_ping[i] : scan_pong[i];
        if (i >= offset) t += in_ping ? scan_ping[i - offset] : scan_pong[i - offset];
        if (in_ping) scan_pong[i] = t;
        else scan_ping[i] = t;
        in_ping = !in_ping;
        memoryBarrierShared();
        barrier();
    }
    uvec2 inclusive = in_ping ? scan_ping[i] : scan_pong[i];
    total = in_ping ? scan_ping[SCAN_SIZE - 1u] : scan_pong[SCAN_SIZE - 1u];
    memoryBarrierShared();
    barrier();
    return inclusive - v;
}

#endif
