// What every PBF pass shares (docs/PBF.md; engine/sim/solvers/pbf.h): the fluid's blocks and the
// solver's constants. Its per-particle arrays, which each pass declares as it uses them:
//     Density         vec4 (rho_i (P2), p_i (P9), lambda_i (P4), flags) of the last lambda pass
//     Lambda          float: lambda_i (P4) of the current iteration, gathered by neighbours in (P6)
//     Start           vec4 per particle, carried with it through the reorder: x_n, the step's start (P1)
//     PbfVelocity     vec4: the velocity (x − x_n)/dt of (P7) before XSPH, gathered by neighbours
//     Vorticity       vec4: omega_i of (P8), gathered by neighbours (with vorticity confinement only)
#include "../fluid/fluid.glsl"

layout(std140, binding = RANRYU_UBO_PBF) uniform PbfBlock { PbfParams pbf; };
