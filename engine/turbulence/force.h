#pragma once
// The turbulence force on the SPH particles (METHOD.md §5):
//
//     f_i = A · (P_i / Δt) · ê_i · y(x_i)
//
// Reading of P_i: P_i = m_i·Δt, the particle's mass times the substep. The pass adds f_i / m_i to
// the acceleration:
//
//     a_i += A · ê_i · y_c(x_i)        (per unit mass; the same whatever the substep or resolution)
//
// Why: the force per unit mass must not depend on the particle's mass (m = ρ0 dx³ changes with the
// resolution) nor on the SPH's dt (smaller at finer resolution). An earlier reading, P_i = m_i, made
// the model a velocity kick A·ê·y per substep, i.e. an acceleration ∝ 1/dt: with ê ∝ 1/s on top
// (wavelet.h), a jet stable at 5k particles went non-finite in its first frame at 943k on the H100.
// Units: ê_i is m²/s² (wavelet.h), y_c is dimensionless (noise.h), so A is 1/m: A·ê is the
// acceleration of an eddy of kinetic energy ê and size 1/A. As the resolution refines, the SPH resolves
// more of the flow and the unresolved ê at s ∝ h falls, and with it the force: the model converges.
// y_c is the noise carried with the fluid (glsl/turbulence/carried_noise.glsl), re-seeded every
// settings.coherence_time.
//
// Each substep, when enabled: "wavelet" (WaveletAnalysis::analyse at s = scale·h) after the density
// pass, on the current cell order, and "turbulence-force" after the forces pass and before integrate.
// The force pass also folds its |a_i| into StepState.max_accel (the next substep's dt, eq. (7)), and
// re-seeds the carried noise (Sph::noise_seeds(), moved with the particles by the reorder).
#include <cstddef>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/program.h"
#include "turbulence/noise.h"
#include "turbulence/wavelet.h"

namespace ranryu::sim { class Sph; }

namespace ranryu::turbulence {

class TurbulenceForce {
public:
    // Tiles from settings.seed, the wavelet buffer for `capacity` particles. `h` is the SPH support (m);
    // `mask_runs`, the SPH's neighbour-mask runs (0: none), as WaveletAnalysis takes it.
    TurbulenceForce(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::TurbulenceSettings& settings,
                    float h, std::size_t capacity, int mask_runs = 0);

    void analyse(sim::Sph& sph);   // "wavelet": ê of sph's current cell order
    // "turbulence-force": a_i += A ê_i y_c,i on sph.accelerations(), re-seeding sph.noise_seeds();
    // binds the SPH's fields first (the caller's bind), then the noise, wavelet and seed buffers.
    void apply(sim::Sph& sph);

    const WaveletAnalysis& wavelet() const { return wavelet_; }
    const NoiseTiles& tiles() const { return tiles_; }   // the CPU copy (tests: curl_noise_octaves)
    const CurlNoise& noise() const { return noise_; }    // the GPU tiles (the sub-particles bind them)
    const scene::TurbulenceSettings& settings() const { return settings_; }
    float scale() const { return scale_; }                // s (m)

private:
    profile::GpuTimer& timer_;
    profile::PassId pass_;
    scene::TurbulenceSettings settings_;
    float scale_;
    NoiseTiles tiles_;
    WaveletAnalysis wavelet_;
    CurlNoise noise_;
    shader::Program program_;
    gl::Buffer noise_params_;
};

}  // namespace ranryu::turbulence
