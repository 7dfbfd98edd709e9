#include "turbulence/wavelet.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/error.h"
#include "sim/sph.h"

namespace ranryu::turbulence {

WaveletAnalysis::WaveletAnalysis(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t capacity,
                                 int mask_runs)
    : timer_(timer),
      pass_(timer.pass("wavelet")),
      // 27 cells per particle, never RANRYU_MERGE_ROWS: correct for linear and Morton keys alike.
      program_(shader::Program::compute(shaders, "turbulence/analyse_velocity.comp")),
      masked_(mask_runs > 0 ? shader::Program::compute(shaders, "turbulence/analyse_velocity.comp",
                                                       "#define RANRYU_NEIGHBOUR_RUNS " + std::to_string(mask_runs) + "u\n")
                            : shader::Program()),
      mask_runs_(mask_runs),
      capacity_(capacity),
      energy_(std::max<std::size_t>(capacity, 1) * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "wavelet energy"),
      params_(sizeof(gpu::WaveletParams), GL_DYNAMIC_DRAW, nullptr, "WaveletParams"),
      sph_params_(sizeof(gpu::SphParams), GL_DYNAMIC_DRAW, nullptr, "wavelet SphParams") {}

void WaveletAnalysis::analyse(sim::Sph& sph, float scale) {
    const std::size_t count = sph.count();
    const float cell = sph.grid().layout().cell;
    // s·R <= cell, with a float rounding's slack so that s = max_scale(cell) itself passes.
    if (!(scale > 0.0f) || !std::isfinite(scale) || scale * kTruncation > cell * (1.0f + 1e-6f))
        throw InputError("wavelet: scale " + std::to_string(scale) + " m must be positive and at most the grid cell / " +
                         std::to_string(kTruncation) + " = " + std::to_string(max_scale(cell)) + " m");
    if (count > capacity_)
        throw InputError("wavelet: " + std::to_string(count) + " particles exceed the capacity " + std::to_string(capacity_));
    if (count == 0) return;

    auto pass = timer_.scope(pass_);
    // The constants change only with the scale, the count or the SPH: upload them then, not every substep.
    const gpu::WaveletParams p{scale, kTruncation, std::uint32_t(count), 0u};
    if (!uploaded_ || std::memcmp(&p, &params_value_, sizeof p) != 0) params_.upload_value(params_value_ = p);
    if (!uploaded_ || std::memcmp(&sph.params(), &sph_value_, sizeof sph_value_) != 0)
        sph_params_.upload_value(sph_value_ = sph.params());   // fluid_run() reads particle_count
    uploaded_ = true;
    sph_params_.bind_base(GL_UNIFORM_BUFFER, RANRYU_UBO_SPH);
    sph.grid().bind_params(count);
    sph.positions().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_POSITION);
    sph.velocities().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_VELOCITY);
    sph.cell_ranges().start.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_CELL_START);
    sph.cell_ranges().end.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_CELL_END);
    sph.grid().sort().sorted_keys().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_SORT_KEYS);
    params_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_WAVELET_PARAMS);
    energy_.bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_WAVELET_ENERGY);
    last_masks_ = masked_.id() && sph.neighbour_masks_current() && sph.neighbour_runs() == mask_runs_ ? 1 : 0;
    if (last_masks_) {
        sph.densities().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_DENSITY);
        sph.neighbour_masks().bind_base(GL_SHADER_STORAGE_BUFFER, RANRYU_SSBO_NEIGHBOURS);
        masked_.dispatch(count);
    } else {
        program_.dispatch(count);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace ranryu::turbulence
