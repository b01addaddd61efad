#include "renderer/passes/reproject_radiance_pass.h"

namespace deepgi {

void readReprojectionInputs(const PipelineConfig& c, PassTable& t) {
    t.read("Depth", "uDepth").level(Levels::Base);
    t.read("Last Depth", "uLastDepthTex");
    if (c.objectMotion) t.read("Motion", "uMotion");  // each surface's own motion (deep G-buffer pass)
}

std::vector<std::string> reprojectionDefines(const PipelineConfig& c) {
    if (c.objectMotion) return {"OBJECT_MOTION"};
    return {};
}

void ReprojectRadiancePass::table(const PipelineConfig& c, PassTable& t) const {
    readReprojectionInputs(c, t);
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
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "reproject_radiance.frag", "", reprojectionDefines(ctx.config)});
    prog.reprojection.set(ctx);
    ctx.bindSamplers(prog);
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.texture("Reprojected Radiance")},
                               {GL_COLOR_ATTACHMENT1, ctx.texture("History Weight")}}, "reprojected radiance");
    ctx.drawFullscreen(prog.id(), fbo, ctx.radiosityWidth(), ctx.radiosityHeight());
}

}  // namespace deepgi
