#ifndef RANRYU_SURFACE_DISPATCH_2D_GLSL
#define RANRYU_SURFACE_DISPATCH_2D_GLSL
// The cell passes dispatch over their blocks as a 2-D grid: one-dimensional dispatches stop at
// 65,535 workgroups (GL 4.3's guaranteed minimum), 4M cells at 64 a workgroup, short of 256^3.
// dispatch_2d gives the arguments for `groups` workgroups (x at most kMaxGroupsX; the last row
// may hold up to kMaxGroupsX - 1 padding workgroups, which find no work); flat_group() the block
// index of this workgroup.
#ifndef RANRYU_MC_GROUPS_X
#define RANRYU_MC_GROUPS_X 32768u   // MeshCapacity::groups_x; C++ defines it for every MC program
#endif
const uint kMaxGroupsX = RANRYU_MC_GROUPS_X;
uvec3 dispatch_2d(uint groups) { return uvec3(min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1u) / kMaxGroupsX, 1u); }
uint flat_group() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }
#endif
