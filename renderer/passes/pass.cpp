#include "renderer/passes/pass.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>

namespace deepgi {

bool PipelineConfig::operator==(const PipelineConfig& o) const {
    return layer2 == o.layer2 && emission == o.emission && indirect == o.indirect && seedComposite == o.seedComposite &&
           blur == o.blur && temporal == o.temporal && temporalFirst == o.temporalFirst && depthPeel == o.depthPeel && ao == o.ao &&
           probes == o.probes && std::equal(probeIrradianceSize, probeIrradianceSize + 2, o.probeIrradianceSize) &&
           std::equal(probeDepthSize, probeDepthSize + 2, o.probeDepthSize) && std::equal(probeDataSize, probeDataSize + 2, o.probeDataSize) &&
           shadowMapLayers == o.shadowMapLayers && shadowCubeLayers == o.shadowCubeLayers;
}

GLuint FramebufferCache::get(const std::vector<Attachment>& atts, const std::string& label) {
    std::vector<int64_t> key;
    for (const auto& a : atts) key.insert(key.end(), {int64_t(a.point), int64_t(a.texture), a.level, a.layer});
    auto it = fbos_.find(key);
    if (it != fbos_.end()) return it->second.id();
    auto fbo = gl::createFramebuffer(label);
    std::vector<GLenum> draws;
    for (const auto& a : atts) {
        if (a.layer < 0) glNamedFramebufferTexture(fbo.id(), a.point, a.texture, a.level);
        else glNamedFramebufferTextureLayer(fbo.id(), a.point, a.texture, a.level, a.layer);
        if (a.point >= GL_COLOR_ATTACHMENT0 && a.point <= GL_COLOR_ATTACHMENT15) draws.push_back(a.point);
    }
    if (draws.empty()) glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    else glNamedFramebufferDrawBuffers(fbo.id(), GLsizei(draws.size()), draws.data());
    gl::checkFramebuffer(fbo.id(), label);
    GLuint id = fbo.id();
    fbos_.emplace(std::move(key), std::move(fbo));
    return id;
}

void FrameContext::drawFullscreen(GLuint program, GLuint fbo, int w, int h) const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program);
    glBindVertexArray(fullscreenVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void FrameContext::setLightUniforms(GLuint program) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, lightBuffer);
    setUniform(program, "uLightCount", lightCount);
    setUniform(program, "uShadowBias", settings.shadowBias);
    glBindTextureUnit(14, textures.has("Shadow Maps") ? textures.id("Shadow Maps") : 0);
    glBindTextureUnit(15, textures.has("Shadow Cubes") ? textures.id("Shadow Cubes") : 0);
}

void setUniform(GLuint p, const char* n, int v) { glProgramUniform1i(p, glGetUniformLocation(p, n), v); }
void setUniform(GLuint p, const char* n, float v) { glProgramUniform1f(p, glGetUniformLocation(p, n), v); }
void setUniform(GLuint p, const char* n, const glm::vec2& v) { glProgramUniform2fv(p, glGetUniformLocation(p, n), 1, glm::value_ptr(v)); }
void setUniform(GLuint p, const char* n, const glm::ivec2& v) { glProgramUniform2iv(p, glGetUniformLocation(p, n), 1, glm::value_ptr(v)); }
void setUniform(GLuint p, const char* n, const glm::vec3& v) { glProgramUniform3fv(p, glGetUniformLocation(p, n), 1, glm::value_ptr(v)); }
void setUniform(GLuint p, const char* n, const glm::mat4& v) { glProgramUniformMatrix4fv(p, glGetUniformLocation(p, n), 1, GL_FALSE, glm::value_ptr(v)); }

}  // namespace deepgi
