#include "renderer/gl/headless_context.h"
#include "renderer/gl/gl.h"

#include <glad/gl.h>  // before osmesa.h: it defines what osmesa.h expects
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

namespace deepgi::gl {

struct HeadlessContext::Impl {
    OSMesaContext ctx = nullptr;
    std::vector<unsigned char> buffer;  // the default framebuffer is unused; all rendering goes to FBOs
};

HeadlessContext::HeadlessContext() : impl_(std::make_unique<Impl>()) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    impl_->ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!impl_->ctx) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    impl_->buffer.resize(4 * 4 * 4);
    if (!OSMesaMakeCurrent(impl_->ctx, impl_->buffer.data(), GL_UNSIGNED_BYTE, 4, 4))
        throw std::runtime_error("OSMesa: cannot make the context current");
    if (!gladLoadGL((GLADloadfunc)OSMesaGetProcAddress))
        throw std::runtime_error("OSMesa: cannot load OpenGL functions");
    if (!GLAD_GL_VERSION_4_5) throw std::runtime_error("OSMesa: OpenGL 4.5 is not available");
}

HeadlessContext::~HeadlessContext() {
    if (impl_->ctx) OSMesaDestroyContext(impl_->ctx);
}

std::string HeadlessContext::renderer() const {
    const GLubyte* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "";
}

bool HeadlessContext::isSoftware() const { return currentContextIsSoftware(); }

}  // namespace deepgi::gl
