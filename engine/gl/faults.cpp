#include "gl/faults.h"

#include <cstdio>
#include <cstdlib>
#include <thread>
#include <utility>

#include "gl/gl.h"

namespace ranryu::gl {
namespace {

bool g_checks = false;
std::string g_pass;
std::optional<std::string> g_fault;

const char* error_name(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
        default: return "unknown";
    }
}

}  // namespace

void set_error_checks(bool on) { g_checks = on; }
bool error_checks() { return g_checks; }
void set_current_pass(const std::string& name) { g_pass = name; }
const std::string& current_pass() { return g_pass; }

void check_gl_error(const std::string& pass) {
    if (!g_checks) return;
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR || g_fault) return;
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", unsigned(e));
    g_fault = std::string("GL error ") + code + " (" + error_name(e) + ") in pass " + (pass.empty() ? "(none)" : pass);
}

std::optional<std::string> take_fault() { return std::exchange(g_fault, std::nullopt); }

void check_faults(std::uint64_t frame) {
    check_gl_error("(between passes)");
    if (auto f = take_fault()) throw GpuFault(*f + ", frame " + std::to_string(frame));
    const GLenum reset = glGetGraphicsResetStatus();   // GL 4.5; NO_ERROR unless a robust context was lost
    if (reset != GL_NO_ERROR)
        throw GpuFault(std::string("the GL context was lost (") +
                       (reset == GL_GUILTY_CONTEXT_RESET ? "guilty" : reset == GL_INNOCENT_CONTEXT_RESET ? "innocent" : "unknown") +
                       " reset) by frame " + std::to_string(frame) + (g_pass.empty() ? "" : ", last pass " + g_pass));
}

double fence_timeout_seconds() {
    if (const char* env = std::getenv("RANRYU_FENCE_TIMEOUT_SECONDS")) {
        char* end = nullptr;
        const double s = std::strtod(env, &end);
        if (*env && !*end && s > 0.0) return s;
    }
    return 10.0;
}

void wait_or_fault(const std::function<bool()>& signaled, std::chrono::duration<double> timeout, const std::string& what) {
    const auto start = std::chrono::steady_clock::now();
    while (!signaled()) {
        if (std::chrono::steady_clock::now() - start >= timeout) {
            char secs[32];
            std::snprintf(secs, sizeof secs, "%g", timeout.count());
            throw GpuFault("GPU fence of " + what + " has not signalled after " + secs + " s");
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
}

}  // namespace ranryu::gl
