#include "renderer/passes/pass.h"

#include "renderer/core/util.h"

#include "renderer/scene/lighting.h"

#include <algorithm>
#include <stdexcept>

namespace deepgi {

bool PipelineConfig::operator==(const PipelineConfig& o) const {
    return layer2 == o.layer2 && emission == o.emission && indirect == o.indirect && seedComposite == o.seedComposite &&
           blur == o.blur && temporal == o.temporal && temporalFirst == o.temporalFirst && depthPeel == o.depthPeel && ao == o.ao &&
           probes == o.probes && probeDirectionalFill == o.probeDirectionalFill && std::equal(probeIrradianceSize, probeIrradianceSize + 2, o.probeIrradianceSize) &&
           std::equal(probeDepthSize, probeDepthSize + 2, o.probeDepthSize) && std::equal(probeDataSize, probeDataSize + 2, o.probeDataSize) &&
           std::equal(probeRadianceSize, probeRadianceSize + 2, o.probeRadianceSize) &&
           shadowMapLayers == o.shadowMapLayers && shadowCubeLayers == o.shadowCubeLayers &&
           radiosityDownsample == o.radiosityDownsample && gatherInterleave == o.gatherInterleave && tapLevel == o.tapLevel && specular == o.specular && occlusion == o.occlusion &&
           normalMaps == o.normalMaps && objectIds == o.objectIds && objectMotion == o.objectMotion &&
           sky == o.sky && environmentMap == o.environmentMap &&
           std::equal(environmentMapSize, environmentMapSize + 2, o.environmentMapSize);
}

const char* accessName(Access a) {
    switch (a) {
    case Access::Read: return "reads";
    case Access::History: return "reads last frame's";
    case Access::Write: return "writes";
    case Access::Update: return "updates";
    case Access::Scratch: return "scratch";
    }
    return "?";
}

Channel& PassTable::add(const std::string& texture, Access a, const std::string& sampler) {
    Channel c;
    c.texture = texture;
    c.access = a;
    c.sampler = sampler;
    channels_.push_back(std::move(c));
    return channels_.back();
}

Channel& PassTable::write(const TextureDecl& decl, const std::string& sampler) {
    Channel& c = add(decl.name, Access::Write, sampler);
    c.decl = decl;
    return c;
}

Channel& PassTable::scratch(const TextureDecl& decl, const std::string& sampler) {
    Channel& c = add(decl.name, Access::Scratch, sampler);
    c.decl = decl;
    c.decl->group = MemoryGroup::Scratch;
    return c;
}

bool PassTable::uses(const std::string& texture) const {
    return std::any_of(channels_.begin(), channels_.end(), [&](const Channel& c) { return c.texture == texture; });
}

void readShadowMaps(PassTable& t) {
    t.read("Shadow Maps", "uShadowMaps").optional();
    t.read("Shadow Cubes", "uShadowCubes").optional();
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
        // Fragment output location k writes colour attachment k; locations without an attachment write nothing.
        if (a.point >= GL_COLOR_ATTACHMENT0 && a.point <= GL_COLOR_ATTACHMENT15) {
            const size_t k = size_t(a.point - GL_COLOR_ATTACHMENT0);
            if (draws.size() <= k) draws.resize(k + 1, GL_NONE);
            draws[k] = a.point;
        }
    }
    if (draws.empty()) glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    else glNamedFramebufferDrawBuffers(fbo.id(), GLsizei(draws.size()), draws.data());
    gl::checkFramebuffer(fbo.id(), label);
    GLuint id = fbo.id();
    fbos_.emplace(std::move(key), std::move(fbo));
    return id;
}

static std::string passName(const FrameContext& ctx);

GLuint FrameContext::texture(const std::string& name) const { return entry(name).texture.id(); }

const TextureRegistry::Entry& FrameContext::entry(const std::string& name) const {
    if (table && !table->uses(name))
        throw std::runtime_error("pass '" + passName(*this) + "' uses texture '" + name +
                                 "', which its table does not declare (add it to " + passName(*this) + "::table)");
    return textures.entry(name);
}

