#pragma once
// Resource limits (issue 15, item 4): before a pipeline allocates, the device memory it will hold is
// estimated from the scene (Pipeline::memory_estimate: each component's bytes_for() beside its
// constructor, the same size expressions) and compared with what the device has free:
//
//     GL_NVX_gpu_memory_info   current available video memory (NVIDIA)
//     GL_ATI_meminfo           free VBO memory (AMD)
//     llvmpipe / softpipe      MemAvailable of /proc/meminfo: the "device" is host memory
//     RANRYU_MEMORY_LIMIT_MB   overrides all of them (tests, or to keep a run below a budget)
//
// A scene whose estimate exceeds kMemoryFraction of that is refused (InputError, exit 2) with the
// estimate and the finest spacing that fits. A device that reports nothing is not checked.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace ranryu::frame {

struct View;

constexpr double kMemoryFraction = 0.9;   // of the available memory a scene may take

struct MemoryPart {
    std::string name;
    std::uint64_t bytes = 0;
};

struct MemoryEstimate {
    std::size_t particles = 0, boundary = 0;
    std::vector<MemoryPart> parts;   // what the pipeline keeps after construction
    std::uint64_t transient = 0;     // held besides during start-up, then freed
    std::uint64_t extra = 0;         // what the command allocates beside the pipeline (View::extra_bytes)
    std::uint64_t total() const;     // parts + extra
};

struct DeviceMemory {
    std::optional<std::uint64_t> available;   // bytes; nothing when the device does not say
    std::string source;                       // where the number came from
    // GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]: a per-particle pass is one 1-D dispatch, so a scene may have
    // at most this times kParticleWorkgroup particles (nothing: not checked).
    std::optional<std::uint64_t> max_workgroups;
};

// The smallest workgroup of the per-particle passes (local_size_x 128 or 256 in glsl/sim,
// glsl/turbulence): with the device's dispatch limit, the most particles a scene may have.
constexpr std::uint64_t kParticleWorkgroup = 128;

// What the current context's device has free (see the header comment). Throws InputError on a
// malformed RANRYU_MEMORY_LIMIT_MB.
DeviceMemory device_memory();

// The estimate for `scene` drawn as `view` (Pipeline::memory_estimate) against `device`: throws
// InputError naming the scene, spacing, particle count, estimate, what is available and the finest
// spacing that fits, when the estimate exceeds kMemoryFraction of device.available, or when the
// particles are more than one dispatch reaches (device.max_workgroups). Returns the estimate.
MemoryEstimate check_memory(const scene::Scene& scene, const View& view, const DeviceMemory& device);

// A pipeline's estimate next to what its construction allocated (gl::allocated_bytes()).
struct MemoryUse {
    MemoryEstimate estimate;
    std::uint64_t allocated = 0;   // live after construction
    std::uint64_t peak = 0;        // the most live during construction, transient buffers included
    DeviceMemory device;
};

// The finest particle spacing, rounded up to 3 significant figures, whose estimate fits `budget`
// bytes; nothing when even the coarsest spacing with a particle left does not.
std::optional<float> finest_spacing_within(const scene::Scene& scene, const View& view, std::uint64_t budget);

// "1234.5 MiB"
std::string mib(std::uint64_t bytes);

}  // namespace ranryu::frame
