// Cells and keys of the uniform neighbour grid (docs/METHOD.md §1). Needs grid (GridParams) in scope.
//
// Linear keys are the talk's i + j*nx + k*nx*ny. Morton keys interleave the bits of (i, j, k)
// (bit b of i goes to bit 3b): cells close in space get close keys, so the sorted particles of
// neighbouring cells sit closer in memory. Either way every cell has one key, and a key's particles
// are the run cell_range[key] = [first, one past the last) of the sorted arrays.

ivec3 grid_cell(vec3 x) {
    ivec3 c = ivec3(floor((x - grid.origin.xyz) / grid.origin.w));
    return clamp(c, ivec3(0), ivec3(grid.dims.xyz) - 1);   // the guard reports particles outside
}

uint spread_bits(uint v) {   // 10 bits -> every third of 30
    v &= 0x3FFu;
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

uint compact_bits(uint v) {   // every third of 30 -> 10 bits: spread_bits' inverse
    v &= 0x09249249u;
    v = (v | (v >> 2)) & 0x030C30C3u;
    v = (v | (v >> 4)) & 0x0300F00Fu;
    v = (v | (v >> 8)) & 0x030000FFu;
    v = (v | (v >> 16)) & 0x3FFu;
    return v;
}

uint cell_key(ivec3 c) {
    uvec3 u = uvec3(c);
    if (grid.morton != 0u) return spread_bits(u.x) | (spread_bits(u.y) << 1) | (spread_bits(u.z) << 2);
    return u.x + grid.dims.x * (u.y + grid.dims.y * u.z);
}

bool cell_inside(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(grid.dims.xyz))); }

// The cell of a key: cell_key's inverse.
ivec3 key_cell(uint key) {
    if (grid.morton != 0u) return ivec3(compact_bits(key), compact_bits(key >> 1), compact_bits(key >> 2));
    uint nx = grid.dims.x, ny = grid.dims.y;
    return ivec3(key % nx, (key / nx) % ny, key / (nx * ny));
}
