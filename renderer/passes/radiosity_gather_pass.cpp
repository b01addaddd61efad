#include "renderer/passes/radiosity_gather_pass.h"

#include "renderer/passes/probe_update_pass.h"

#include <algorithm>

namespace deepgi {

int spiralTurns(int n) {
    static const int kTurns[100] = {1,  1,  1,  2,  3,  2,  5,  2,  3,  2,  3,  3,  5,  5,  3,  4,  7,  5,  5,  7,
                                    9,  8,  5,  5,  7,  7,  7,  8,  5,  8,  11, 12, 7,  10, 13, 8,  11, 8,  7,  14,
                                    11, 11, 13, 12, 13, 19, 17, 13, 11, 18, 19, 11, 11, 14, 17, 21, 15, 16, 17, 18,
                                    13, 17, 11, 17, 19, 18, 25, 18, 19, 19, 29, 21, 19, 27, 31, 29, 21, 18, 17, 29,
                                    31, 31, 23, 18, 25, 26, 25, 23, 19, 34, 19, 27, 21, 25, 39, 29, 17, 21, 27, 29};
    return (n >= 0 && n < 100) ? kTurns[n] : 5779;
}

void RadiosityGatherPass::declare(const PipelineConfig&, std::vector<TextureDecl>& out) const {
    out.push_back({"Output Radiance", {"Output Radiance"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, SizeRule::Screen, 1,
                   MemoryGroup::Radiosity, Visualize::Radiance,
                   "Indirect irradiance at layer 1: raw gather, then blurred and temporally blended in place"});
    out.push_back({"Gather Coverage", {"Gather Coverage"}, GL_R8, GL_TEXTURE_2D, SizeRule::Screen, 1, MemoryGroup::Extra,
                   Visualize::Color,
                   "Share of the cosine-weighted hemisphere the screen's visible surfaces covered in the gather (1 = all light "
                   "came from the screen; the rest has to come from elsewhere)"});
}

void RadiosityGatherPass::execute(FrameContext& ctx) {
    const Settings& s = ctx.settings;
    // Layer 2 off: a variant without the layer-2 code (llvmpipe runs a branch on a uniform anyway).
    std::vector<std::string> defines;
    if (!ctx.config.layer2) defines.push_back("DEEPGI_SINGLE_LAYER");
    if (ctx.config.probes) defines.push_back("DEEPGI_PROBES");
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "radiosity_gather.frag", "", defines});
    const int levels = ctx.textures.entry("Input Radiance").decl.levels;
    setUniform(prog, "uNumSamples", s.numSamples);
    setUniform(prog, "uSpiralTurns", float(spiralTurns(s.numSamples)));
    setUniform(prog, "uRadius", s.radius);
    setUniform(prog, "uMaxMip", std::max(0, std::min(5, levels - 1)));
    setUniform(prog, "uMinMip", std::min(s.minMip, std::max(0, std::min(5, levels - 1))));
    setUniform(prog, "uLogMaxOffset", s.logMaxOffset);
    setUniform(prog, "uTapNormalTest", s.tapNormalTest ? 1 : 0);
    setUniform(prog, "uUseLayer2", ctx.config.layer2 ? 1 : 0);
    setUniform(prog, "uTime", s.varyTaps ? ctx.time : 0.0f);
    setUniform(prog, "uThickness", s.minSeparation);
    setUniform(prog, "uVisibilitySteps", s.visibilitySteps);
    if (ctx.config.probes) bindProbeVolume(ctx);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(8, ctx.textures.id("Normal"));
    glBindTextureUnit(11, ctx.textures.id("Input Radiance"));
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.textures.id("Output Radiance")},
                               {GL_COLOR_ATTACHMENT1, ctx.textures.id("Gather Coverage")}}, "output radiance");
    ctx.drawFullscreen(prog, fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
