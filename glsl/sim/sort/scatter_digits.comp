#version 430
// Radix pass 3 of 3 (Satish et al. IPDPS 2009, "scatter"; the subgroup ranking is the warp-level
// multi-split by ballots of Adinets & Merrill, "Onesweep: A Faster Least Significant Digit Radix
// Sort for GPUs", arXiv 2206.01784, 2022, without its single-pass look-back): every workgroup sorts
// its tile by this pass's digit in shared memory, stably, then writes each pair to its global place.
//   in   keys, values (blocks Keys, Values), the first u_count pairs
//        histogram after scan_counts: total[d] and, per (d, t), keys with digit d in tiles < t
//   out  keys, values (blocks KeysOut, ValuesOut): the pairs ordered by digit,
//        pairs of equal digit in input order (stable), which is what makes LSD radix sort correct
// One workgroup per tile: dispatch tile_count() groups.
//
// Global place of the pair at position p of the tile's digit-sorted order, digit d:
//     out = digit_start[d] + before_tile[d][t] + (p - tile_start[d])
//     digit_start[d] = sum of total[e] over e < d            (scanned here, over 256 digits)
//     tile_start[d]  = sum of tile_count[e] over e < d       (ditto), tile_count[d] = before_tile[d][t+1]
//                      - before_tile[d][t] (total[d] - before_tile[d][t] for the last tile)
//
// Worked example, 2-bit digits (4 buckets), tiles of 8, u_count = 12, digit = key:
//   keys         tile 0: 2 0 3 0 2 1 0 2        tile 1: 1 3 0 2
//   count_digits histogram rows (d: t0 t1):   d0: 3 1   d1: 1 1   d2: 3 1   d3: 1 1
//   scan_counts  total = [4 2 4 2]; rows:     d0: 0 3   d1: 0 1   d2: 0 3   d3: 0 1
//   scatter, tile 1:  tile_count = [4-3 2-1 4-3 2-1] = [1 1 1 1]
//                     digit_start = [0 4 6 10], tile_start = [0 1 2 3]
//                     out_base = digit_start + before_tile - tile_start = [0+3-0 4+1-1 6+3-2 10+1-3] = [3 4 7 8]
//                     tile sorted in shared memory: 0 1 2 3 (from input 10, 8, 11, 9)
//                     p = 0..3 goes to out_base[d] + p = 3, 5, 9, 11
//   scatter, tile 0:  tile_count = [3 1 3 1], tile_start = [0 3 4 7], out_base = [0 1 2 3]
//                     tile sorted: 0 0 0 1 2 2 2 3 (from input 1 3 6 5 0 4 7 2) -> 0 1 2 4 6 7 8 10
//   output keys:      0 0 0 0 1 1 2 2 2 2 3 3   from input 1 3 6 10 5 8 0 4 7 11 2 9   (stable)
//
// Ranking within the tile, two variants with identical results:
//   shared memory: the tile is split-sorted by the digit SPLIT_BITS bits at a time (3, 3, 2 for
//     8 bits). Invocation i holds positions [i*RADIX_ITEMS, (i+1)*RADIX_ITEMS); it counts each of
//     the 2^SPLIT_BITS sub-digits in 16-bit fields packed in a uvec4, one workgroup scan of those
//     gives every (sub-digit, invocation) its start, and a pair's new position is
//         (pairs with a smaller sub-digit) + (equal sub-digit, lower invocation) + (equal, earlier in mine).
//     Each split is stable, so after the last the tile is stably sorted by the whole digit.
//   subgroups: subgroup s ranks the consecutive run [s*size*RADIX_ITEMS, (s+1)*size*RADIX_ITEMS) in
//     steps of `size` pairs; in a step, the lanes holding the same digit find each other with one
//     ballot per digit bit (peers = AND of ballot or ~ballot), a lane's rank is the number of its
//     peers on lower lanes plus the subgroup's count of that digit so far (a shared counter per
//     (subgroup, digit) that the highest peer advances). Then per digit an exclusive scan over the
//     subgroups' counts; position = tile_start[d] + (subgroups before) + (rank in subgroup).
// Digits >= 2^u_bits occur in no key of this pass; their histogram entries may be stale (scan_counts
// skips them) and so are their offsets here, which are never used.
// Pad pairs (positions past u_count in the last tile) get key 0xFFFFFFFF, hence the largest digit;
// they come last in input order, so they rank after every real pair and are never written.
#if defined(RANRYU_SUBGROUPS)
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "sim/sort/radix.glsl"

layout(local_size_x = RADIX_GROUP) in;

#include "sim/sort/subgroup.glsl"
#include "sim/sort/block_scan.glsl"

layout(std430) readonly buffer KeysIn { uint keys_in[]; };
layout(std430) readonly buffer ValuesIn { uint values_in[]; };
layout(std430) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430) writeonly buffer ValuesOut { uint values_out[]; };
layout(std430) readonly buffer Histogram { uint histogram[]; };

const uint PAD_KEY = 0xFFFFFFFFu;

shared uint s_key[RADIX_TILE];          // the tile, sorted by digit once ranked
shared uint s_value[RADIX_TILE];
shared uint s_tile_start[RADIX_DIGITS];  // first position of digit d in the tile's sorted order
shared uint s_out_base[RADIX_DIGITS];    // global index of that position, minus the position