uint64_t FrameContext::writtenTexturesKey() const {
    uint64_t key = kFnvOffset;
    if (table)
        for (const Channel& c : table->channels())
            if (c.access == Access::Write) {
                const uint64_t serial = textures.entry(c.texture).serial;
                key = fnv1a(key, &serial, sizeof(serial));
            }
    return key;
}

void FrameContext::bindSamplers(const gl::Program& program,
                                std::initializer_list<std::pair<const char*, const char*>> overrides) const {
    std::optional<gl::LenientProgramChecks> lenient;
    if (program.reloaded()) lenient.emplace();
    for (const std::string& sampler : program.activeSamplers()) {
        const char* texture = nullptr;
        for (const auto& [s, t] : overrides)
            if (sampler == s) texture = t;
        const TextureBinding* found = nullptr;
        if (bindings)
            for (const auto& b : *bindings)
                if (texture ? b.texture == texture : b.sampler == sampler) { found = &b; break; }
        if (!found) {
            gl::programMistake("pass '" + passName(*this) + "': program '" + program.name() + "' samples '" + sampler +
                               (texture ? "' from '" + std::string(texture) + "', which has no sampler entry in the pass's table"
                                        : "', which the pass's table does not declare (an undeclared read)"));
            continue;
        }
        program.setSampler(sampler, found->unit);
    }
}

static std::string passName(const FrameContext& ctx) { return ctx.pass ? ctx.pass->name() : "?"; }

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

void FrameContext::drawFullscreenDepthTested(GLuint program, GLuint fbo, int w, int h, GLenum depthFunc,
                                             bool depthWrite, float depth) const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depthFunc);
    glDepthMask(depthWrite ? GL_TRUE : GL_FALSE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program);
    glBindVertexArray(fullscreenVao);
    glDepthRange(depth, depth);  // the triangle's z is 0: it lands on `depth` whatever the range
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthRange(0.0, 1.0);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

int FrameContext::radiosityWidth() const {
    int w = 0, h = 0;
    config.radiositySize().resolve(width, height, 0, w, h);
    return w;
}

int FrameContext::radiosityHeight() const {
    int w = 0, h = 0;
    config.radiositySize().resolve(width, height, 0, w, h);
    return h;
}

void addLightingDefines(const FrameContext& ctx, std::vector<std::string>& defines) {
    // Both branches of lightAt() run on llvmpipe: the storage buffer only when some light is not in the block (the
    // input radiance pass 0.89 x with the sun alone).
    if (ctx.lightCount <= kBlockLights) defines.push_back("DEEPGI_BLOCK_LIGHTS_ONLY");
    // A few lights: a light loop of compile-time length, unrolled to constant indices (lighting.glsl says why).
    if (ctx.lightCount <= kUnrolledLights) {
        defines.push_back("DEEPGI_LIGHT_COUNT " + std::to_string(ctx.lightCount));
        // And their types, so that each light runs its own type's code only (llvmpipe runs both sides of a test of
        // a uniform type: the sun's 2D shadow lookup and a cube one; composite 0.94 x in CPU time on the atrium).
        if (ctx.lightTypes && int(ctx.lightTypes->size()) >= ctx.lightCount) {
            std::string types;
            for (int i = 0; i < kUnrolledLights; ++i)
                types += (i ? ", " : "") + std::to_string(i < ctx.lightCount ? (*ctx.lightTypes)[size_t(i)] : 0);
            defines.push_back("DEEPGI_LIGHT_TYPES " + types);
        }
    }
}

void LightingUniforms::set(const FrameContext& ctx) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, ctx.lightBuffer);
    glBindBufferRange(GL_UNIFORM_BUFFER, 3, ctx.lightBuffer, 0, GLsizeiptr(kBlockLights * kGpuLightBytes));
    count.set(ctx.lightCount);
    const LightSettings& light = ctx.settings;
    shadowBias.set(light.shadowBias);
}

}  // namespace deepgi
