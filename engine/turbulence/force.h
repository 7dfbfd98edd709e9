#pragma once
// The turbulence force on the SPH particles (METHOD.md §5):
//
//     f_i = A · (P_i / Δt) · ê_i · y(x_i)
//
// Reading of P_i: P_i = m_i, the particle's mass. The pass adds f_i / m_i to the acceleration, so
//
//     a_i += A · ê_i · y(x_i) / Δt,        i.e. the substep's velocity kick is Δv_i = A · ê_i · y(x_i).
//
// Why mass: f/m is then independent of the particle's mass and of the resolution's m = ρ0 dx³, and
// the 1/Δt makes the model a velocity kick per substep (what the method's "P/Δt" reads as: a
// momentum P delivered over one step) whose size depends on ê and y only, not on the SPH's dt.
// Units: ê_i is m/s² (wavelet.h: (m/s)²/m from the 1/√s normalisation), y is dimensionless (the curl
// of the noise in noise coordinates, noise.h), Δt is s: A carries seconds, Δv = A·ê·y is m/s and a is
// m/s². Δt is the substep's dt as chosen on the GPU (StepState.dt), read by the pass.
//
// Each substep, when enabled: "wavelet" (WaveletAnalysis::analyse at s = scale·h) after the density
// pass, on the current cell order, and "turbulence-force" after the forces pass and before integrate.
// The force pass also folds its |a_i| into StepState.max_accel (the next substep's dt, eq. (7)).
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
    // Tiles from settings.seed, the wavelet buffer for `capacity` particles. `h` is the SPH support (m).
    TurbulenceForce(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::TurbulenceSettings& settings,
                    float h, std::size_t capacity);

    void analyse(sim::Sph& sph);   // "wavelet": ê of sph's current cell order
    // "turbulence-force": a_i += A ê_i y(x_i) / dt on sph.accelerations(); binds the SPH's fields
    // first (the caller's bind), then the noise and wavelet buffers.
    void apply(sim::Sph& sph);

    const WaveletAnalysis& wavelet() const { return wavelet_; }
    const NoiseTiles& tiles() const { return tiles_; }   // the CPU copy (tests: curl_noise_octaves)
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
