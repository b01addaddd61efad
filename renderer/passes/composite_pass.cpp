#include "renderer/passes/composite_pass.h"

#include <cmath>

namespace deepgi {

void CompositePass::declare(const PipelineConfig&, std::vector<TextureDecl>& out) const {
    out.push_back({"Final Radiance", {"Final Radiance"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::Screen, 1, MemoryGroup::Extra,
                   Visualize::Radiance, "Linear radiance of the final image (what final.exr holds)"});
    out.push_back({"Final Display", {"Final Display"}, GL_RGBA8, GL_TEXTURE_2D, SizeRule::Screen, 1, MemoryGroup::Extra,
                   Visualize::Display, "Exposed, tone-mapped, sRGB-encoded final image (what final.png holds)"});
}

void CompositePass::execute(FrameContext& ctx) {
    const Settings& s = ctx.settings;
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "composite.frag", "", {}});
    ctx.setLightUniforms(prog);
    setUniform(prog, "uHasEmission", ctx.config.emission ? 1 : 0);
    setUniform(prog, "uIndirectOn", ctx.config.indirect ? 1 : 0);
    setUniform(prog, "uSeedMode", ctx.config.seedComposite ? 1 : 0);
    setUniform(prog, "uExposure", std::exp2(s.exposure));
    setUniform(prog, "uTonemap", s.tonemap);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(7, ctx.textures.id("Albedo"));
    glBindTextureUnit(8, ctx.textures.id("Normal"));
    glBindTextureUnit(9, ctx.config.emission ? ctx.textures.id("Emission") : 0);
    glBindTextureUnit(11, ctx.textures.id("Input Radiance"));
    glBindTextureUnit(12, ctx.textures.id("Output Radiance"));
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.textures.id("Final Radiance")},
                               {GL_COLOR_ATTACHMENT1, ctx.textures.id("Final Display")}}, "final");
    ctx.drawFullscreen(prog, fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
