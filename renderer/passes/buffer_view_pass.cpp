#include "renderer/passes/buffer_view_pass.h"

#include "renderer/gl/program.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace deepgi {

namespace {

constexpr int kObjectIdMode = 5;  // buffer_view.frag: a colour per integer id (Object ID), whatever the mode
constexpr int kUnitUintArray[2] = {4, 5};  // integer (R32UI) arrays: a usampler of their own

int resolveMode(ViewMode m, Visualize vis) {
    if (vis == Visualize::ObjectId) return kObjectIdMode;
    if (m != ViewMode::Auto) return int(m);
    switch (vis) {
        case Visualize::Radiance:
        case Visualize::Color: return int(ViewMode::Radiance);  // linear colour: exposure, then sRGB like radiance
        case Visualize::Depth: return int(ViewMode::Depth);
        case Visualize::Normal: return int(ViewMode::Normal);
        case Visualize::ObjectId: return kObjectIdMode;
        default: return int(ViewMode::Raw);
    }
}

// Normalised and integer formats hold neither NaN, infinities nor negative values.
bool mayHoldNonFinite(GLenum format) {
    switch (format) {
        case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_RGB8: case GL_SRGB8: case GL_RG8: case GL_R8: case GL_RGB10_A2:
        case GL_RGBA16: case GL_RG16: case GL_R16: case GL_DEPTH_COMPONENT16: case GL_DEPTH_COMPONENT24:
        case GL_R32UI: case GL_RG32UI: case GL_RGBA32UI: case GL_R8UI: case GL_R16UI: return false;
        default: return true;
    }
}

std::string at(const char* name, int i) { return std::string(name) + "[" + std::to_string(i) + "]"; }

// Units of the view's own samplers (it is not a pipeline pass, so it has no table): 2D and array view of A, of B.
constexpr int kUnit2D[2] = {0, 2}, kUnitArray[2] = {1, 3};

}  // namespace

struct BufferViewPass::Program : gl::Program {
    struct Source {
        // A variant leaves out what its sampler and mapping do not read (B's, without a split).
        Source(gl::Program& p, int i)
            : layer(p, at("uLayer", i).c_str()), faces(p, at("uFaces", i).c_str()), level(p, at("uLevel", i).c_str()),
              size(p, at("uSize", i).c_str()) {}
        gl::OptionalUniform<int> layer, faces, level;
        gl::OptionalUniform<glm::ivec2> size;
    };
    Program(GLuint id, std::string name) : gl::Program(id, std::move(name)) {
        setSampler("uTex2DA", kUnit2D[0]);
        setSampler("uTexArrA", kUnitArray[0]);
        setSampler("uTex2DB", kUnit2D[1]);
        setSampler("uTexArrB", kUnitArray[1]);
        setSampler("uTexArrUA", kUnitUintArray[0]);
        setSampler("uTexArrUB", kUnitUintArray[1]);
    }
    Source source[2]{{*this, 0}, {*this, 1}};
    gl::OptionalUniform<float> exposure{*this, "uExposure"};      // radiance
    gl::OptionalUniform<glm::vec2> range{*this, "uRange"};        // USE_RANGE
    gl::Uniform<glm::vec2> origin{*this, "uOrigin"};
    gl::Uniform<float> texelsPerPixel{*this, "uTexelsPerPixel"};
    gl::Uniform<glm::vec4> background{*this, "uBackground"};
    gl::OptionalUniform<glm::vec2> clip{*this, "uClip"};         // depth
    gl::OptionalUniform<bool> persp{*this, "uPersp"};
    gl::OptionalUniform<float> splitX{*this, "uSplitX"};         // the split
    gl::OptionalUniform<glm::vec2> cropA{*this, "uCropA"};
};

int BufferSource::levelWidth() const { return std::max(1, width >> level) * (target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1); }
int BufferSource::levelHeight() const { return std::max(1, height >> level); }

