#pragma once
// The turbulence force on the SPH particles (docs/METHOD.md §5):
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
// Each step, when enabled, as the step's hooks (sim/solver.h): "wavelet" (WaveletAnalysis::analyse
// at s = scale·h) after the solver's density pass, on the current cell order, and "turbulence-force"
// once the non-pressure accelerations are in the fluid's accelerations(), before they are applied.
// The force pass also folds its |a_i| into StepState.max_accel (the next step's dt), and re-seeds the
// carried noise (noise_seeds(): a carried array of the fluid, moved with the particles by the reorder).
#include <cstddef>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/program.h"
#include "sim/solver.h"
#include "turbulence/noise.h"
#include "turbulence/wavelet.h"

namespace ranryu::sim { class Fluid; }

namespace ranryu::turbulence {

class TurbulenceForce final : public sim::StepHooks {
public:
    // Tiles from settings.seed, the wavelet buffer for the fluid's particles and their noise seeds,
    // carried by the fluid (every particle unseeded at first).
    // Device memory the constructor allocates for `count` particles: the noise tiles, the wavelet
    // energies and the carried noise seeds (frame/memory.h).
    static std::size_t bytes_for(std::size_t count);
    TurbulenceForce(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::TurbulenceSettings& settings,
                    sim::Fluid& fluid);

    void analyse(sim::Fluid& fluid);   // "wavelet": ê of the fluid's current cell order
    // "turbulence-force": a_i += A ê_i y_c,i on fluid.accelerations(), re-seeding noise_seeds().
    void apply(sim::Fluid& fluid);
    void after_density(sim::Fluid& fluid) override { analyse(fluid); }
    void add_accelerations(sim::Fluid& fluid) override { apply(fluid); }

    // The carried noise's seeds: gpu::NoiseSeed per particle, in the fluid's current cell order.
    const gl::Buffer& noise_seeds() const;

    const WaveletAnalysis& wavelet() const { return wavelet_; }
    const NoiseTiles& tiles() const { return tiles_; }   // the CPU copy (tests: curl_noise_octaves)
    const CurlNoise& noise() const { return noise_; }    // the GPU tiles (the sub-particles bind them)
    const scene::TurbulenceSettings& settings() const { return settings_; }
    // Live (run's panel): A from the next step on; 0 turns the force off while ê is still analysed.
    void set_amplitude(float amplitude);
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
    const sim::Fluid& fluid_;
    int seeds_;   // the fluid's carried array
};

}  // namespace ranryu::turbulence
