#include "renderer/passes/input_radiance_pass.h"

#include "renderer/passes/probe_update_pass.h"
#include "renderer/scene/lighting.h"

#include <algorithm>

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
    t.read("Specular", "uSpecular").optional(!c.specular);     // layer 1's direct specular joins Direct Radiance
    t.read("Occlusion", "uOcclusion").optional(!c.occlusion);  // scales the indirect feedback
    t.read("Reprojected Radiance", "uReprojected").optional(!c.indirect);  // the multi-bounce feedback
    readShadowMaps(t);
    if (c.sky) readProbeSky(t);  // the sky's light (and the probe volume)
    else if (c.probes) readProbeVolume(t);  // layer 2's indirect light, and layer 1's before there is a history
    if (c.indirect || c.seedComposite)
        t.write({"Input Radiance", {"Input Radiance 1", "Input Radiance 2"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D_ARRAY,
                 SizeRule::screen(), 6, MemoryGroup::Radiosity, Visualize::Radiance,
                 "Outgoing radiance of both layers (what the gather collects); layer 2 from the gather's finest tap "
                 "level (radiosity.min_mip) up, its finer levels 0"},
                "uRadiance");
    // Half floats: the direct light keeps 11 bits of precision (R11G11B10's 6 would put 1.5 % steps in it); as
    // outgoing radiance it is bounded by the same clamp as the final image (an irradiance could pass 65504).
    t.write({"Direct Radiance", {"Direct Radiance"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1,
             MemoryGroup::Extra, Visualize::Radiance,
             "Outgoing direct radiance of layer 1 (albedo / pi x the shadowed direct irradiance from every light, plus "
             "the GGX specular of Specular), evaluated once; the composite adds emission and indirect light"});
}

void InputRadiancePass::execute(FrameContext& ctx) {
    const RadiositySettings& s = ctx.settings;
    const bool radianceOut = ctx.config.indirect || ctx.config.seedComposite;
    const GLuint radiance = radianceOut ? ctx.texture("Input Radiance") : 0, direct = ctx.texture("Direct Radiance");
    std::vector<std::string> defines;
    if (ctx.config.probes) defines.push_back("DEEPGI_PROBES");
    if (ctx.config.specular) defines.push_back("SPECULAR");
    if (ctx.config.occlusion) defines.push_back("OCCLUSION");
    if (ctx.config.sky) defines.push_back("DEEPGI_SKY");
    // Both branches of lightAt() run on llvmpipe (0.89 x of the pass with the sun alone when the buffer's is dropped).
    if (ctx.lightCount <= kBlockLights) defines.push_back("DEEPGI_BLOCK_LIGHTS_ONLY");
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
    // No layer-2 work when layer 2 is off, nor without indirect light (layer 1's direct light only). Layer 2 goes
    // straight to the gather's finest level (none finer is read: the seed composite reads layer 1 alone).
    const int layers = radianceOut && ctx.config.layer2 ? 2 : 1;
    const int radianceLevels = radianceOut ? ctx.entry("Input Radiance").decl.levels : 1;
    const int layer2Level = ctx.config.indirect ? std::clamp(s.minMip, 0, std::min(5, radianceLevels - 1)) : 0;
    if (layers == 2)
        for (int level = 0; level < layer2Level; ++level)  // never read: a defined 0 for the inspector and dumps
            glClearTexSubImage(radiance, level, 0, 0, 1, std::max(1, ctx.width >> level), std::max(1, ctx.height >> level), 1,
                               GL_RGB, GL_FLOAT, nullptr);
    for (int layer = 0; layer < layers; ++layer) {
        const int level = layer == 1 ? layer2Level : 0;
        RadianceProgram& prog = program(layer);
        prog.layer.set(layer);
        prog.sourceLevel.set(level);
        GLuint fbo = !radianceOut ? ctx.fbos.get({{GL_COLOR_ATTACHMENT1, direct}}, "direct irradiance")
                     : layer == 0 ? ctx.fbos.get({{GL_COLOR_ATTACHMENT0, radiance, 0, layer}, {GL_COLOR_ATTACHMENT1, direct}}, "input radiance 1")
                                  : ctx.fbos.get({{GL_COLOR_ATTACHMENT0, radiance, level, layer}}, "input radiance");
        ctx.drawFullscreen(prog.id(), fbo, std::max(1, ctx.width >> level), std::max(1, ctx.height >> level));
    }
    if (!ctx.config.indirect) return;

    // Mip chains for the gather. Reading level k-1 while writing level k of the same texture: restrict the
    // sampled range to level k-1 (base = max = k-1) so there is no feedback loop.
    const GLuint depth = ctx.texture("Depth"), normal = ctx.texture("Normal");
    const int levels = std::min({ctx.entry("Depth").decl.levels, ctx.entry("Normal").decl.levels,
                                 ctx.entry("Input Radiance").decl.levels});
    MipProgram& mipProg = mips_.get(ctx.shaders, {"fullscreen.vert", "", "gather_mips.frag", "", {}});
    mipProg.srcLevel.set(0);
    ctx.bindSamplers(mipProg);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    for (int level = 1; level < levels; ++level) {
        for (GLuint t : {depth, normal, radiance}) {
            glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, level - 1);
            glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, level - 1);
        }
        const int w = std::max(1, ctx.width >> level), h = std::max(1, ctx.height >> level);
        for (int layer = 0; layer < layers; ++layer) {
            mipProg.layer.set(layer);
            // Layer 2's radiance exists from layer2Level up: the levels up to it are not built from it.
            GLuint fbo = layer == 1 && level <= layer2Level
                             ? ctx.fbos.get({{GL_DEPTH_ATTACHMENT, depth, level, layer}, {GL_COLOR_ATTACHMENT0, normal, level, layer}}, "gather mips")
                             : ctx.fbos.get({{GL_DEPTH_ATTACHMENT, depth, level, layer},
                                             {GL_COLOR_ATTACHMENT0, normal, level, layer},
                                             {GL_COLOR_ATTACHMENT1, radiance, level, layer}}, "gather mips");
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, w, h);
            glUseProgram(mipProg.id());
            glBindVertexArray(ctx.fullscreenVao);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
    for (GLuint t : {depth, normal, radiance}) {
        glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, 0);
        glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, levels - 1);
    }
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

}  // namespace deepgi
