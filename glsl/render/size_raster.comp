#version 430
// The compute raster's dispatch (docs/RENDERING.md (R14)), from the mesh's vertex count that marching
// cubes left in its glDrawArraysIndirect arguments (the count never comes to the CPU):
//   raster.xyz = workgroups of rasterise_layers.comp, one invocation per triangle (dispatch_2d),
//   raster.w   = triangles, count / 3;
// and empties the lists of large triangles of the sun's and the eye's view (large[0], large[1]):
//   large[v] = (0 listed: the workgroups along x, RANRYU_RASTER_LARGE_TILES along y, 1, 0 claimed).
// Read by glDispatchComputeIndirect and by rasterise_layers.comp. Dispatch: one invocation.
#include "../shared/bindings.h"
#include "shading.h"
#include "../surface/dispatch_2d.glsl"

layout(local_size_x = 1) in;
layout(std430) readonly buffer MeshDraw { uint mesh_draw[]; };   // the draw's arguments at word u_group.y
layout(std430) writeonly buffer RasterDispatch { uvec4 raster; };
layout(std430) writeonly buffer RasterLarge { uvec4 large[2]; };
layout(location = RANRYU_LOC_RASTER_GROUP) uniform uvec4 u_group;   // x: rasterise_layers' local size

void main() {
    uint triangles = mesh_draw[u_group.y] / 3u;
    raster = uvec4(dispatch_2d((triangles + u_group.x - 1u) / u_group.x), triangles);
    // Two stores, not a chained assignment: the chain reads large[1] back, which NVIDIA's compiler
    // refuses for a writeonly block.
    large[0] = uvec4(0u, RANRYU_RASTER_LARGE_TILES, 1u, 0u);
    large[1] = uvec4(0u, RANRYU_RASTER_LARGE_TILES, 1u, 0u);
}
