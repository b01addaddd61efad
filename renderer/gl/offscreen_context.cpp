#include "renderer/gl/offscreen_context.h"

#include "renderer/gl/gl.h"
#include "renderer/gl/headless_context.h"

#include <glad/gl.h>

#ifdef DEEPGI_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

#include <cstring>
#include <stdexcept>

namespace deepgi::gl {

#ifdef DEEPGI_HAVE_EGL
struct OffscreenContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    ~Egl() {
        if (display == EGL_NO_DISPLAY) return;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
        eglTerminate(display);
    }
};

namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

std::string eglError(const char* step) {
    char b[128];
    std::snprintf(b, sizeof b, "EGL: %s failed (error 0x%04x)", step, unsigned(eglGetError()));
    return b;
}

}  // namespace
#else
struct OffscreenContext::Egl {};
#endif

bool OffscreenContext::eglAvailable() {
#ifdef DEEPGI_HAVE_EGL
    return true;
#else
    return false;
#endif
}

OffscreenContext::OffscreenContext(const std::string& kind) {
    if (kind == "osmesa" || kind.empty()) {
        osmesa_ = std::make_unique<HeadlessContext>();
        description_ = "osmesa";
        return;
    }
    if (kind != "egl") throw std::runtime_error("unknown context '" + kind + "' (choose osmesa or egl)");
#ifndef DEEPGI_HAVE_EGL
    throw std::runtime_error("this build has no EGL (install libegl-dev and re-run cmake)");
#else
    egl_ = std::make_unique<Egl>();
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    std::string how;
    if (getPlatformDisplay && hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
        egl_->display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        how = "surfaceless platform";
        if (egl_->display != EGL_NO_DISPLAY && !eglInitialize(egl_->display, nullptr, nullptr)) egl_->display = EGL_NO_DISPLAY;
    }
    if (egl_->display == EGL_NO_DISPLAY && getPlatformDisplay && hasExtension(clientExt, "EGL_EXT_platform_device")) {
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (queryDevices && queryDevices(8, devices, &count) && count > 0) {
            egl_->display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
            how = "device platform";
            if (egl_->display != EGL_NO_DISPLAY && !eglInitialize(egl_->display, nullptr, nullptr)) egl_->display = EGL_NO_DISPLAY;
        }
    }
    if (egl_->display == EGL_NO_DISPLAY) {
        egl_->display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        how = "default display";
        if (egl_->display == EGL_NO_DISPLAY || !eglInitialize(egl_->display, nullptr, nullptr)) {
            egl_->display = EGL_NO_DISPLAY;
            throw std::runtime_error(eglError("no display could be initialised; eglInitialize"));
        }
    }
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(eglError("eglBindAPI(EGL_OPENGL_API)"));
    const char* dispExt = eglQueryString(egl_->display, EGL_EXTENSIONS);
    const bool surfaceless = hasExtension(dispExt, "EGL_KHR_surfaceless_context");
    const EGLint cfgAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT,
                                 EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n = 0;
    if (!eglChooseConfig(egl_->display, cfgAttribs, &config, 1, &n) || n < 1) throw std::runtime_error(eglError("eglChooseConfig"));
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    egl_->context = eglCreateContext(egl_->display, config, EGL_NO_CONTEXT, ctxAttribs);
    if (egl_->context == EGL_NO_CONTEXT) throw std::runtime_error(eglError("eglCreateContext (OpenGL 4.5 core)"));
    if (!surfaceless) {
        const EGLint pb[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
        egl_->surface = eglCreatePbufferSurface(egl_->display, config, pb);
        if (egl_->surface == EGL_NO_SURFACE) throw std::runtime_error(eglError("eglCreatePbufferSurface"));
    }
    if (!eglMakeCurrent(egl_->display, egl_->surface, egl_->surface, egl_->context)) throw std::runtime_error(eglError("eglMakeCurrent"));
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress))) throw std::runtime_error("EGL: cannot load OpenGL functions");
    if (!GLAD_GL_VERSION_4_5) throw std::runtime_error("EGL: OpenGL 4.5 is not available");
    description_ = "egl (" + how + (surfaceless ? ", no surface)" : ", 16x16 pbuffer)");
#endif
}

OffscreenContext::~OffscreenContext() = default;

std::string OffscreenContext::renderer() const {
    const GLubyte* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "";
}

std::string OffscreenContext::description() const { return description_; }

bool OffscreenContext::isSoftware() const { return currentContextIsSoftware(); }

}  // namespace deepgi::gl
