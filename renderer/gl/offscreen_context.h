#pragma once
// A headless OpenGL 4.5 core context of a chosen kind, for `deepgi render/bench --context`:
//   "osmesa" (default): OSMesa, llvmpipe (HeadlessContext);
//   "egl": EGL without a window: Mesa's surfaceless platform (EGL_MESA_platform_surfaceless), else the first EGL
//          device (EGL_EXT_platform_device: a GPU driver such as NVIDIA's), else the default display; made current
//          without a surface (EGL_KHR_surfaceless_context) or with a 16x16 pbuffer. Rendering goes to FBOs either way.
#include <memory>
#include <string>

namespace deepgi::gl {

class HeadlessContext;

class OffscreenContext {
public:
    // Throws std::runtime_error naming the step that failed (or "built without EGL").
    explicit OffscreenContext(const std::string& kind = "osmesa");
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;
    std::string renderer() const;  // GL_RENDERER
    bool isSoftware() const;       // llvmpipe/softpipe: GPU timer queries are not trustworthy
    std::string description() const;  // kind and how it was made, e.g. "egl (surfaceless, no surface)"
    static bool eglAvailable();        // built with EGL

private:
    std::unique_ptr<HeadlessContext> osmesa_;
    struct Egl;
    std::unique_ptr<Egl> egl_;
    std::string description_;
};

}  // namespace deepgi::gl
