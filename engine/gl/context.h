#pragma once
// OpenGL 4.3 core contexts: headless through EGL (device platform first, so an NVIDIA GPU is used
// where there is one; Mesa's surfaceless platform otherwise, which gives llvmpipe with no GPU) and,
// in engine/gl/window.h, a GLFW window. Both print the same DeviceInfo line at start.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace ranryu::gl {

struct DeviceInfo {
    std::string vendor;     // GL_VENDOR
    std::string renderer;   // GL_RENDERER, e.g. "NVIDIA H100 80GB HBM3/PCIe/SSE2" or "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version;    // GL_VERSION, which carries the driver version on NVIDIA and Mesa
    std::string glsl;       // GL_SHADING_LANGUAGE_VERSION
    std::string platform;   // "EGL device", "EGL surfaceless", "GLFW"
    bool timer_queries = false;
    bool robust = false;    // lose-context-on-reset: a lost context is reported (gl/faults.h), not drawn from
    std::string line() const;   // one line for logs: renderer | GL version | platform
};

// Whether the current context lists GL extension `name`.
bool has_extension(std::string_view name);
// Whether the current context's renderer is a software rasteriser (Mesa's llvmpipe or softpipe): its
// "device" memory is host memory and its raster a loop over the covered pixels on the CPU.
bool software_renderer();

// Reads DeviceInfo from the current context.
DeviceInfo query_device(const std::string& platform);

// Installs a KHR_debug callback (debug contexts only) that prints driver messages above notification
// severity to stderr and keeps GL errors for take_gl_errors(), which the tests check after each case.
// Never throws: the callback runs inside the driver.
void install_debug_callback();
std::vector<std::string> take_gl_errors();

class HeadlessContext {
public:
    // Creates and makes current a GL 4.3 core context with no surface. `debug` asks for a debug
    // context. Throws ranryu::Error naming every platform tried when none works.
    explicit HeadlessContext(bool debug);
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;
    const DeviceInfo& info() const { return info_; }

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    DeviceInfo info_;
};

}  // namespace ranryu::gl
