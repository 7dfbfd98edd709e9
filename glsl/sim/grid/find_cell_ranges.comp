#version 430
// Cell ranges (METHOD.md §1 step 3): from keys sorted ascending, the run of each key:
//     cell_start[k] = first i with key[i] = k,   cell_end[k] = last such i + 1.
// Cells with no particle keep the 0, 0 they were cleared to, an empty run.
// Example: keys 2 2 5 7 7 7 -> start[2]=0 end[2]=2, start[5]=2 end[5]=3, start[7]=3 end[7]=6.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std430, binding = RANRYU_SSBO_SORT_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = RANRYU_SSBO_CELL_START) writeonly buffer Start { uint cell_start[]; };
layout(std430, binding = RANRYU_SSBO_CELL_END) writeonly buffer End { uint cell_end[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint n = grid.count;
    if (i >= n) return;
    uint k = keys[i];
    if (i == 0u || keys[i - 1u] != k) cell_start[k] = i;
    if (i + 1u == n || keys[i + 1u] != k) cell_end[k] = i + 1u;
}
