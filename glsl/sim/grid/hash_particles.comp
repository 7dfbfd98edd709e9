#version 430
// Grid hash (docs/METHOD.md §1 step 1): key[i] = the key of particle i's cell, value[i] = i.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) writeonly buffer Keys { uint keys[]; };
layout(std430) writeonly buffer Values { uint values[]; };

#include "../grid.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= grid.count) return;
    keys[i] = cell_key(grid_cell(position[i].xyz));
    values[i] = i;
}
