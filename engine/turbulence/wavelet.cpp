#include "turbulence/wavelet.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/error.h"
#include "sim/fluid.h"

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
      energy_(bytes_for(capacity) - sizeof(gpu::WaveletParams), GL_DYNAMIC_COPY, nullptr, "wavelet energy"),
      params_(sizeof(gpu::WaveletParams), GL_DYNAMIC_DRAW, nullptr, "WaveletParams") {}

std::size_t WaveletAnalysis::bytes_for(std::size_t capacity) {
    return std::max<std::size_t>(capacity, 1) * sizeof(glm::vec4) + sizeof(gpu::WaveletParams);
}

void WaveletAnalysis::analyse(sim::Fluid& fluid, float scale) {
    const std::size_t count = fluid.count();
    const float cell = fluid.grid().layout().cell;
    // s·R <= cell, with a float rounding's slack so that s = max_scale(cell) itself passes.
    if (!(scale > 0.0f) || !std::isfinite(scale) || scale * kTruncation > cell * (1.0f + 1e-6f))
        throw InputError("wavelet: scale " + std::to_string(scale) + " m must be positive and at most the grid cell / " +
                         std::to_string(kTruncation) + " = " + std::to_string(max_scale(cell)) + " m");
    if (count > capacity_)
        throw InputError("wavelet: " + std::to_string(count) + " particles exceed the capacity " + std::to_string(capacity_));
    if (count == 0) return;

    auto pass = timer_.scope(pass_);
    // The constants change only with the scale or the count: upload them then, not every substep.
    const gpu::WaveletParams p{scale, kTruncation, std::uint32_t(count), 0u};
    if (!uploaded_ || std::memcmp(&p, &params_value_, sizeof p) != 0) params_.upload_value(params_value_ = p);
    uploaded_ = true;
    const shader::StorageSet buffers = fluid.bind_state().with("WaveletConstants", params_).with("WaveletEnergy", energy_);
    last_masks_ = masked_.id() && fluid.neighbour_masks_current() && fluid.neighbour_runs() == mask_runs_ ? 1 : 0;
    (last_masks_ ? masked_ : program_).bind(buffers).dispatch(count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace ranryu::turbulence
