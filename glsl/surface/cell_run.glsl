// The cell-ordered particles of one neighbour-grid cell, for the surface passes that gather over the
// grid (compute_level_set.comp, compute_anisotropy.comp). The including pass declares cell_range[],
// sorted_keys[] and surface (SurfaceParams) first.
// Cell ranges need not have been cleared (NeighbourGrid::build with clear = false): a run is taken
// only if the sorted key at its start is the cell's own, as fluid_run() in sim/fluid/fluid.glsl.
#ifndef RANRYU_SURFACE_CELL_RUN_GLSL
#define RANRYU_SURFACE_CELL_RUN_GLSL
// The particles of cell `key`: [start, end) of the sorted arrays, or empty when the entry is stale.
uvec2 cell_run(uint key) {
    uvec2 r = cell_range[key];
    if (r.x < surface.particle_count && sorted_keys[r.x] == key) return r;
    return uvec2(0u);
}
#endif
