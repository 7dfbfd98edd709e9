#include "turbulence/force.h"

#include <algorithm>

#include "shared/bindings.h"
#include "sim/sph.h"

namespace ranryu::turbulence {

TurbulenceForce::TurbulenceForce(const shader::FileSource& shaders, profile::GpuTimer& timer,
                                 const scene::TurbulenceSettings& settings, float h, std::size_t capacity, int mask_runs)
    : timer_(timer),
      pass_(timer.pass("turbulence-force")),
      settings_(settings),
      // settings.scale <= 1/3 (scene.cpp); the clamp absorbs float rounding of s = h/3.
      scale_(std::min(settings.scale * h, WaveletAnalysis::max_scale(h))),
      tiles_(NoiseTiles::generate(settings.seed)),
      wavelet_(shaders, timer, capacity, mask_runs),
      noise_(shaders, timer, tiles_),
      program_(shader::Program::compute(shaders, "turbulence/apply_turbulence_force.comp")),
      noise_params_(sizeof(gpu::NoiseParams), GL_STATIC_DRAW, nullptr, "turbulence NoiseParams") {
    gpu::NoiseParams p{};
    p.lmin = settings.lmin;
    p.lmax = settings.lmax;
    p.beta = settings.beta;
    p.tile_size = std::uint32_t(tiles_.n);
    noise_params_.upload_value(p);   // the sampling grid's fields are unused by the force pass
    glProgramUniform1f(program_.id(), RANRYU_LOC_TURBULENCE_AMPLITUDE, settings.amplitude);
    glProgramUniform1f(program_.id(), RANRYU_LOC_COHERENCE_TIME, settings.coherence_time);
}

void TurbulenceForce::analyse(sim::Sph& sph) { wavelet_.analyse(sph, scale_); }

void TurbulenceForce::apply(sim::Sph& sph) {
    if (sph.count() == 0) return;
    auto pass = timer_.scope(pass_);
    noise_params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_NOISE);
    noise_.tiles().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_NOISE_TILES);
    wavelet_.energy().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_WAVELET_ENERGY);
    sph.noise_seeds()->bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_NOISE_SEED);
    program_.dispatch(sph.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace ranryu::turbulence
