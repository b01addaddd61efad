#include "renderer/passes/ambient_occlusion_pass.h"

#include "renderer/passes/radiosity_gather_pass.h"

#include <algorithm>

namespace deepgi {

void AmbientOcclusionPass::table(const PipelineConfig& c, PassTable& t) const {
    // The depth mips are built by the input-radiance pass only when indirect light is on; otherwise level 0.
    const Levels levels = c.indirect ? Levels::All : Levels::Base;
    t.read("Depth", "uDepth").level(levels);
    t.read("Normal", "uNormal").level(levels);
    if (c.ao)
        t.write({"Ambient Occlusion", {"Ambient Occlusion"}, GL_R8, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra,
                 Visualize::Color, "Two-layer ambient occlusion at layer 1 (1 = unoccluded); only with ao.enabled"});
}

void AmbientOcclusionPass::execute(FrameContext& ctx) {
    const RadiositySettings& r = ctx.settings;  // the gather's taps, radius and mips
    const AOSettings& ao = ctx.settings;
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "ambient_occlusion.frag", "", {}});
    const int levels = ctx.config.indirect ? ctx.entry("Depth").decl.levels : 1;
    const int maxMip = std::max(0, std::min(5, levels - 1));
    prog.numSamples.set(r.numSamples);
    prog.spiralTurns.set(float(spiralTurns(r.numSamples)));
    prog.radius.set(r.radius);
    prog.maxMip.set(maxMip);
    prog.minMip.set(std::min(ctx.config.tapLevel, maxMip));  // the gather's finest tap level (0 without indirect light)
    prog.logMaxOffset.set(r.logMaxOffset);
    prog.useLayer2.set(ctx.config.layer2);
    prog.time.set(r.varyTaps ? ctx.time : 0.0f);
    prog.bias.set(ao.aoBias);
    prog.intensity.set(ao.aoIntensity);
    ctx.bindSamplers(prog);
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.texture("Ambient Occlusion")}}, "ambient occlusion");
    ctx.drawFullscreen(prog.id(), fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
