#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/context.h"
#include "gl/gl.h"

namespace ranryu::gl {
namespace {

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// Tries to make a GL 4.3 core context current on `dpy`. Returns the context, or nullptr with a reason.
EGLContext try_context(EGLDisplay dpy, bool debug, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) {
        why = "eglInitialize failed";
        return EGL_NO_CONTEXT;
    }
    const char* ext = eglQueryString(dpy, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_surfaceless_context")) {
        why = "no EGL_KHR_surfaceless_context";
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed";
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    EGLConfig config = nullptr;
    if (!has_extension(ext, "EGL_KHR_no_config_context")) {
        const EGLint attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, attrs, &config, 1, &n) || n == 0) {
            why = "no EGL config with OpenGL";
            eglTerminate(dpy);
            return EGL_NO_CONTEXT;
        }
    }
    // Robust where the driver offers it (EGL 1.5): a lost context then reports its reset through
    // glGetGraphicsResetStatus, which gl/faults.h checks at every frame's end. Else a plain context.
    const EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                             EGL_CONTEXT_MINOR_VERSION, 3,
                             EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                             EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                             EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE,
                             EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY, EGL_LOSE_CONTEXT_ON_RESET,
                             EGL_NONE};
    const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                            EGL_CONTEXT_MINOR_VERSION, 3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                            EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, robust);
    if (ctx == EGL_NO_CONTEXT) ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attrs);
    if (ctx == EGL_NO_CONTEXT) {
        why = "no OpenGL 4.3 core context (EGL error 0x" + std::to_string(eglGetError()) + ")";
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        why = "eglMakeCurrent failed";
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    return ctx;
}

}  // namespace

HeadlessContext::HeadlessContext(bool debug) {
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!get_platform_display) throw Error("EGL has no eglGetPlatformDisplayEXT: cannot create a headless context");

    // RANRYU_EGL_PLATFORM=device|surfaceless forces one platform (for tests and diagnosis).
    const char* force = std::getenv("RANRYU_EGL_PLATFORM");
    const std::string forced = force ? force : "";
    std::string tried;

    if ((forced.empty() || forced == "device") && query_devices) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (query_devices(16, devices, &count) && count > 0) {
            // Hardware devices first: Mesa also lists a software device, which must not win over a GPU.
            std::vector<EGLDeviceEXT> order(devices, devices + count);
            auto is_software = [&](EGLDeviceEXT d) {
                return query_device_string &&
                       has_extension(query_device_string(d, EGL_EXTENSIONS), "EGL_MESA_device_software");
            };
            std::stable_partition(order.begin(), order.end(), [&](EGLDeviceEXT d) { return !is_software(d); });
            for (std::size_t i = 0; i < order.size(); ++i) {
                EGLDisplay dpy = get_platform_display(EGL_PLATFORM_DEVICE_EXT, order[i], nullptr);
                std::string why = "no display";
                if (dpy != EGL_NO_DISPLAY) {
                    if (EGLContext ctx = try_context(dpy, debug, why); ctx != EGL_NO_CONTEXT) {
                        display_ = dpy;
                        context_ = ctx;
                        info_ = query_device("EGL device");
                        return;
                    }
                }
                tried += " EGL device " + std::to_string(i) + ": " + why + ";";
            }
        } else {
            tried += " EGL device: none enumerated;";
        }
    }
    if (forced.empty() || forced == "surfaceless") {
        EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        std::string why = "no display";
        if (dpy != EGL_NO_DISPLAY) {
            if (EGLContext ctx = try_context(dpy, debug, why); ctx != EGL_NO_CONTEXT) {
                display_ = dpy;
                context_ = ctx;
                info_ = query_device("EGL surfaceless");
                return;
            }
        }
        tried += " EGL surfaceless: " + why + ";";
    }
    if (tried.empty()) tried = " RANRYU_EGL_PLATFORM=" + forced + " names no platform (device, surfaceless);";
    tried.pop_back();
    throw Error("no headless OpenGL 4.3 core context:" + tried);
}

HeadlessContext::~HeadlessContext() {
    if (display_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_) eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
}

}  // namespace ranryu::gl
