#include "renderer/gl/gl.h"

#include <cstring>

#include <cstdio>
#include <stdexcept>

namespace deepgi::gl {

bool currentContextIsSoftware() {
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return r && (std::strstr(r, "llvmpipe") || std::strstr(r, "softpipe"));
}

void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }
void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }
void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }

static void label(GLenum kind, GLuint id, const std::string& text) {
    if (GLAD_GL_KHR_debug || GLAD_GL_VERSION_4_3) glObjectLabel(kind, id, (GLsizei)text.size(), text.c_str());
}

TextureHandle createTexture(GLenum target, const std::string& l) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    label(GL_TEXTURE, id, l);
    return TextureHandle(id);
}
BufferHandle createBuffer(const std::string& l) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    label(GL_BUFFER, id, l);
    return BufferHandle(id);
}
FramebufferHandle createFramebuffer(const std::string& l) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    label(GL_FRAMEBUFFER, id, l);
    return FramebufferHandle(id);
}
VertexArrayHandle createVertexArray(const std::string& l) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    label(GL_VERTEX_ARRAY, id, l);
    return VertexArrayHandle(id);
}
SamplerHandle createSampler(const std::string& l) {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    label(GL_SAMPLER, id, l);
    return SamplerHandle(id);
}

void checkFramebuffer(GLuint fbo, const std::string& what) {
    GLenum st = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (st == GL_FRAMEBUFFER_COMPLETE) return;
    const char* name = "unknown";
    switch (st) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: name = "incomplete attachment"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: name = "missing attachment"; break;
    case GL_FRAMEBUFFER_UNSUPPORTED: name = "unsupported format combination"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: name = "incomplete layer targets"; break;
    }
    throw std::runtime_error("framebuffer '" + what + "' is incomplete: " + name);
}

static void GLAD_API_PTR debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                       const GLchar* message, const void* user) {
    bool verbose = user != nullptr;
    if (!verbose && type != GL_DEBUG_TYPE_ERROR) return;
    std::fprintf(stderr, "deepgi: GL %s: %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "message", message);
}

void installDebugOutput(bool verbose) {
    glEnable(GL_DEBUG_OUTPUT);
    glDebugMessageCallback(debugCallback, verbose ? (const void*)1 : nullptr);
}

int formatBits(GLenum f) {
    switch (f) {
    case GL_DEPTH_COMPONENT32: case GL_DEPTH_COMPONENT32F: case GL_R11F_G11F_B10F: case GL_RGBA8:
    case GL_SRGB8_ALPHA8: case GL_R32F: case GL_R32UI: case GL_RG16F: case GL_RGB10_A2: case GL_RG16_SNORM: return 32;
    case GL_RGB8: return 24;
    case GL_RG8_SNORM: case GL_RG8: case GL_R16F: case GL_DEPTH_COMPONENT16: return 16;
    case GL_R8: return 8;
    case GL_RGBA16F: case GL_RG32F: return 64;
    case GL_RGBA32F: return 128;
    case GL_DEPTH_COMPONENT24: return 24;
    }
    return 0;
}

const char* formatName(GLenum f) {
    switch (f) {
    case GL_DEPTH_COMPONENT32: return "DEPTH_COMPONENT32";
    case GL_DEPTH_COMPONENT32F: return "DEPTH_COMPONENT32F";
    case GL_DEPTH_COMPONENT24: return "DEPTH_COMPONENT24";
    case GL_DEPTH_COMPONENT16: return "DEPTH_COMPONENT16";
    case GL_R11F_G11F_B10F: return "R11F_G11F_B10F";
    case GL_RGBA8: return "RGBA8";
    case GL_SRGB8_ALPHA8: return "SRGB8_ALPHA8";
    case GL_RGB8: return "RGB8";
    case GL_RG8_SNORM: return "RG8_SNORM";
    case GL_RGBA16F: return "RGBA16F";
    case GL_RGBA32F: return "RGBA32F";
    case GL_RG32F: return "RG32F";
    case GL_R32F: return "R32F";
    case GL_R32UI: return "R32UI";
    case GL_R16F: return "R16F";
    case GL_R8: return "R8";
    case GL_RG16F: return "RG16F";
    }
    return "?";
}

bool isDepthFormat(GLenum f) {
    return f == GL_DEPTH_COMPONENT32 || f == GL_DEPTH_COMPONENT32F || f == GL_DEPTH_COMPONENT24 || f == GL_DEPTH_COMPONENT16;
}

int formatChannels(GLenum f) {
    if (isDepthFormat(f)) return 1;
    switch (f) {
        case GL_R8: case GL_R16F: case GL_R32F: case GL_R8_SNORM: case GL_R16_SNORM: case GL_R32UI: return 1;
        case GL_RG8: case GL_RG8_SNORM: case GL_RG16F: case GL_RG32F: case GL_RG16_SNORM: return 2;
        case GL_RGB8: case GL_R11F_G11F_B10F: case GL_RGB16F: case GL_RGB32F: case GL_SRGB8: return 3;
        default: return 4;
    }
}

}  // namespace deepgi::gl
