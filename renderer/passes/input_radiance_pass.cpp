#include "renderer/passes/input_radiance_pass.h"

#include "renderer/passes/probe_update_pass.h"

#include <algorithm>

namespace deepgi {

void InputRadiancePass::declare(const PipelineConfig&, std::vector<TextureDecl>& out) const {
    out.push_back({"Input Radiance", {"Input Radiance 1", "Input Radiance 2"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D_ARRAY,
                   SizeRule::Screen, 6, MemoryGroup::Radiosity, Visualize::Radiance,
                   "Outgoing radiance of both layers (what the gather collects); layer 2 is the blur's scratch afterwards, as in the seed"});
}

void InputRadiancePass::execute(FrameContext& ctx) {
    const GLuint radiance = ctx.textures.id("Input Radiance");
    std::vector<std::string> defines;
    if (ctx.config.probes) defines.push_back("DEEPGI_PROBES");
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "input_radiance.frag", "", defines});
    if (ctx.config.probes) bindProbeVolume(ctx);
    ctx.setLightUniforms(prog);
    setUniform(prog, "uHasEmission", ctx.config.emission ? 1 : 0);
    setUniform(prog, "uFeedback", ctx.config.indirect && ctx.historyValid ? 1 : 0);
    setUniform(prog, "uDamping", ctx.settings.damping);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(7, ctx.textures.id("Albedo"));
    glBindTextureUnit(8, ctx.textures.id("Normal"));
    glBindTextureUnit(9, ctx.config.emission ? ctx.textures.id("Emission") : 0);
    glBindTextureUnit(10, ctx.config.indirect ? ctx.textures.id("Reprojected Radiance") : 0);
    const int layers = ctx.config.layer2 ? 2 : 1;  // no layer-2 work when layer 2 is off
    for (int layer = 0; layer < layers; ++layer) {
        setUniform(prog, "uLayer", layer);
        GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, radiance, 0, layer}}, "input radiance");
        ctx.drawFullscreen(prog, fbo, ctx.width, ctx.height);
    }
    if (!ctx.config.indirect) return;

    // Mip chains for the gather. Reading level k-1 while writing level k of the same texture: restrict the
    // sampled range to level k-1 (base = max = k-1) so there is no feedback loop.
    const GLuint depth = ctx.textures.id("Depth"), normal = ctx.textures.id("Normal");
    const int levels = std::min({ctx.textures.entry("Depth").decl.levels, ctx.textures.entry("Normal").decl.levels,
                                 ctx.textures.entry("Input Radiance").decl.levels});
    GLuint mipProg = ctx.shaders.get({"fullscreen.vert", "", "gather_mips.frag", "", {}});
    setUniform(mipProg, "uSrcLevel", 0);
    glBindTextureUnit(4, depth);
    glBindTextureUnit(8, normal);
    glBindTextureUnit(11, radiance);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    for (int level = 1; level < levels; ++level) {
        for (GLuint t : {depth, normal, radiance}) {
            glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, level - 1);
            glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, level - 1);
        }
        const int w = std::max(1, ctx.width >> level), h = std::max(1, ctx.height >> level);
        for (int layer = 0; layer < layers; ++layer) {
            setUniform(mipProg, "uLayer", layer);
            GLuint fbo = ctx.fbos.get({{GL_DEPTH_ATTACHMENT, depth, level, layer},
                                       {GL_COLOR_ATTACHMENT0, normal, level, layer},
                                       {GL_COLOR_ATTACHMENT1, radiance, level, layer}}, "gather mips");
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, w, h);
            glUseProgram(mipProg);
            glBindVertexArray(ctx.fullscreenVao);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
    }
    for (GLuint t : {depth, normal, radiance}) {
        glTextureParameteri(t, GL_TEXTURE_BASE_LEVEL, 0);
        glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, levels - 1);
    }
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

}  // namespace deepgi
