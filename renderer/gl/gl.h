#pragma once
// Move-only RAII owners of GL objects, each with a KHR_debug label (Magnum-style value types).
#include <glad/gl.h>

#include <string>
#include <utility>

namespace deepgi::gl {

// Owns one GL name; Deleter is a function that deletes one object.
template <void (*Deleter)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) { reset(); id_ = std::exchange(o.id_, 0); }
        return *this;
    }
    void reset() { if (id_) Deleter(id_); id_ = 0; }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

private:
    GLuint id_ = 0;
};

// Whether the current context renders in software (llvmpipe, softpipe): its timer queries miss vertex work, it tests
// a discarding shader's depth after shading, and the defaults that depend on the platform follow it.
bool currentContextIsSoftware();

void deleteTexture(GLuint id);
void deleteBuffer(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);
void deleteQuery(GLuint id);
void deleteSampler(GLuint id);

using TextureHandle = Handle<deleteTexture>;
using BufferHandle = Handle<deleteBuffer>;
using FramebufferHandle = Handle<deleteFramebuffer>;
using VertexArrayHandle = Handle<deleteVertexArray>;
using ProgramHandle = Handle<deleteProgram>;
using QueryHandle = Handle<deleteQuery>;
using SamplerHandle = Handle<deleteSampler>;

// Creation helpers (DSA) that label the object for debuggers.
TextureHandle createTexture(GLenum target, const std::string& label);
BufferHandle createBuffer(const std::string& label);
FramebufferHandle createFramebuffer(const std::string& label);
VertexArrayHandle createVertexArray(const std::string& label);
SamplerHandle createSampler(const std::string& label);

// Throws std::runtime_error with the status name if the framebuffer is incomplete.
void checkFramebuffer(GLuint fbo, const std::string& what);

// Installs a KHR_debug callback that prints GL errors (and, if verbose, other messages) to stderr.
void installDebugOutput(bool verbose);

// Bits per texel of a sized internal format (as allocated by the seed layout, not the driver's padding).
int formatBits(GLenum internalFormat);
const char* formatName(GLenum internalFormat);
bool isDepthFormat(GLenum internalFormat);
// Channels a read-back of the format returns (1 for depth).
int formatChannels(GLenum internalFormat);

}  // namespace deepgi::gl
