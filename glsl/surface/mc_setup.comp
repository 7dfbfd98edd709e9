#version 430
// "mc.classify", step 1 of 2 (one invocation): sizes the cell passes from the φ grid's dims, which a
// GPU pass may have chosen.
//   in   surface_grid.dims; capacity.z = cells the buffers hold; group.x = mc_classify's local size
//   out  mc.cell_dispatch = (dispatch_2d(blocks of group.x cells), cells), and clears the rest of MeshState
// A grid with more cells than the capacity meshes nothing and sets totals.w.
#include "../shared/bindings.h"

layout(local_size_x = 1) in;
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) readonly buffer Phi { float phi[]; };
layout(std430) writeonly buffer Mesh { MeshState mc; };
layout(location = RANRYU_LOC_SURFACE_CAPACITY) uniform uvec4 capacity;
layout(location = RANRYU_LOC_SURFACE_GROUP) uniform uvec4 group;

#include "mc_common.glsl"

void main() {
    uvec3 d = cell_dims();
    // d.x * d.y * d.z > capacity.z, in integers that cannot wrap around: x*y <= c  <=>  y <= c / x.
    uint c = capacity.z;
    bool over = d.x > c || d.y > c / max(d.x, 1u) || d.z > c / max(d.x * d.y, 1u);
    uint cells = over ? 0u : d.x * d.y * d.z;
    mc.cell_dispatch = uvec4(dispatch_2d((cells + group.x - 1u) / group.x), cells);
    mc.emit_dispatch = uvec4(0u, 0u, 1u, 0u);
    mc.draw = uvec4(0u, 1u, 0u, 0u);
    mc.totals = uvec4(0u, 0u, 0u, over ? 1u : 0u);
}
