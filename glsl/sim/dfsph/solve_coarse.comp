#version 430
// "dfsph.coarse.solve" (docs/DFSPH.md (D12)), one workgroup: the coarse Poisson problem
//     Σ_f∈active (e_f − e_c) − Σ_f∈air e_c / theta_f = −rhs_c       on every active cell c
// (a solid neighbour drops out: the wall's zero gradient; at an air neighbour the surface lies
// theta_f H away, where e = 0: coarse_surface_coefficient()), by dfsph.coarse_sweeps red-black sweeps
// of successive over-relaxation from e = 0,
//     e_c ← (1 − ω) e_c + ω (Σ_f∈active e_f + rhs_c) / (|active| + Σ_f∈air 1/theta_f),   ω = kCoarseOverRelaxation,
// first linking each active cell to its neighbours (CoarseCell.w). A sweep of one colour reads only
// the other's values, so the result does not depend on the lists' order. Does nothing once the solve
// has converged (its dispatch is 0).
#include "dfsph.glsl"
#include "coarse.glsl"

layout(local_size_x = 1024) in;
layout(std430) readonly buffer Solve { SolveState solve; };
layout(std430) coherent buffer CoarseCell { vec4 coarse[]; };
layout(std430) readonly buffer CoarseList { uvec2 coarse_count; uint coarse_capacity; uint coarse_pad; uint coarse_list[]; };

uint links_of(uint index) {
    ivec3 c = coarse_cell_of(index);
    uint bits = 0u;
    for (int f = 0; f < 6; ++f) {
        ivec3 m = c + kCoarseFaces[f];
        float phi = coarse_inside(m) ? coarse[coarse_index(m)].z : -1.0;
        if (coarse_active(phi)) bits |= 1u << uint(f);
        else if (coarse_solid(phi)) bits |= 1u << (kCoarseSolidShift + uint(f));
    }
    return bits;
}

void relax(uint index) {
    vec4 cell = coarse[index];
    uint bits = floatBitsToUint(cell.w);
    ivec3 c = coarse_cell_of(index);
    float sum = cell.y, diagonal = 0.0;
    for (int f = 0; f < 6; ++f) {
        if ((bits & (1u << (kCoarseSolidShift + uint(f)))) != 0u) continue;
        vec4 m = coarse[coarse_index(c + kCoarseFaces[f])];
        if ((bits & (1u << uint(f))) != 0u) sum += m.x, diagonal += 1.0;
        else diagonal += coarse_surface_coefficient(cell.z, m.z);
    }
    float e = diagonal == 0.0 ? 0.0 : mix(cell.x, sum / diagonal, kCoarseOverRelaxation);
    coarse[index].x = e;
}

void main() {
    if (solve.dispatch.x == 0u) return;   // uniform over the one workgroup: no barrier is skipped by some
    uint l = gl_LocalInvocationIndex, size = gl_WorkGroupSize.x;
    for (uint colour = 0u; colour < 2u; ++colour)
        for (uint k = l; k < coarse_count[colour]; k += size) {
            uint index = coarse_list[colour * coarse_capacity + k];
            coarse[index].w = uintBitsToFloat(links_of(index));
        }
    memoryBarrierBuffer();
    barrier();
    for (uint sweep = 0u; sweep < dfsph.coarse_sweeps; ++sweep)
        for (uint colour = 0u; colour < 2u; ++colour) {
            for (uint k = l; k < coarse_count[colour]; k += size) relax(coarse_list[colour * coarse_capacity + k]);
            memoryBarrierBuffer();
            barrier();
        }
}
