// The density solve's coarse correction (docs/DFSPH.md (D12)): a grid of cells two neighbour-grid
// cells wide (H = 2h, about 64 particles a full cell) over the neighbour grid's box, with a dense
// array of one CoarseCell (vec4) per cell and a list of the cells that hold fluid, by colour:
//     CoarseCell     x: the correction e_c (m^5 kg^-1 s^-2, kappa's unit); y: the right-hand side
//                    H^2 r_c / (rho0^2 dt^2) of an active cell; z: the fluid's fraction phi_c of the
//                    cell's open volume, or −1 for a solid cell (coarse_solid(), coarse_active());
//                    w: an active cell's links to its face neighbours (the bits below)
//     CoarseList     coarse_count[c]: the active cells of colour c = (x + y + z) mod 2 this solve;
//                    coarse_list[c * coarse_capacity + k]: their dense indices, in no fixed order
// Needs dfsph.glsl (GridParams grid) in scope.
// A cell is solid when it holds no fluid but walls (or lies outside the tank), active when fluid
// fills at least half its open volume (phi_c >= 1/2: its centre lies in the fluid), air otherwise.
bool coarse_solid(float phi) { return phi < 0.0; }
bool coarse_active(float phi) { return phi >= 0.5; }

// The free surface between active cell c and air neighbour a lies theta·H from c's centre, theta =
// min(phi_c, 1) − 1/2 + phi_a (each cell's fluid taken as filling it from the side of c), at least
// kCoarseNearest; the face's coefficient in the Poisson problem is then 1/theta (a Dirichlet
// condition e = 0 at the surface, as Gibou et al.'s ghost fluid).
const float kCoarseNearest = 0.1;
float coarse_surface_coefficient(float phi_c, float phi_a) { return 1.0 / clamp(min(phi_c, 1.0) - 0.5 + phi_a, kCoarseNearest, 1.0); }

// Red-black successive over-relaxation's factor of the coarse Poisson problem (D12).
const float kCoarseOverRelaxation = 1.5;

float coarse_cell_size() { return 2.0 * grid.origin.w; }
ivec3 coarse_dims() { return (ivec3(grid.dims.xyz) + 1) / 2; }
bool coarse_inside(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, coarse_dims())); }
uint coarse_index(ivec3 c) { ivec3 n = coarse_dims(); return uint(c.x + n.x * (c.y + n.y * c.z)); }
ivec3 coarse_cell_of(uint index) {
    ivec3 n = coarse_dims();
    return ivec3(int(index) % n.x, (int(index) / n.x) % n.y, int(index) / (n.x * n.y));
}
uint coarse_colour(ivec3 c) { return uint(c.x + c.y + c.z) & 1u; }

// The six face neighbours, in the order of the bits below.
const ivec3 kCoarseFaces[6] = ivec3[6](ivec3(-1, 0, 0), ivec3(1, 0, 0), ivec3(0, -1, 0), ivec3(0, 1, 0), ivec3(0, 0, -1), ivec3(0, 0, 1));
// An active cell's links: bit f set when face neighbour f is active, bit 8 + f when it is solid (or
// outside the grid: the walls' side of the box). The rest are air, where e = 0.
const uint kCoarseSolidShift = 8u;
