#include "turbulence/force.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "shared/bindings.h"
#include "sim/fluid.h"

namespace ranryu::turbulence {

namespace {
constexpr std::uint32_t kSeedWords = std::uint32_t(sizeof(gpu::NoiseSeed) / sizeof(std::uint32_t));
std::vector<std::uint32_t> unseeded_words() {
    const gpu::NoiseSeed s = unseeded_noise();
    std::vector<std::uint32_t> w(sizeof s / sizeof(std::uint32_t));
    std::memcpy(w.data(), &s, sizeof s);
    return w;
}
}  // namespace

TurbulenceForce::TurbulenceForce(const shader::FileSource& shaders, profile::GpuTimer& timer,
                                 const scene::TurbulenceSettings& settings, sim::Fluid& fluid)
    : timer_(timer),
      pass_(timer.pass("turbulence-force")),
      settings_(settings),
      // settings.scale <= 1/3 (scene.cpp); the clamp absorbs float rounding of s = h/3.
      scale_(std::min(settings.scale * fluid.params().h, WaveletAnalysis::max_scale(fluid.params().h))),
      tiles_(NoiseTiles::generate(settings.seed)),
      wavelet_(shaders, timer, fluid.count(), fluid.neighbour_masks().id() ? fluid.neighbour_runs() : 0),
      noise_(shaders, timer, tiles_),
      program_(shader::Program::compute(shaders, "turbulence/apply_turbulence_force.comp")),
      noise_params_(sizeof(gpu::NoiseParams), GL_STATIC_DRAW, nullptr, "turbulence NoiseParams"),
      fluid_(fluid),
      seeds_(fluid.carry("NoiseSeeds", kSeedWords, unseeded_words())) {
    gpu::NoiseParams p{};
    p.lmin = settings.lmin;
    p.lmax = settings.lmax;
    p.beta = settings.beta;
    p.tile_size = std::uint32_t(tiles_.n);
    noise_params_.upload_value(p);   // the sampling grid's fields are unused by the force pass
    glProgramUniform1f(program_.id(), RANRYU_LOC_TURBULENCE_AMPLITUDE, settings.amplitude);
    glProgramUniform1f(program_.id(), RANRYU_LOC_COHERENCE_TIME, settings.coherence_time);
}

void TurbulenceForce::set_amplitude(float amplitude) {
    settings_.amplitude = amplitude;
    glProgramUniform1f(program_.id(), RANRYU_LOC_TURBULENCE_AMPLITUDE, amplitude);
}

std::size_t TurbulenceForce::bytes_for(std::size_t count) {
    return CurlNoise::bytes_for(kDefaultTileSize) + WaveletAnalysis::bytes_for(count) + sizeof(gpu::NoiseParams) +
           sim::Fluid::carried_bytes(count, kSeedWords);
}

const gl::Buffer& TurbulenceForce::noise_seeds() const { return fluid_.carried(seeds_); }

void TurbulenceForce::analyse(sim::Fluid& fluid) { wavelet_.analyse(fluid, scale_); }

void TurbulenceForce::apply(sim::Fluid& fluid) {
    if (fluid.count() == 0) return;
    auto pass = timer_.scope(pass_);
    noise_params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_NOISE);
    program_.bind(fluid.bind_state().with("NoiseTiles", noise_.tiles()).with("WaveletEnergy", wavelet_.energy()))
        .dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace ranryu::turbulence
