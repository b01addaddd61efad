#include "renderer/passes/reproject_radiance_pass.h"

namespace deepgi {

void ReprojectRadiancePass::table(const PipelineConfig& c, PassTable& t) const {
    // reprojection.glsl's inputs: this frame's layer-1 depth, last frame's, and each surface's own motion.
    t.read("Depth", "uDepth").level(Levels::Base);
    t.read("Last Depth", "uLastDepthTex");
    if (c.objectMotion) t.read("Motion", "uMotion");
    // Last frame's filtered irradiance: unblurred (temporal_first) or the final Output Radiance.
    t.history(c.temporalFirst ? "Temporal History" : "Output Radiance", "uHistory");
    t.write({"Reprojected Radiance", {"Reprojected Radiance"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, c.radiositySize(), 1,
             MemoryGroup::Radiosity, Visualize::Radiance, "Last frame's indirect irradiance seen from this frame's camera (0 where rejected)"});
    t.write({"History Weight", {"History Weight"}, GL_R16F, GL_TEXTURE_2D, c.radiositySize(), 1, MemoryGroup::Extra,
             Visualize::Color,
             "How far last frame's irradiance is trusted at each radiosity pixel (1 - smoothstep of the world distance "
             "between the reprojected surfaces; 0 = rejected), for the gather's selection and the temporal blend"});
}

void ReprojectRadiancePass::execute(FrameContext& ctx) {
    std::vector<std::string> defines;
    if (ctx.config.objectMotion) defines.push_back("OBJECT_MOTION");  // else the camera's motion alone
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "reproject_radiance.frag", "", defines});
    const TemporalSettings& s = ctx.settings;
    prog.falloffStart.set(s.falloffStart);
    prog.falloffEnd.set(s.falloffEnd);
    prog.historyValid.set(ctx.historyValid);
    ctx.bindSamplers(prog);
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.texture("Reprojected Radiance")},
                               {GL_COLOR_ATTACHMENT1, ctx.texture("History Weight")}}, "reprojected radiance");
    ctx.drawFullscreen(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight());
}

}  // namespace deepgi