// Fills s_tile_start and s_out_base (see the formula at the top).
// One invocation per digit (radix.glsl checks RADIX_GROUP == RADIX_DIGITS).
void find_offsets(uint tile, uint tiles) {
    const uint d = block_rank();
    const uint before = histogram[count_index(d, tile, tiles)];
    const uint total = histogram[d];
    const uint after = tile + 1u < tiles ? histogram[count_index(d, tile + 1u, tiles)] : total;
    uvec4 sums;
    const uvec4 start = block_exclusive_scan(uvec4(total, after - before, 0u, 0u), sums);
    s_tile_start[d] = start.y;
    s_out_base[d] = start.x + before - start.y;
}

#ifdef SORT_SUBGROUP_ALGORITHM

shared uint s_subgroup_count[SG_MAX_COUNT * RADIX_DIGITS];   // [subgroup][digit]

void rank_tile(uint first, uint valid) {
    for (uint j = gl_LocalInvocationIndex; j < SG_MAX_COUNT * uint(RADIX_DIGITS); j += gl_WorkGroupSize.x)
        s_subgroup_count[j] = 0u;
    sync_shared();
    const uint id = sg_id(), lane = sg_lane(), size = sg_size();
    const uint run = id * size * uint(RADIX_ITEMS);
    uint key[RADIX_ITEMS], value[RADIX_ITEMS], digit[RADIX_ITEMS], rank[RADIX_ITEMS];
    for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
        // Branch-free load (a clamped read, then a select): the ballots below see every lane.
        const uint p = run + k * size + lane;
        const uint at = first + min(p, valid - 1u);
        const uint loaded = keys_in[at];
        key[k] = p < valid ? loaded : PAD_KEY;
        value[k] = values_in[at];
        const uint d = digit_of(key[k]);
        digit[k] = d;
        uvec4 peers = sg_ballot(true);
        for (uint b = 0u; b < u_bits; ++b) {
            const bool set = ((d >> b) & 1u) != 0u;
            const uvec4 vote = sg_ballot(set);
            peers &= set ? vote : ~vote;
        }
        const uint slot = id * uint(RADIX_DIGITS) + d;
        const uint so_far = s_subgroup_count[slot];
        sg_sync_shared();   // every lane has read the counter before its highest peer advances it
        if (sg_find_msb(peers) == lane) s_subgroup_count[slot] = so_far + sg_bit_count(peers);
        sg_sync_shared();
        rank[k] = so_far + sg_bit_count(peers & sg_lt_mask());
    }
    sync_shared();
    // Per digit: counts of the subgroups -> how many of that digit the earlier subgroups hold.
    for (uint d = block_rank(); d < uint(RADIX_DIGITS); d += gl_WorkGroupSize.x) {
        uint sum = 0u;
        for (uint s = 0u; s < sg_count(); ++s) {
            const uint c = s_subgroup_count[s * uint(RADIX_DIGITS) + d];
            s_subgroup_count[s * uint(RADIX_DIGITS) + d] = sum;
            sum += c;
        }
    }
    sync_shared();
    for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
        const uint p = s_tile_start[digit[k]] + s_subgroup_count[id * uint(RADIX_DIGITS) + digit[k]] + rank[k];
        s_key[p] = key[k];
        s_value[p] = value[k];
    }
    sync_shared();
}

#else

#define SPLIT_BITS 3u   // 8 sub-digits: eight 16-bit counters in a uvec4

uint field(uvec4 c, uint b) { return (c[b >> 1u] >> ((b & 1u) * 16u)) & 0xFFFFu; }
uint fields_below(uvec4 c, uint b) {
    uint sum = 0u;
    for (uint q = 0u; q < b; ++q) sum += field(c, q);
    return sum;
}

void rank_tile(uint first, uint valid) {
    for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
        const uint p = k * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        s_key[p] = PAD_KEY;
        s_value[p] = 0u;
        if (p < valid) {
            s_key[p] = keys_in[first + p];
            s_value[p] = values_in[first + p];
        }
    }
    sync_shared();
    for (uint low = 0u; low < u_bits; low += SPLIT_BITS) {
        const uint mask = (1u << min(SPLIT_BITS, u_bits - low)) - 1u;
        uint key[RADIX_ITEMS], value[RADIX_ITEMS], rank[RADIX_ITEMS];
        uvec4 mine = uvec4(0u);
        for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
            const uint p = gl_LocalInvocationIndex * uint(RADIX_ITEMS) + k;
            key[k] = s_key[p];
            value[k] = s_value[p];
            const uint b = (digit_of(key[k]) >> low) & mask;
            rank[k] = field(mine, b);
            mine[b >> 1u] += 1u << ((b & 1u) * 16u);
        }
        uvec4 total;
        const uvec4 before = block_exclusive_scan(mine, total);   // ends with a barrier: reads done
        for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
            const uint b = (digit_of(key[k]) >> low) & mask;
            const uint p = fields_below(total, b) + field(before, b) + rank[k];
            s_key[p] = key[k];
            s_value[p] = value[k];
        }
        sync_shared();
    }
}

#endif

void main() {
    const uint tile = gl_WorkGroupID.x;
    const uint first = tile * uint(RADIX_TILE);
    const uint valid = min(uint(RADIX_TILE), u_count - first);
    find_offsets(tile, tile_count());
    sync_shared();
    rank_tile(first, valid);
    // Strided writes: runs of one digit go to consecutive addresses.
    for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
        const uint p = k * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        if (p < valid) {
            const uint key = s_key[p];
            const uint at = s_out_base[digit_of(key)] + p;
            keys_out[at] = key;
            values_out[at] = s_value[p];
        }
    }
}
