#version 430
// Radix pass 2 of 3 (Satish et al. IPDPS 2009, "prefix sum"): exclusive prefix sums of the tile
// counts, one digit's row per workgroup.
//   in   histogram[RADIX_DIGITS + d*T + t] = keys of tile t with digit d (count_digits)
//   out  histogram[RADIX_DIGITS + d*T + t] = keys with digit d in tiles 0..t-1
//        histogram[d]                      = keys with digit d in all tiles (total[d])
// One workgroup per digit: dispatch 2^b groups for a pass of b-bit digits (a 64^3 grid's third pass
// has b = 2: 4 groups). Rows and totals of higher digits are left as they were: scatter_digits
// reads them, but they only enter the sums of digits that no key of this pass has.
// A workgroup walks its row in chunks of local_size * SCAN_ITEMS tiles (1024 tiles = 2M keys),
// carrying the running sum from chunk to chunk, so any number of tiles works (16M keys = 8192
// tiles = 8 chunks) without a third level. The scan across digits (total[] -> where each digit
// starts) is at most 256 values; scatter_digits does it per workgroup rather than spend a dispatch.
#if defined(RANRYU_SUBGROUPS)
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "sim/sort/radix.glsl"

layout(local_size_x = 256) in;

#include "sim/sort/subgroup.glsl"
#include "sim/sort/block_scan.glsl"

#define SCAN_ITEMS 4   // tiles per invocation per chunk

layout(std430) buffer Histogram { uint histogram[]; };

#if defined(RANRYU_SCAN_SERIAL)
// Few tiles (KeySort::kSerialScanTiles or fewer): one workgroup, and invocation d walks digit d's
// row alone, with no barrier. Same output as below; far cheaper where a dispatch of 2^b workgroups
// would mostly idle (small particle counts, and drivers that run workgroups serially).
void main() {
    const uint digit = gl_LocalInvocationID.x;
    const uint tiles = tile_count();
    const uint row = count_index(digit, 0u, tiles);
    uint run = 0u;
    for (uint t = 0u; t < tiles; ++t) {
        const uint c = histogram[row + t];
        histogram[row + t] = run;
        run += c;
    }
    histogram[digit] = run;
}
#else
void main() {
    const uint digit = gl_WorkGroupID.x;
    const uint tiles = tile_count();
    const uint row = count_index(digit, 0u, tiles);
    const uint rank = block_rank();
    uint carry = 0u;
    for (uint base = 0u; base < tiles; base += gl_WorkGroupSize.x * uint(SCAN_ITEMS)) {
        const uint first = base + rank * uint(SCAN_ITEMS);
        uint v[SCAN_ITEMS];
        uint sum = 0u;
        for (uint j = 0u; j < uint(SCAN_ITEMS); ++j) {
            v[j] = first + j < tiles ? histogram[row + first + j] : 0u;
            sum += v[j];
        }
        uvec4 total;
        uint run = carry + block_exclusive_scan(uvec4(sum, 0u, 0u, 0u), total).x;
        for (uint j = 0u; j < uint(SCAN_ITEMS); ++j) {
            if (first + j < tiles) histogram[row + first + j] = run;
            run += v[j];
        }
        carry += total.x;
    }
    if (rank == 0u) histogram[digit] = carry;
}
#endif
