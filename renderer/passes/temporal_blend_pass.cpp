#include "renderer/passes/temporal_blend_pass.h"

#include "renderer/passes/bilateral_blur_pass.h"
#include "renderer/passes/reproject_radiance_pass.h"

namespace deepgi {

void TemporalBlendPass::execute(FrameContext& ctx) {
    const GLuint scratch = scratchView(ctx, scratchView_, viewOf_, viewGeneration_);
    const GLuint output = ctx.textures.id("Output Radiance");
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "temporal_blend.frag", "", {}});
    setReprojectionUniforms(ctx, prog);
    setUniform(prog, "uAlpha", ctx.settings.hysteresis);
    glBindTextureUnit(12, output);
    glBindTextureUnit(10, ctx.textures.id("Reprojected Radiance"));
    ctx.drawFullscreen(prog, ctx.fbos.get({{GL_COLOR_ATTACHMENT0, scratch}}, "blur scratch"), ctx.width, ctx.height);
    glCopyImageSubData(scratch, GL_TEXTURE_2D, 0, 0, 0, 0, output, GL_TEXTURE_2D, 0, 0, 0, 0, ctx.width, ctx.height, 1);
    if (ctx.config.temporalFirst)
        glCopyImageSubData(scratch, GL_TEXTURE_2D, 0, 0, 0, 0, ctx.textures.id("Temporal History"), GL_TEXTURE_2D, 0, 0,
                           0, 0, ctx.width, ctx.height, 1);
}

}  // namespace deepgi