BufferSource bufferSource(const TextureRegistry& registry, const std::string& layerName, int level) {
    BufferSource s;
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!registry.findLayer(layerName, &e, &layer) || !e->texture) return s;
    s.texture = e->texture.id();
    s.target = e->decl.target;
    s.format = e->decl.format;
    s.layer = layer;
    s.levels = e->decl.levels;
    s.level = std::clamp(level, 0, e->decl.levels - 1);
    s.width = e->width;
    s.height = e->height;
    s.vis = e->decl.vis;
    return s;
}

BufferViewPass::BufferViewPass() : program_(std::make_unique<gl::ProgramSlot<Program>>()) {
    fbo_ = gl::createFramebuffer("buffer view");
    vao_ = gl::createVertexArray("buffer view triangle");
    sampler_ = gl::createSampler("buffer view sampler");
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

BufferViewPass::~BufferViewPass() = default;

GLuint BufferViewPass::viewOf(const BufferSource& s) {
    if (s.target != GL_TEXTURE_CUBE_MAP_ARRAY) return s.texture;
    if (cubeViewSource_ != s.texture || !cubeView_) {
        // A 2D-array view over every face of the cube array (same storage, no copy).
        GLint layers = 0;
        glGetTextureLevelParameteriv(s.texture, 0, GL_TEXTURE_DEPTH, &layers);
        GLuint id = 0;
        glGenTextures(1, &id);
        glTextureView(id, GL_TEXTURE_2D_ARRAY, s.texture, s.format, 0, std::max(1, s.levels), 0, std::max(layers, 6));
        cubeView_ = gl::TextureHandle(id);
        cubeViewSource_ = s.texture;
    }
    return cubeView_.id();
}

void BufferViewPass::draw(gl::ShaderLibrary& shaders, const BufferSource& a, const BufferSource* b,
                          const BufferViewParams& p, int outW, int outH) {
    if (outW <= 0 || outH <= 0) return;
    if (!out_ || outW != outW_ || outH != outH_) {
        out_ = gl::createTexture(GL_TEXTURE_2D, "buffer view output");
        glTextureStorage2D(out_.id(), 1, GL_RGBA8, outW, outH);
        glTextureParameteri(out_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(out_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        // The viewer magnifies it bilinearly: its edges must not blend with the opposite ones (GL_REPEAT).
        glTextureParameteri(out_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(out_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, out_.id(), 0);
        outW_ = outW;
        outH_ = outH;
    }
    const bool hasB = b && b->valid();
    const BufferSource* srcs[2] = {&a, hasB ? b : &a};
    // The variant: each side's sampler kind and mapping (buffer_view.frag).
    std::vector<std::string> defines;
    for (int i = 0; i < (hasB ? 2 : 1); ++i) {
        const BufferSource& s = *srcs[i];
        const int kind = s.target == GL_TEXTURE_2D ? 0 : s.format == GL_R32UI ? 2 : 1;
        const std::string side = i == 0 ? "A " : "B ";
        defines.push_back("SOURCE_" + side + std::to_string(kind));
        defines.push_back("MODE_" + side + std::to_string(resolveMode(p.mode, s.vis)));
    }
    if (hasB) defines.push_back("HAS_B");
    if (p.channel != ViewChannel::RGB) defines.push_back("CHANNEL " + std::to_string(int(p.channel)));
    if (p.useRange) defines.push_back("USE_RANGE");
    // Only a float texel can be NaN, infinite or negative: the highlight tests nothing in an RGBA8 or integer one.
    if (p.highlight && (mayHoldNonFinite(a.format) || (hasB && mayHoldNonFinite(b->format)))) defines.push_back("HIGHLIGHT");
    if (p.grid && std::max(p.texelsPerPixel, 1e-6f) <= 1.0f / 8.0f) defines.push_back("GRID");
    Program& prog = program_->get(shaders, {"fullscreen.vert", "", "buffer_view.frag", "", defines});
    for (int i = 0; i < 2; ++i) {
        const BufferSource& s = *srcs[i];
        const bool array = s.target != GL_TEXTURE_2D;
        const GLuint tex = s.valid() ? viewOf(s) : 0;
        const bool uintArray = array && s.format == GL_R32UI;
        glBindTextureUnit(GLuint(kUnit2D[i]), array ? 0 : tex);
        glBindTextureUnit(GLuint(kUnitArray[i]), array && !uintArray ? tex : 0);
        glBindTextureUnit(GLuint(kUnitUintArray[i]), uintArray ? tex : 0);
        const Program::Source& u = prog.source[i];
        u.layer.set(s.target == GL_TEXTURE_CUBE_MAP_ARRAY ? s.layer * 6 : s.layer);
        u.faces.set(s.target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1);
        u.level.set(s.level);
        u.size.set(glm::ivec2(std::max(1, s.width >> s.level), std::max(1, s.height >> s.level)));
    }
    // Depth textures may carry a compare mode (shadow maps): a sampler object without it makes texelFetch defined.
    for (GLuint u = 0; u < 6; ++u) glBindSampler(u, sampler_.id());

    prog.exposure.set(std::exp2(p.exposureEV));
    prog.range.set(glm::vec2(p.rangeMin, p.rangeMax));
    prog.origin.set(p.origin);
    prog.texelsPerPixel.set(std::max(p.texelsPerPixel, 1e-6f));
    prog.background.set(p.background);
    prog.clip.set(glm::vec2(p.znear, p.zfar));
    prog.persp.set(p.perspective);
    prog.splitX.set(p.splitX * float(outW));
    prog.cropA.set(p.cropA);

    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, outW, outH);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(prog.id());
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (GLuint u = 0; u < 6; ++u) {
        glBindSampler(u, 0);
        glBindTextureUnit(u, 0);
    }
}

TexelBlock BufferViewPass::readTexels(const BufferSource& s, int x0, int y0, int w, int h) {
    TexelBlock b;
    if (!s.valid()) return b;
    const int faceW = std::max(1, s.width >> s.level), lh = std::max(1, s.height >> s.level);
    const bool cube = s.target == GL_TEXTURE_CUBE_MAP_ARRAY;
    int face = 0, minX = 0, maxX = faceW;
    if (cube) {
        // Stay on the face under the block's centre.
        face = std::clamp((x0 + w / 2) / faceW, 0, 5);
        minX = face * faceW;
        maxX = minX + faceW;
    }
    const int cx0 = std::max(x0, minX), cy0 = std::max(y0, 0);
    const int cx1 = std::min(x0 + w, maxX), cy1 = std::min(y0 + h, lh);
    if (cx1 <= cx0 || cy1 <= cy0) return b;
    b.x0 = cx0;
    b.y0 = cy0;
    b.width = cx1 - cx0;
    b.height = cy1 - cy0;
    b.channels = gl::formatChannels(s.format);
    const GLenum fmt = gl::isDepthFormat(s.format) ? GL_DEPTH_COMPONENT
                       : b.channels == 1 ? GL_RED : b.channels == 2 ? GL_RG : b.channels == 3 ? GL_RGB : GL_RGBA;
    b.values.assign(size_t(b.width) * b.height * b.channels, 0.0f);
    const int z = s.target == GL_TEXTURE_2D ? 0 : cube ? s.layer * 6 + face : s.layer;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (s.format == GL_R32UI) {  // integer ids, shown as their values
        std::vector<uint32_t> ids(b.values.size());
        glGetTextureSubImage(s.texture, s.level, cx0 - minX, cy0, z, b.width, b.height, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                             GLsizei(ids.size() * sizeof(uint32_t)), ids.data());
        for (size_t i = 0; i < ids.size(); ++i) b.values[i] = float(ids[i]);
        return b;
    }
    glGetTextureSubImage(s.texture, s.level, cx0 - minX, cy0, z, b.width, b.height, 1, fmt, GL_FLOAT,
                         GLsizei(b.values.size() * sizeof(float)), b.values.data());
    return b;
}

}  // namespace deepgi
