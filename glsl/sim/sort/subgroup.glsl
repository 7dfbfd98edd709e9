// One text of the subgroup algorithms, three ways to run it:
//   RANRYU_SUBGROUPS           the driver's GL_KHR_shader_subgroup built-ins (basic, vote, ballot,
//                              arithmetic; the including .comp enables the extensions after #version)
//   RANRYU_SUBGROUPS_EMULATED  the same functions built from shared memory and barrier(), so that
//                              the subgroup algorithm can be tested on a driver without subgroups
//                              (llvmpipe). Its lanes are dealt round-robin: invocation i is lane
//                              i / count of subgroup i % count, so an algorithm that assumed subgroups
//                              of consecutive invocations fails the tests.
//   neither                    SORT_SUBGROUP_ALGORITHM stays undefined; passes use shared memory only.
// RANRYU_SUBGROUP_SIZE (from C++, GL_SUBGROUP_SIZE_KHR) sizes per-subgroup shared arrays and is the
// emulation's subgroup size.
//
// Contract for callers: include after the layout(local_size_x = ...) declaration; subgroups are
// full (gl_NumSubgroups * gl_SubgroupSize == local size, true for 256 invocations and 32- or 64-wide
// subgroups); call every function here in workgroup-uniform control flow (the emulation holds
// barrier()s), and never with an empty mask where a mask is asked for.
#ifndef RANRYU_SORT_SUBGROUP_GLSL
#define RANRYU_SORT_SUBGROUP_GLSL

#if defined(RANRYU_SUBGROUPS) || defined(RANRYU_SUBGROUPS_EMULATED)
#define SORT_SUBGROUP_ALGORITHM 1
#ifndef RANRYU_SUBGROUP_SIZE
#error "RANRYU_SUBGROUP_SIZE must be defined with the subgroup variants"
#endif
// Subgroups per workgroup, for sizing shared arrays.
const uint SG_MAX_COUNT = gl_WorkGroupSize.x / uint(RANRYU_SUBGROUP_SIZE);
#endif

#if defined(RANRYU_SUBGROUPS) && !defined(RANRYU_SUBGROUPS_EMULATED)

uint sg_id() { return gl_SubgroupID; }
uint sg_lane() { return gl_SubgroupInvocationID; }
uint sg_size() { return gl_SubgroupSize; }
uint sg_count() { return gl_NumSubgroups; }
uvec4 sg_ballot(bool p) { return subgroupBallot(p); }
uint sg_bit_count(uvec4 mask) { return subgroupBallotBitCount(mask); }
uint sg_find_msb(uvec4 mask) { return subgroupBallotFindMSB(mask); }
uvec4 sg_lt_mask() { return gl_SubgroupLtMask; }
uvec4 sg_exclusive_add(uvec4 v) { return subgroupExclusiveAdd(v); }
bool sg_all_equal(uint v) { return subgroupAllEqual(v); }
// Orders shared-memory accesses between the lanes of one subgroup (a read by every lane, then a
// write by one, then reads again).
void sg_sync_shared() {
    subgroupMemoryBarrierShared();
    subgroupBarrier();
}

#elif defined(RANRYU_SUBGROUPS_EMULATED)

const uint EMU_SIZE = uint(RANRYU_SUBGROUP_SIZE);
const uint EMU_COUNT = gl_WorkGroupSize.x / EMU_SIZE;
shared uint emu_ballot[EMU_COUNT * 4u];
shared uvec4 emu_value[gl_WorkGroupSize.x];

uint sg_id() { return gl_LocalInvocationIndex % EMU_COUNT; }
uint sg_lane() { return gl_LocalInvocationIndex / EMU_COUNT; }
uint sg_size() { return EMU_SIZE; }
uint sg_count() { return EMU_COUNT; }
uint emu_invocation(uint id, uint lane) { return lane * EMU_COUNT + id; }

void emu_sync() {
    memoryBarrierShared();
    barrier();
}
// Bits [0, n) of a 128-bit lane mask.
uvec4 emu_lanes_below(uint n) {
    uvec4 m;
    for (uint c = 0u; c < 4u; ++c) {
        uint lo = 32u * c;
        m[c] = n >= lo + 32u ? 0xFFFFFFFFu : n <= lo ? 0u : (1u << (n - lo)) - 1u;
    }
    return m;
}
uvec4 sg_ballot(bool p) {
    uint id = sg_id(), lane = sg_lane();
    if (lane < 4u) emu_ballot[4u * id + lane] = 0u;
    emu_sync();
    if (p) atomicOr(emu_ballot[4u * id + (lane >> 5u)], 1u << (lane & 31u));
    emu_sync();
    uvec4 m = uvec4(emu_ballot[4u * id], emu_ballot[4u * id + 1u], emu_ballot[4u * id + 2u], emu_ballot[4u * id + 3u]);
    emu_sync();
    return m;
}
uint sg_bit_count(uvec4 mask) {
    mask &= emu_lanes_below(EMU_SIZE);
    return uint(bitCount(mask.x) + bitCount(mask.y) + bitCount(mask.z) + bitCount(mask.w));
}
uint sg_find_msb(uvec4 mask) {
    mask &= emu_lanes_below(EMU_SIZE);
    for (int c = 3; c >= 0; --c)
        if (mask[c] != 0u) return 32u * uint(c) + uint(findMSB(mask[c]));
    return 0xFFFFFFFFu;
}
uvec4 sg_lt_mask() { return emu_lanes_below(sg_lane()); }
uvec4 sg_exclusive_add(uvec4 v) {
    emu_value[gl_LocalInvocationIndex] = v;
    emu_sync();
    uvec4 sum = uvec4(0u);
    for (uint l = 0u; l < sg_lane(); ++l) sum += emu_value[emu_invocation(sg_id(), l)];
    emu_sync();
    return sum;
}
bool sg_all_equal(uint v) {
    emu_value[gl_LocalInvocationIndex].x = v;
    emu_sync();
    uint first = emu_value[emu_invocation(sg_id(), 0u)].x;
    emu_sync();
    return sg_bit_count(sg_ballot(v == first)) == EMU_SIZE;
}
void sg_sync_shared() { emu_sync(); }

#endif
#endif
