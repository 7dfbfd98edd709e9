#version 430
// Once at start: near[key] = 1 when a boundary particle lies in one of the 27 cells around the cell
// (the cells a density walk from there visits, clamped the same way), else 0. The boundary is
// static, so the flag holds for the whole run; the density pass skips the boundary runs of particles
// whose cell reads 0, which changes no sum (those runs are empty). One invocation per cell.
#include "../fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std430) writeonly buffer BoundaryNear { uint near[]; };

void main() {
    uint n = gl_GlobalInvocationID.x;
    uvec3 dims = grid.dims.xyz;
    if (n >= dims.x * dims.y * dims.z) return;
    ivec3 c = ivec3(n % dims.x, (n / dims.x) % dims.y, n / (dims.x * dims.y));
    uint any_run = 0u;
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, false);
        if (run.y > run.x) any_run = 1u;
    }
    near[cell_key(c)] = any_run;
}
