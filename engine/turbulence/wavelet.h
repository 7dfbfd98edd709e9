#pragma once
// Wavelet analysis of the SPH velocity: where is the flow turbulent (docs/METHOD.md §3). Per fluid
// particle i and scale s, the pass "wavelet" (glsl/turbulence/analyse_velocity.comp) computes
//
//     û_i = 1/ψ_sum,i · Σ_j (u_j − u_i) · ψ((x_i − x_j)/s),     ê_i = ½|û_i|²
//
// with the 3-D Mexican hat ψ(x) = (3 − |x|²)·e^(−|x|²/2) = −∇²e^(−|x|²/2). The choices the paper
// leaves open (docs/METHOD.md §3):
//   - Zero mean: u_j − u_i instead of u_j. Σ_j ψ_ij is not 0 on irregular samples (nor on any sample
//     once ψ is truncated: ∫_{|x|<R} ψ = 4πR³e^(−R²/2), 3.77 for R = 3, a third of the peak of ψ̂),
//     so Σ_j u_j ψ_ij would report a uniform flow as energy ∝ |u|². With u_j − u_i every term of a
//     uniform flow is fl(u − u) = 0: û_i = 0 exactly, in float too, whatever the sampling; û is
//     invariant under a Galilean change of frame. The price: in the continuum limit the response to
//     a plane wave of wavenumber k is ψ̂_R(ks) − ψ̂_R(0) (ψ̂_R the transform of the truncated ψ),
//     which does not vanish at large k (it oscillates about −ψ̂_R(0)): at R = 3 the energy of waves
//     shorter than 0.6 λ* (below) is up to 29 % of the peak's (a high-pass leak of the truncation;
//     a larger R shrinks it, ψ̂_R(0) = 4πR³e^(−R²/2), but needs a smaller s for the same grid).
//   - ψ_sum,i = Σ_j |ψ_ij|, j = i included (ψ(0) = 3, so ψ_sum >= 3: never a division by 0). It is
//     the discrete form of n·s³·∫|ψ| (n the particles' number density), so û does not change with
//     the particles' resolution or compression, and a particle at a free surface, with fewer
//     neighbours, is normalised by the neighbours it has. An analytic normalisation would need n,
//     which differs from 1/dx³ wherever the fluid is compressed or near a surface.
//   - Truncation: ψ is not compactly supported; the sums run over |x_i − x_j| < R·s with R = 3
//     (kTruncation), and s·R must not exceed the neighbour grid's cell (the SPH support h), so the
//     27 cells around x_i hold every term: s <= h/3, s = h/3 the largest scale (max_scale()).
//     Beyond r = 3, |ψ| is at most 0.067 (ψ(0) = 3), but its negative lobe is wide: 13 % of ∫|ψ| lies
//     beyond. At s = h/3 = 2dx/3 on particles of spacing dx the sampling still resolves ψ: the smooth
//     hat's first alias, at ks = 2πs/dx = 4.19, is ψ̂(4.19)/ψ̂(√2) = 0.4 % of its peak; the sharp cut
//     at r = 3s is sampled by shells of particles and moves the energy by a few % (wavelet_test.cpp).
//   - The response peaks at k s = 1.455 for R = 3 (√2 for R = ∞): wavelength λ* = 4.32 s.
// The output: energy() holds vec4(û_i, ê_i) per particle (storage block WaveletEnergy), in the
// cell order of the positions analysed.
// Units: û is a velocity (m/s), the ψ-weighted mean of the neighbours' velocity differences, and ê a
// kinetic energy per unit mass (m²/s²). The continuous transform's 1/√s is left out: with ψ_sum's
// normalisation it would only give ê a factor 1/s, which grows as the resolution (s ∝ h) refines and
// made the turbulence force of a scene blow up at a million particles that was stable at five
// thousand. Without it, the same velocity field at the same physical scale has the same ê at every
// resolution, and ê compares directly with ½|u|² (the sub-particles' threshold is in m²/s²).
#include <cstddef>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "shader/program.h"
#include "shared/bindings.h"

namespace ranryu::sim { class Fluid; }

namespace ranryu::turbulence {

class WaveletAnalysis {
public:
    // Truncation radius in units of s (see above).
    static constexpr float kTruncation = 3.0f;
    // The largest scale the neighbour grid of cell `cell` (m) can analyse: cell / kTruncation.
    static float max_scale(float cell) { return cell / kTruncation; }

    // Compiles the pass and allocates energy() for up to `capacity` particles.
    // `mask_runs` > 0 (sim::Fluid::neighbour_runs() of a fluid with neighbour masks) also builds the
    // variant that reads the density pass's masks for that many runs.
    WaveletAnalysis(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t capacity, int mask_runs = 0);
    static std::size_t bytes_for(std::size_t capacity);   // device memory the constructor allocates

    // ê of `fluid` at scale s (m), 0 < s <= max_scale(fluid.grid().layout().cell), from the
    // positions, velocities, cell ranges and sorted keys of its last rebuild_grid(). Exact when the
    // particles have not moved since (between rebuild_grid() and the integration, as a step's hooks and
    // the tests call it); after a whole step they have moved by up to ~0.4 dx (CFL), and a neighbour near
    // the cut, R·s = h, can fall outside the 27 cells searched (a term with |ψ| <= 0.07). Throws
    // InputError on a bad scale or more particles than the capacity. Runs inside a GpuTimer frame; ends
    // with a shader-storage barrier.
    void analyse(sim::Fluid& fluid, float scale);

    const gl::Buffer& energy() const { return energy_; }   // vec4[capacity]: (û_i, ê_i)
    // Which path the last analyse() took: 0 the grid walk, 1 the density pass's neighbour masks (built
    // with mask_runs and fluid.neighbour_masks_current(); analyse_velocity.comp). Tests.
    int last_path_masks() const { return last_masks_; }
    std::size_t capacity() const { return capacity_; }

private:
    profile::GpuTimer& timer_;
    profile::PassId pass_;
    shader::Program program_, masked_;
    int mask_runs_;
    std::size_t capacity_;
    int last_masks_ = 0;
    gl::Buffer energy_, params_;
    gpu::WaveletParams params_value_{};   // what params_ holds
    bool uploaded_ = false;
};

}  // namespace ranryu::turbulence
