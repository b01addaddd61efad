#include "renderer/passes/reproject_radiance_pass.h"

namespace deepgi {

void ReprojectRadiancePass::declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const {
    out.push_back({"Reprojected Radiance", {"Reprojected Radiance"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, SizeRule::Screen, 1,
                   MemoryGroup::Radiosity, Visualize::Radiance, "Last frame's indirect irradiance seen from this frame's camera (0 where rejected)"});
    if (c.temporalFirst)
        out.push_back({"Temporal History", {"Temporal History"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D, SizeRule::Screen, 1,
                       MemoryGroup::Extra, Visualize::Radiance, "Temporally filtered, unblurred irradiance (temporal_first order only)"});
}

void setReprojectionUniforms(FrameContext& ctx, GLuint prog) {
    setUniform(prog, "uFalloffStart", ctx.settings.falloffStart);
    setUniform(prog, "uFalloffEnd", ctx.settings.falloffEnd);
    setUniform(prog, "uHistoryValid", ctx.historyValid ? 1 : 0);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(5, ctx.textures.id("Last Depth"));
}

void ReprojectRadiancePass::execute(FrameContext& ctx) {
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "reproject_radiance.frag", "", {}});
    setReprojectionUniforms(ctx, prog);
    const GLuint history = ctx.config.temporalFirst ? ctx.textures.id("Temporal History") : ctx.textures.id("Output Radiance");
    glBindTextureUnit(6, history);
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.textures.id("Reprojected Radiance")}}, "reprojected radiance");
    ctx.drawFullscreen(prog, fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
