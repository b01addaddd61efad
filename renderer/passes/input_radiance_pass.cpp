#include "renderer/passes/input_radiance_pass.h"

#include "renderer/passes/deep_gbuffer_pass.h"
#include "renderer/passes/probe_update_pass.h"
#include "renderer/scene/lighting.h"

#include <algorithm>
#include <array>

namespace deepgi {

void InputRadiancePass::table(const PipelineConfig& c, PassTable& t) const {
    // With indirect light the pass also builds the mip levels of Depth and Normal from their level 0.
    if (c.indirect) {
        t.update("Depth", "uDepth").level(Levels::Mips);
        t.update("Normal", "uNormal").level(Levels::Mips);
    } else {
        t.read("Depth", "uDepth").level(Levels::Base);
        t.read("Normal", "uNormal").level(Levels::Base);
    }
    t.read("Albedo", "uAlbedo");
    t.read("Emission", "uEmission").optional(!c.emission);
    t.read("Occlusion", "uOcclusion").optional(!c.occlusion);  // scales the indirect feedback
    t.read("Reprojected Radiance", "uReprojected").optional(!c.indirect);  // the multi-bounce feedback
    readShadowMaps(t);
    if (c.sky) readProbeSky(t);  // the sky's light (and the probe volume)
    else if (c.probes) readProbeVolume(t);  // layer 2's indirect light, and layer 1's before there is a history
    t.write({"Input Radiance", {"Input Radiance 1", "Input Radiance 2"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D_ARRAY,
             SizeRule::screen(), 6, MemoryGroup::Radiosity, Visualize::Radiance,
             "Outgoing radiance of both layers (what the gather collects), from the gather's finest tap level "
             "(radiosity.min_mip) up, the finer levels 0 (layer 1 from level 0 with the seed composite)"},
            "uRadiance");
}

// The levels below the coarse one that nothing writes (radiance of the layers evaluated at the coarse level; depth
// and normal from level 1) hold a defined value for the inspector and the dumps: 0, and the far plane for depth.
// Once per allocation of the textures and layout of the levels: no pass writes them in between.
void InputRadiancePass::clearUnbuiltLevels(const FrameContext& ctx, GLuint radiance, GLuint depth, GLuint normal,
                                           int coarse, bool layer1Coarse, int layers) {
    const std::array<uint64_t, 4> key{ctx.textures.generation(), uint64_t(coarse), uint64_t(layer1Coarse), uint64_t(layers)};
    if (key == clearedKey_) return;
    clearedKey_ = key;
    const float far = 1.0f;
    GLint arrayLayers = 1;  // depth and normal: both layers whether or not layer 2 is drawn
    glGetTextureLevelParameteriv(depth, 0, GL_TEXTURE_DEPTH, &arrayLayers);
    for (int level = 0; level < coarse; ++level) {
        const int w = std::max(1, ctx.width >> level), h = std::max(1, ctx.height >> level);
        const int first = layer1Coarse ? 0 : 1;
        if (layers > first) glClearTexSubImage(radiance, level, 0, 0, first, w, h, layers - first, GL_RGB, GL_FLOAT, nullptr);
        if (level == 0 || !ctx.config.indirect) continue;
        glClearTexSubImage(depth, level, 0, 0, 0, w, h, arrayLayers, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
        glClearTexSubImage(normal, level, 0, 0, 0, w, h, arrayLayers, GL_RG, GL_FLOAT, nullptr);
    }
}

void InputRadiancePass::execute(FrameContext& ctx) {
    const RadiositySettings& s = ctx.settings;
    const GLuint radiance = ctx.texture("Input Radiance");
    std::vector<std::string> defines;
    if (ctx.config.probes) defines.push_back("DEEPGI_PROBES");
    if (ctx.config.occlusion) defines.push_back("OCCLUSION");
    if (ctx.config.sky) defines.push_back("DEEPGI_SKY");
    addLightingDefines(ctx, defines);
    if (ctx.config.probes || ctx.config.sky) bindProbeUniforms(ctx);
    // Layer 1 with a history takes last frame's gathered light, the rest the probes': two variants, since llvmpipe
    // runs both sides of an if (the probe lookup under a uniform test was a fifth of the pass).
    const bool feedback = ctx.config.indirect && ctx.historyValid;
    auto program = [&](int layer) -> RadianceProgram& {
        std::vector<std::string> d = defines;
        if (feedback && layer == 0) d.push_back("DEEPGI_HISTORY_FEEDBACK");
        RadianceProgram& p = radiance_.get(ctx.shaders, {"fullscreen.vert", "", "input_radiance.frag", "", d});
        p.lighting.set(ctx);
        p.hasEmission.set(ctx.config.emission);
        p.damping.set(s.damping);
        ctx.bindSamplers(p);
        return p;
    };
    // No layer-2 work when layer 2 is off. The gather reads radiance from its finest tap level up
    // (radiosity.min_mip, `coarse`): both layers' radiance is evaluated there, layer 1's at level 0 instead when the
    // seed composite reads it. Layer 1's direct light at full resolution is the composite's.
    const int layers = ctx.config.layer2 ? 2 : 1;
    const int coarse = ctx.config.tapLevel;
    const int layer2Level = DeepGBufferPass::layer2Level(ctx);  // coarse, or 0: where the G-buffer drew layer 2
    const bool layer1Coarse = coarse > 0 && !ctx.config.seedComposite;
    const GLuint depth = ctx.texture("Depth"), normal = ctx.texture("Normal");
    clearUnbuiltLevels(ctx, radiance, depth, normal, coarse, layer1Coarse, layers);
    for (int layer = 0; layer < layers; ++layer) {
        const int level = layer == 1 || layer1Coarse ? coarse : 0;
        RadianceProgram& prog = program(layer);
        prog.layer.set(layer);
        prog.sourceLevel.set(level);
        prog.gbufferLevel.set(layer == 1 ? layer2Level : 0);
        ctx.drawFullscreen(prog.id(), ctx.fbos.get({{GL_COLOR_ATTACHMENT0, radiance, level, layer}}, "input radiance"),
                           std::max(1, ctx.width >> level), std::max(1, ctx.height >> level));
    }
    if (!ctx.config.indirect) return;

    // Mip chains for the gather from the coarse level up: that level straight from level 0 (the texel the chain of
    // levels would pick), each coarser one from the one before. Reading level k while writing another level of the
    // same texture: the sampled range is restricted to level k (base = max = k), so there is no feedback loop.
    const int levels = std::min({ctx.entry("Depth").decl.levels, ctx.entry("Normal").decl.levels,
                                 ctx.entry("Input Radiance").decl.levels});
    MipProgram& chainProg = mips_.get(ctx.shaders, {"fullscreen.vert", "", "gather_mips.frag", "", {}});
    MipFromBaseProgram& baseProg = mipsFromBase_.get(ctx.shaders, {"fullscreen.vert", "", "gather_mips.frag", "", {"MIP_FROM_BASE"}});
    for (MipProgram* p : {static_cast<MipProgram*>(&chainProg), static_cast<MipProgram*>(&baseProg)}) {
        p->srcLevel.set(0);
        ctx.bindSamplers(*p);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    for (int level = std::max(1, coarse); level < levels; ++level) {
        const bool fromBase = level == coarse;
        const int src = fromBase ? 0 : level - 1;
        for (GLuint t : {depth, normal, radiance}) {
            glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, src);
            glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, src);
        }
        MipProgram& prog = fromBase ? baseProg : chainProg;  // uSrcLevel 0: a fetch's level counts from the base level
        if (fromBase) baseProg.level.set(level);
        const int w = std::max(1, ctx.width >> level), h = std::max(1, ctx.height >> level);
        for (int layer = 0; layer < layers; ++layer) {
            prog.layer.set(layer);
            // At the coarse level the radiance was evaluated (layer 2; layer 1 unless the seed composite needs its
            // level 0): only depth and normal are built there, and not at all for a layer 2 drawn there.
            if (fromBase && layer == 1 && layer2Level == coarse) continue;
            const bool withRadiance = !fromBase || (layer == 0 && !layer1Coarse);
            GLuint fbo = withRadiance ? ctx.fbos.get({{GL_DEPTH_ATTACHMENT, depth, level, layer},
                                                      {GL_COLOR_ATTACHMENT0, normal, level, layer},
                                                      {GL_COLOR_ATTACHMENT1, radiance, level, layer}}, "gather mips")
                                      : ctx.fbos.get({{GL_DEPTH_ATTACHMENT, depth, level, layer},
                                                      {GL_COLOR_ATTACHMENT0, normal, level, layer}}, "gather mips");
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, w, h);
            glUseProgram(prog.id());
            glBindVertexArray(ctx.fullscreenVao);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
    for (GLuint t : {depth, normal, radiance}) {
        glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, 0);
        glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, levels - 1);
    }
}

}  // namespace deepgi
