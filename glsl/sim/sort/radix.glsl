// Shared by the LSD radix sort passes (count_digits, scan_counts, scatter_digits): constants, the
// per-pass uniforms, and the layout of the histogram buffer. The method is the reduce-then-scan
// radix sort of Satish, Harris & Garland, "Designing efficient sorting algorithms for manycore
// GPUs", IPDPS 2009: per digit of RANRYU_SORT_RADIX_BITS bits, (1) every tile counts its digits,
// (2) the counts are scanned in (digit, tile) order, (3) every tile ranks its keys stably and
// writes them to their global places.
//
// Histogram buffer (block Histogram), for T = tile_count() tiles:
//     [0, RADIX_DIGITS)                         total[d]: how many keys have digit d  (scan_counts)
//     [RADIX_DIGITS + d*T + t]                  count_digits: keys of tile t with digit d;
//                                               scan_counts: keys with digit d in tiles < t
// Digit-major order makes each digit's row contiguous, so scan_counts scans one row per workgroup.
#ifndef RANRYU_SORT_RADIX_GLSL
#define RANRYU_SORT_RADIX_GLSL
#include "shared/bindings.h"

#define RADIX_GROUP 256                                   // local_size_x of count_digits and scatter_digits
#define RADIX_ITEMS RANRYU_SORT_RADIX_ITEMS_PER_THREAD    // keys per invocation
#define RADIX_TILE (RADIX_GROUP * RADIX_ITEMS)            // keys per workgroup (C++ reads local size x items)
#define RADIX_DIGITS (1 << RANRYU_SORT_RADIX_BITS)        // buckets per pass

#if RADIX_GROUP != RADIX_DIGITS
#error "scatter_digits gives one invocation to each digit: RADIX_GROUP must equal RADIX_DIGITS"
#endif
#if RADIX_TILE > 65535
#error "scatter_digits packs in-tile counts into 16-bit fields: a tile must hold fewer than 65536 keys"
#endif

layout(location = RANRYU_LOC_COUNT) uniform uint u_count;   // pairs being sorted
layout(location = RANRYU_LOC_SHIFT) uniform uint u_shift;   // lowest key bit of this pass's digit
layout(location = RANRYU_LOC_AUX) uniform uint u_bits;      // bits in this pass's digit, 1..RANRYU_SORT_RADIX_BITS

uint tile_count() { return (u_count + uint(RADIX_TILE) - 1u) / uint(RADIX_TILE); }
// The digit this pass sorts by. The mask keeps a key above max_key from indexing past the buckets.
uint digit_of(uint key) { return (key >> u_shift) & ((1u << u_bits) - 1u); }
uint count_index(uint digit, uint tile, uint tiles) { return uint(RADIX_DIGITS) + digit * tiles + tile; }

// Shared-memory writes before this are seen by the whole workgroup after it.
void sync_shared() {
    memoryBarrierShared();
    barrier();
}

#endif
