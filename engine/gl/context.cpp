#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/context.h"
#include "gl/gl.h"

namespace ranryu::gl {
namespace {

std::string gl_string(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "?";
}

const char* source_name(GLenum s) {
    switch (s) {
        case GL_DEBUG_SOURCE_API: return "api";
        case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
        case GL_DEBUG_SOURCE_APPLICATION: return "application";
        default: return "other";
    }
}

void APIENTRY on_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* msg,
                           const void* user) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    // Compile errors are reported by shader::Program with file names and lines; the raw copy would
    // carry the driver's source-string numbers instead.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    const bool is_error = type == GL_DEBUG_TYPE_ERROR;
    std::fprintf(stderr, "ranryu: GL %s (%s, id %u): %s\n", is_error ? "error" : "message", source_name(source),
                 id, msg);
    if (is_error && user) static_cast<std::vector<std::string>*>(const_cast<void*>(user))->push_back(msg);
}

std::vector<std::string> g_errors;  // GL errors since the last take_gl_errors(); one context per process

}  // namespace

bool has_extension(std::string_view name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && name == e) return true;
    }
    return false;
}

bool software_renderer() {
    const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string_view renderer = r ? r : "";
    return renderer.find("llvmpipe") != std::string_view::npos || renderer.find("softpipe") != std::string_view::npos;
}

std::string DeviceInfo::line() const { return renderer + " | OpenGL " + version + " | " + platform; }

DeviceInfo query_device(const std::string& platform) {
    DeviceInfo d;
    d.vendor = gl_string(GL_VENDOR);
    d.renderer = gl_string(GL_RENDERER);
    d.version = gl_string(GL_VERSION);
    d.glsl = gl_string(GL_SHADING_LANGUAGE_VERSION);
    d.platform = platform;
    GLint bits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
    d.timer_queries = bits > 0;
    GLint strategy = 0;
    glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    d.robust = strategy == GL_LOSE_CONTEXT_ON_RESET;
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 43)
        throw Error("OpenGL " + d.version + " on " + d.renderer + " is older than the 4.3 that ranryu needs");
    return d;
}

void install_debug_callback() {
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT)) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_message, &g_errors);
}

std::vector<std::string> take_gl_errors() {
    std::vector<std::string> out;
    out.swap(g_errors);
    return out;
}

}  // namespace ranryu::gl
