#include "renderer/passes/ambient_occlusion_pass.h"

#include "renderer/passes/radiosity_gather_pass.h"

#include <algorithm>

namespace deepgi {

void AmbientOcclusionPass::declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const {
    if (!c.ao) return;
    out.push_back({"Ambient Occlusion", {"Ambient Occlusion"}, GL_R8, GL_TEXTURE_2D, SizeRule::Screen, 1, MemoryGroup::Extra,
                   Visualize::Color, "Two-layer ambient occlusion at layer 1 (1 = unoccluded); only with ao.enabled"});
}

void AmbientOcclusionPass::execute(FrameContext& ctx) {
    const Settings& s = ctx.settings;
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "ambient_occlusion.frag", "", {}});
    // The depth mips are built by the input-radiance pass only when indirect light is on; otherwise read level 0.
    const int levels = ctx.config.indirect ? ctx.textures.entry("Depth").decl.levels : 1;
    const int maxMip = std::max(0, std::min(5, levels - 1));
    setUniform(prog, "uNumSamples", s.numSamples);
    setUniform(prog, "uSpiralTurns", float(spiralTurns(s.numSamples)));
    setUniform(prog, "uRadius", s.radius);
    setUniform(prog, "uMaxMip", maxMip);
    setUniform(prog, "uMinMip", std::min(s.minMip, maxMip));
    setUniform(prog, "uLogMaxOffset", s.logMaxOffset);
    setUniform(prog, "uUseLayer2", ctx.config.layer2 ? 1 : 0);
    setUniform(prog, "uTime", s.varyTaps ? ctx.time : 0.0f);
    setUniform(prog, "uBias", s.aoBias);
    setUniform(prog, "uIntensity", s.aoIntensity);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(8, ctx.textures.id("Normal"));
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.textures.id("Ambient Occlusion")}}, "ambient occlusion");
    ctx.drawFullscreen(prog, fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
