#include "frame/memory.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "frame/pipeline.h"
#include "gl/context.h"
#include "gl/gl.h"

namespace ranryu::frame {
namespace {

constexpr GLenum kNvxCurrentAvailable = 0x9049;   // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX (KiB)
constexpr GLenum kAtiVboFree = 0x87FB;            // GL_VBO_FREE_MEMORY_ATI: [0] total free (KiB)

std::optional<std::uint64_t> host_available() {
    std::ifstream in("/proc/meminfo");
    for (std::string line; std::getline(in, line);)
        if (line.starts_with("MemAvailable:")) {
            std::istringstream s(line.substr(13));
            std::uint64_t kib = 0;
            if (s >> kib) return kib * 1024;
        }
    return std::nullopt;
}

std::string fmt_spacing(float dx) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", double(dx));
    return buf;
}

// Rounds up to 3 significant figures.
float round_up_3(float dx) {
    const double step = std::pow(10.0, std::floor(std::log10(double(dx))) - 2.0);
    return float(std::ceil(double(dx) / step - 1e-6) * step);
}

}  // namespace

std::uint64_t MemoryEstimate::total() const {
    std::uint64_t t = extra;
    for (const MemoryPart& p : parts) t += p.bytes;
    return t;
}

std::string mib(std::uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
    return buf;
}

DeviceMemory device_capacity();   // below: the memory figures alone

DeviceMemory device_memory() {
    DeviceMemory d = device_capacity();
    GLint groups = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &groups);
    if (groups > 0) d.max_workgroups = std::uint64_t(groups);
    return d;
}

DeviceMemory device_capacity() {
    if (const char* env = std::getenv("RANRYU_MEMORY_LIMIT_MB")) {
        char* end = nullptr;
        const double mb = std::strtod(env, &end);
        if (!*env || *end || !(mb > 0.0 && mb < 1e9))
            throw InputError(std::string("RANRYU_MEMORY_LIMIT_MB=") + env + ": expected a positive number of MiB");
        return {std::uint64_t(mb * 1024.0 * 1024.0), "RANRYU_MEMORY_LIMIT_MB", std::nullopt};
    }
    // A software rasteriser's buffers are host memory (Mesa's llvmpipe reports NVX figures of its own).
    const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = r ? r : "";
    if (gl::software_renderer())
        if (const auto host = host_available()) return {*host, "host memory (MemAvailable), " + renderer.substr(0, renderer.find(' ')), std::nullopt};
    if (gl::has_extension("GL_NVX_gpu_memory_info")) {
        GLint kib = 0;
        glGetIntegerv(kNvxCurrentAvailable, &kib);
        if (kib > 0) return {std::uint64_t(kib) * 1024, "GL_NVX_gpu_memory_info", std::nullopt};
    }
    if (gl::has_extension("GL_ATI_meminfo")) {
        GLint v[4] = {0, 0, 0, 0};
        glGetIntegerv(kAtiVboFree, v);
        if (v[0] > 0) return {std::uint64_t(v[0]) * 1024, "GL_ATI_meminfo", std::nullopt};
    }
    return {std::nullopt, "not reported by " + renderer, std::nullopt};
}

std::optional<float> finest_spacing_within(const scene::Scene& scene, const View& view, std::uint64_t budget) {
    const auto fits = [&](float dx, std::uint64_t& total) {
        total = Pipeline::memory_estimate(scene::with_spacing(scene, dx, "the fitted spacing"), view).total();
        return total <= budget;
    };
    // The particle arrays scale as 1/dx³: scale the spacing by the cube root of the excess until it
    // fits, then round up and check again (lattice counts are not quite smooth in dx).
    float dx = scene.spacing;
    std::uint64_t total = Pipeline::memory_estimate(scene, view).total();
    try {
        for (int i = 0; i < 60; ++i) {
            if (total <= budget) break;
            dx = round_up_3(dx * float(std::max(std::cbrt(double(total) / double(budget)), 1.01)));
            fits(dx, total);
        }
        for (int i = 0; i < 60 && !fits(dx, total); ++i) dx = round_up_3(dx * 1.01f);
        if (total > budget) return std::nullopt;
    } catch (const InputError&) {   // coarse enough to leave no particle
        return std::nullopt;
    }
    return dx;
}

// The dispatch limit of DeviceMemory::max_workgroups (see check_memory()).
static void check_dispatch_reach(const scene::Scene& scene, const MemoryEstimate& e, const DeviceMemory& device) {
    if (device.max_workgroups && e.particles > *device.max_workgroups * kParticleWorkgroup) {
        const std::uint64_t reach = *device.max_workgroups * kParticleWorkgroup;
        float dx = round_up_3(scene.spacing * float(std::cbrt(double(e.particles) / double(reach))));
        for (int i = 0; i < 60 && scene::with_spacing(scene, dx, "the fitted spacing").particle_count() > reach; ++i)
            dx = round_up_3(dx * 1.01f);
        throw InputError("scene " + scene.name + " at spacing " + fmt_spacing(scene.spacing) + " m: " + std::to_string(e.particles) +
                         " particles are more than one dispatch reaches on this device (" + std::to_string(*device.max_workgroups) +
                         " workgroups of " + std::to_string(kParticleWorkgroup) + ": " + std::to_string(reach) +
                         " particles); the finest spacing within it is --spacing " + fmt_spacing(dx));
    }
}

MemoryEstimate check_memory(const scene::Scene& scene, const View& view, const DeviceMemory& device) {
    MemoryEstimate e = Pipeline::memory_estimate(scene, view);
    if (!device.available) return check_dispatch_reach(scene, e, device), e;
    const auto budget = std::uint64_t(kMemoryFraction * double(*device.available));
    if (e.total() <= budget) return check_dispatch_reach(scene, e, device), e;
    std::string parts;
    for (const MemoryPart& p : e.parts)
        if (p.bytes * 20 >= e.total()) parts += (parts.empty() ? "" : ", ") + p.name + " " + mib(p.bytes);
    const std::optional<float> fit = finest_spacing_within(scene, view, budget);
    std::string suggestion = "; no spacing of this scene fits";
    if (fit) {
        const scene::Scene at = scene::with_spacing(scene, *fit, "the fitted spacing");
        const MemoryEstimate f = Pipeline::memory_estimate(at, view);
        suggestion = "; the finest spacing that fits is --spacing " + fmt_spacing(*fit) + " (" + std::to_string(f.particles) +
                     " particles, estimated " + mib(f.total()) + ")";
    }
    throw InputError("scene " + scene.name + " at spacing " + fmt_spacing(scene.spacing) + " m: " + std::to_string(e.particles) +
                     " particles need an estimated " + mib(e.total()) + " of device memory (" + parts + "), more than " +
                     std::to_string(int(kMemoryFraction * 100.0 + 0.5)) + " % of the " + mib(*device.available) +
                     " available (" + device.source + ")" + suggestion);
}

}  // namespace ranryu::frame
