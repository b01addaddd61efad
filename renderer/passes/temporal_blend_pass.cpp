#include "renderer/passes/temporal_blend_pass.h"

#include <algorithm>

namespace deepgi {

TextureDecl radiosityScratch(const PipelineConfig& c) {
    return {"Radiosity Scratch", {"Radiosity Scratch"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, c.radiositySize(), 1,
            MemoryGroup::Scratch, Visualize::Radiance,
            "Scratch of the blur (horizontal result) and the temporal blend (blended result before the copy back)"};
}

void TemporalBlendPass::table(const PipelineConfig& c, PassTable& t) const {
    t.read("History Weight", "uHistoryWeight");
    t.read("Reprojected Radiance", "uReprojected");
    t.update("Output Radiance", "uCurrent").after(!c.temporalFirst && c.blur ? "Bilateral blur" : "Radiosity gather");
    t.scratch(radiosityScratch(c));
    if (c.temporalFirst)
        t.write({"Temporal History", {"Temporal History"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, c.radiositySize(), 1,
                 MemoryGroup::Extra, Visualize::Radiance, "Temporally filtered, unblurred irradiance (temporal_first order only)"});
}

void TemporalBlendPass::execute(FrameContext& ctx) {
    const TemporalSettings& s = ctx.settings;
    const GLuint scratch = ctx.texture("Radiosity Scratch"), output = ctx.texture("Output Radiance");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "temporal_blend.frag", "", {}});
    // With the interleaved gather about 1 in N of the blurred values is new this frame (the rest is the history
    // itself): the history weight that keeps temporal.alpha's response, 1 - alpha' = N (1 - alpha).
    const int n = ctx.config.gatherInterleave;
    prog.alpha.set(n > 1 ? std::max(0.0f, 1.0f - float(n) * (1.0f - s.hysteresis)) : s.hysteresis);
    ctx.bindSamplers(prog);
    const int w = ctx.radiosityWidth(), h = ctx.radiosityHeight();
    ctx.drawFullscreen(prog.id(), ctx.fbos.get({{GL_COLOR_ATTACHMENT0, scratch}}, "radiosity scratch"), w, h);
    glCopyImageSubData(scratch, GL_TEXTURE_2D, 0, 0, 0, 0, output, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
    if (ctx.config.temporalFirst)
        glCopyImageSubData(scratch, GL_TEXTURE_2D, 0, 0, 0, 0, ctx.texture("Temporal History"), GL_TEXTURE_2D, 0, 0,
                           0, 0, w, h, 1);
}

}  // namespace deepgi
