#include "renderer/passes/gather_select_pass.h"

namespace deepgi {

int interleaveSlot(int n, uint64_t frameIndex) {
    static const int kFourOrder[4] = {0, 3, 1, 2};
    return n == 4 ? kFourOrder[frameIndex % 4] : n == 2 ? int(frameIndex % 2) : 0;
}

void GatherSelectPass::table(const PipelineConfig& c, PassTable& t) const {
    t.read("Depth", "uDepth").level(Levels::Base);
    t.read("Normal", "uNormal").level(Levels::Base);
    if (c.gatherInterleave > 1) {  // the pixels not gathered this frame take the reprojected history
        t.read("History Weight", "uHistoryWeight");
        t.read("Reprojected Radiance", "uReprojected");
        t.write({"Gather Mask", {"Gather Mask"}, GL_DEPTH_COMPONENT16, GL_TEXTURE_2D, c.radiositySize(), 1,
                 MemoryGroup::Extra, Visualize::Color,
                 "Where the interleaved gather runs this frame: 0 = gathers, 1 = reuses the history or is sky (the "
                 "gather's early depth test, so llvmpipe skips the shader on the rest)"});
    }
    t.write({"Output Radiance", {"Output Radiance"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, c.radiositySize(), 1,
             MemoryGroup::Radiosity, Visualize::Radiance,
             "Indirect irradiance at layer 1: raw gather (the probes fill what the screen did not cover; the "
             "interleaved gather's other pixels reuse the history), then blurred and temporally blended in place"});
    t.write({"Gather Coverage", {"Gather Coverage"}, GL_R8, GL_TEXTURE_2D, c.radiositySize(), 1, MemoryGroup::Extra,
             Visualize::Color,
             "Share of the cosine-weighted hemisphere that the screen's visible surfaces covered in the gather (1 = all "
             "light came from the screen; the probes give the rest); 0 on the blocks that reused the history (radiosity.interleave)"});
    // Extra: a cache of what Depth and Normal hold, not part of the paper's radiosity layout.
    t.write({"Radiosity Geometry", {"Radiosity Geometry"}, GL_RGBA32F, GL_TEXTURE_2D, c.radiositySize(), 1,
             MemoryGroup::Extra, Visualize::Color,
             "Each radiosity-grid pixel's receiver: world position (xyz) and its Normal texel's two bytes (w; -1 = "
             "sky), so the blur and the upsample fetch one texel instead of rebuilding it from depth"});
}

void GatherSelectPass::execute(FrameContext& ctx) {
    const int interleave = ctx.config.gatherInterleave;
    std::vector<std::string> defines;
    if (interleave > 1) defines.push_back("DEEPGI_INTERLEAVE");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "gather_select.frag", "", defines});
    if (interleave > 1) {
        prog.interleave.set(interleave);
        prog.interleaveSlot.set(interleaveSlot(interleave, ctx.frameIndex));
    }
    ctx.bindSamplers(prog);
    std::vector<FramebufferCache::Attachment> atts = {{GL_COLOR_ATTACHMENT0, ctx.texture("Output Radiance")},
                                                      {GL_COLOR_ATTACHMENT1, ctx.texture("Gather Coverage")},
                                                      {GL_COLOR_ATTACHMENT2, ctx.texture("Radiosity Geometry")}};
    if (interleave > 1) atts.push_back({GL_DEPTH_ATTACHMENT, ctx.texture("Gather Mask")});
    const GLuint fbo = ctx.fbos.get(atts, interleave > 1 ? "gather select + mask" : "gather select");
    if (interleave > 1)  // every pixel's depth written (gl_FragDepth), whatever was there
        ctx.drawFullscreenDepthTested(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight(), GL_ALWAYS, true);
    else
        ctx.drawFullscreen(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight());
}

}  // namespace deepgi
