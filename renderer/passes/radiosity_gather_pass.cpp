#include "renderer/passes/radiosity_gather_pass.h"

#include "renderer/passes/probe_update_pass.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace deepgi {

int spiralTurns(int n) {
    static const int kTurns[100] = {1,  1,  1,  2,  3,  2,  5,  2,  3,  2,  3,  3,  5,  5,  3,  4,  7,  5,  5,  7,
                                    9,  8,  5,  5,  7,  7,  7,  8,  5,  8,  11, 12, 7,  10, 13, 8,  11, 8,  7,  14,
                                    11, 11, 13, 12, 13, 19, 17, 13, 11, 18, 19, 11, 11, 14, 17, 21, 15, 16, 17, 18,
                                    13, 17, 11, 17, 19, 18, 25, 18, 19, 19, 29, 21, 19, 27, 31, 29, 21, 18, 17, 29,
                                    31, 31, 23, 18, 25, 26, 25, 23, 19, 34, 19, 27, 21, 25, 39, 29, 17, 21, 27, 29};
    if (n >= 0 && n < 100) return kTurns[n];
    if (n <= 0) return 1;
    // Beyond the table: the integer nearest N (2 - golden ratio) that is coprime with N, so consecutive taps are a
    // golden angle apart (Vogel's spiral) and no two taps share a direction (G3D's 5779 lines taps up for N = 578).
    int t = int(std::lround(double(n) * 0.38196601125));
    while (std::gcd(t, n) != 1) ++t;
    return t;
}

void RadiosityGatherPass::table(const PipelineConfig& c, PassTable& t) const {
    t.read("Depth", "uDepth");
    t.read("Normal", "uNormal");
    t.read("Input Radiance", "uRadiance");
    if (c.probes) readProbeVolume(t);  // the part of the hemisphere the screen does not cover
    if (c.probeDirectionalFill) readProbeRadiance(t);  // per sector
    // Gather Select wrote them whole; this pass overwrites the pixels that gather (with the interleaved gather,
    // those where Gather Mask is 0: an early depth test, so the others cost llvmpipe nothing).
    t.update("Output Radiance");
    t.update("Gather Coverage");
    if (c.gatherInterleave > 1) t.read("Gather Mask");
}

void RadiosityGatherPass::execute(FrameContext& ctx) {
    const RadiositySettings& s = ctx.settings;
    // Layer 2 off: a variant without the layer-2 code (llvmpipe runs a branch on a uniform anyway).
    std::vector<std::string> defines;
    if (!ctx.config.layer2) defines.push_back("DEEPGI_SINGLE_LAYER");
    if (ctx.config.probes) defines.push_back("DEEPGI_PROBES");
    if (ctx.config.probeDirectionalFill) defines.push_back("DEEPGI_PROBE_DIRECTIONAL_FILL");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "radiosity_gather.frag", "", defines});
    const int levels = ctx.entry("Input Radiance").decl.levels;
    const int maxMip = std::max(0, std::min(5, levels - 1));
    prog.numSamples.set(s.numSamples);
    prog.spiralTurns.set(float(spiralTurns(s.numSamples)));
    prog.radius.set(s.radius);
    prog.maxMip.set(maxMip);
    prog.minMip.set(std::min(ctx.config.tapLevel, maxMip));  // radiosity.min_mip at this image's height
    prog.logMaxOffset.set(s.logMaxOffset);
    prog.tapNormalTest.set(s.tapNormalTest);
    prog.useLayer2.set(ctx.config.layer2);
    prog.time.set(s.varyTaps ? ctx.time : 0.0f);
    prog.thickness.set(ctx.settings.minSeparation);
    prog.visibilitySteps.set(s.visibilitySteps);
    if (ctx.config.probes) bindProbeUniforms(ctx);
    ctx.bindSamplers(prog);
    const bool masked = ctx.config.gatherInterleave > 1;
    std::vector<FramebufferCache::Attachment> atts = {{GL_COLOR_ATTACHMENT0, ctx.texture("Output Radiance")},
                                                      {GL_COLOR_ATTACHMENT1, ctx.texture("Gather Coverage")}};
    if (masked) atts.push_back({GL_DEPTH_ATTACHMENT, ctx.texture("Gather Mask")});
    const GLuint fbo = ctx.fbos.get(atts, masked ? "output radiance + gather mask" : "output radiance");
    if (!masked) {
        ctx.drawFullscreen(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight());
        return;
    }
    // The full-screen triangle lies at depth 0.5: it passes where the mask holds 0. No depth writes, and the shader
    // neither discards nor writes depth, so the test runs before it.
    ctx.drawFullscreenDepthTested(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight(), GL_GREATER, false);
}

}  // namespace deepgi
