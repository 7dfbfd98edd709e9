// Shared by the bitonic sort passes: Batcher, "Sorting networks and their applications", AFIPS
// 1968, in the form whose comparators all point one way (every "flip" block of stage k compares i
// with i ^ (k-1), then half-cleaners compare i with i + j for j = k/4 .. 1), so that every
// comparator puts the smaller pair at the lower index.
//
// Order: (key, value) lexicographic, so that with value = original index the result equals a
// stable sort by key. In place on keys/values (blocks Keys, Values), first u_count.
//
// Padding to the next power of two n happens in the kernel: positions [u_count, n) are virtual
// pairs greater than every real one. Since comparators only ever move the larger pair up, those
// positions hold the virtual pairs at every step, so a comparator whose upper index is >= u_count
// is a no-op and is skipped; nothing past u_count is read or written.
//
// Stages k <= BITONIC_TILE run in shared memory (bitonic_sort_local); for larger k, the steps with
// stride j >= BITONIC_TILE run one dispatch each over global memory (bitonic_merge_global) and the
// remaining strides in one dispatch in shared memory (bitonic_merge_local).
#ifndef RANRYU_SORT_BITONIC_GLSL
#define RANRYU_SORT_BITONIC_GLSL
#include "shared/bindings.h"

#define BITONIC_GROUP 256                                         // local_size_x of every bitonic pass
#define BITONIC_ITEMS RANRYU_SORT_BITONIC_ITEMS_PER_THREAD        // pairs per invocation, local passes
#define BITONIC_TILE (BITONIC_GROUP * BITONIC_ITEMS)              // pairs per shared-memory tile (power of two)

layout(std430) buffer Keys { uint keys[]; };
layout(std430) buffer Values { uint values[]; };
layout(location = RANRYU_LOC_COUNT) uniform uint u_count;   // pairs being sorted

bool pair_less(uint key_a, uint value_a, uint key_b, uint value_b) {
    return key_a < key_b || (key_a == key_b && value_a < value_b);
}
// Comparator c of a step of stride j (a power of two): its lower index, c with a zero bit
// inserted at j.
uint comparator_low(uint c, uint j) { return ((c & ~(j - 1u)) << 1u) | (c & (j - 1u)); }
// Its upper index: the flip of stage k (j = k/2) mirrors within the block of k, half-cleaners add j.
uint comparator_high(uint low, uint k, uint j) { return j == (k >> 1u) ? (low ^ (k - 1u)) : (low + j); }

#endif
