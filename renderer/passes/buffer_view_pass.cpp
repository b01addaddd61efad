#include "renderer/passes/buffer_view_pass.h"

#include "renderer/passes/pass.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace deepgi {

namespace {

int resolveMode(ViewMode m, Visualize vis) {
    if (m != ViewMode::Auto) return int(m);
    switch (vis) {
        case Visualize::Radiance:
        case Visualize::Color: return int(ViewMode::Radiance);  // linear colour: exposure, then sRGB like radiance
        case Visualize::Depth: return int(ViewMode::Depth);
        case Visualize::Normal: return int(ViewMode::Normal);
        default: return int(ViewMode::Raw);
    }
}

void setUniformAt(GLuint prog, const char* name, int index, int v) {
    const std::string n = std::string(name) + "[" + std::to_string(index) + "]";
    glProgramUniform1i(prog, glGetUniformLocation(prog, n.c_str()), v);
}

}  // namespace

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

int BufferViewPass::channelCount(GLenum format) {
    if (gl::isDepthFormat(format)) return 1;
    switch (format) {
        case GL_R8: case GL_R16F: case GL_R32F: case GL_R8_SNORM: case GL_R16_SNORM: return 1;
        case GL_RG8: case GL_RG8_SNORM: case GL_RG16F: case GL_RG32F: case GL_RG16_SNORM: return 2;
        case GL_RGB8: case GL_R11F_G11F_B10F: case GL_RGB16F: case GL_RGB32F: case GL_SRGB8: return 3;
        default: return 4;
    }
}

BufferViewPass::BufferViewPass() {
    fbo_ = gl::createFramebuffer("buffer view");
    vao_ = gl::createVertexArray("buffer view triangle");
    sampler_ = gl::createSampler("buffer view sampler");
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

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
        glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, out_.id(), 0);
        outW_ = outW;
        outH_ = outH;
    }
    const GLuint prog = shaders.get({"fullscreen.vert", "", "buffer_view.frag", "", {}});
    const bool hasB = b && b->valid();
    const BufferSource* srcs[2] = {&a, hasB ? b : &a};
    for (int i = 0; i < 2; ++i) {
        const BufferSource& s = *srcs[i];
        const bool array = s.target != GL_TEXTURE_2D;
        const GLuint tex = s.valid() ? viewOf(s) : 0;
        glBindTextureUnit(GLuint(i * 2 + 0), array ? 0 : tex);
        glBindTextureUnit(GLuint(i * 2 + 1), array ? tex : 0);
        setUniformAt(prog, "uIsArray", i, array ? 1 : 0);
        setUniformAt(prog, "uLayer", i, s.target == GL_TEXTURE_CUBE_MAP_ARRAY ? s.layer * 6 : s.layer);
        setUniformAt(prog, "uFaces", i, s.target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1);
        setUniformAt(prog, "uLevel", i, s.level);
        setUniformAt(prog, "uMode", i, resolveMode(p.mode, s.vis));
        const glm::ivec2 size(std::max(1, s.width >> s.level), std::max(1, s.height >> s.level));
        glProgramUniform2i(prog, glGetUniformLocation(prog, ("uSize[" + std::to_string(i) + "]").c_str()), size.x, size.y);
    }
    // Depth textures may carry a compare mode (shadow maps): a sampler object without it makes texelFetch defined.
    for (GLuint u = 0; u < 4; ++u) glBindSampler(u, sampler_.id());

    setUniform(prog, "uHasB", hasB ? 1 : 0);
    setUniform(prog, "uChannel", int(p.channel));
    setUniform(prog, "uExposure", std::exp2(p.exposureEV));
    setUniform(prog, "uRange", glm::vec2(p.rangeMin, p.rangeMax));
    setUniform(prog, "uUseRange", p.useRange ? 1 : 0);
    setUniform(prog, "uHighlight", p.highlight ? 1 : 0);
    setUniform(prog, "uOrigin", p.origin);
    setUniform(prog, "uTexelsPerPixel", std::max(p.texelsPerPixel, 1e-6f));
    setUniform(prog, "uGrid", p.grid ? 1 : 0);
    glProgramUniform4f(prog, glGetUniformLocation(prog, "uBackground"), p.background.x, p.background.y, p.background.z,
                       p.background.w);
    setUniform(prog, "uClip", glm::vec2(p.znear, p.zfar));
    setUniform(prog, "uPersp", p.perspective ? 1 : 0);
    setUniform(prog, "uSplitX", p.splitX * float(outW));

    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, outW, outH);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(prog);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (GLuint u = 0; u < 4; ++u) {
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
    b.channels = channelCount(s.format);
    const GLenum fmt = gl::isDepthFormat(s.format) ? GL_DEPTH_COMPONENT
                       : b.channels == 1 ? GL_RED : b.channels == 2 ? GL_RG : b.channels == 3 ? GL_RGB : GL_RGBA;
    b.values.assign(size_t(b.width) * b.height * b.channels, 0.0f);
    const int z = s.target == GL_TEXTURE_2D ? 0 : cube ? s.layer * 6 + face : s.layer;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(s.texture, s.level, cx0 - minX, cy0, z, b.width, b.height, 1, fmt, GL_FLOAT,
                         GLsizei(b.values.size() * sizeof(float)), b.values.data());
    return b;
}

}  // namespace deepgi
