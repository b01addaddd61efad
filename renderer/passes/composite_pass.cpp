#include "renderer/passes/composite_pass.h"

#include "renderer/passes/environment_pass.h"

#include <cmath>

namespace deepgi {

void CompositePass::table(const PipelineConfig& c, PassTable& t) const {
    t.read("Depth", "uDepth").level(Levels::Base);
    t.read("Albedo", "uAlbedo");
    t.read("Normal", "uNormal").level(Levels::Base);
    t.read("Emission", "uEmission").optional(!c.emission);
    t.read("Occlusion", "uOcclusion").optional(!c.occlusion);  // the occlusion texture darkens indirect light only
    t.read("Input Radiance", "uRadiance").level(Levels::Base).optional(!c.seedComposite);  // seed formula only
    t.read("Output Radiance", "uIndirect").optional(!c.indirect);
    t.read("Radiosity Geometry", "uGeometry").optional(!c.indirect || c.radiosityDownsample == 1);  // the upsample
    t.read("Direct Radiance", "uDirect");  // evaluated once, by the input radiance pass
    readEnvironmentMap(c, t);                // the backdrop
    t.write({"Final Radiance", {"Final Radiance"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra,
             Visualize::Radiance, "Linear radiance of the final image (what final.exr holds)"});
    t.write({"Final Display", {"Final Display"}, GL_RGBA8, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra,
             Visualize::Display, "Exposed, tone-mapped, sRGB-encoded final image (what final.png holds)"});
}

std::vector<std::string> CompositePass::materialDefines(const PipelineConfig& c) {
    std::vector<std::string> d;
    if (c.occlusion) d.push_back("OCCLUSION");
    return d;
}

void CompositePass::execute(FrameContext& ctx) {
    const CompositeSettings& s = ctx.settings;
    std::vector<std::string> defines = materialDefines(ctx.config);
    if (ctx.config.environmentMap) defines.push_back("DEEPGI_ENVIRONMENT_MAP");
    // Direct light only: a variant without the upsample (llvmpipe ran it under the uniform test, 2/3 of the pass).
    if (!ctx.config.indirect) defines.push_back("DEEPGI_NO_INDIRECT");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "composite.frag", "", defines});
    prog.environment.set(environmentUniform(ctx));
    prog.hasEmission.set(ctx.config.emission);
    prog.seedMode.set(ctx.config.seedComposite);
    prog.exposure.set(std::exp2(s.exposure));
    prog.tonemap.set(int(s.tonemap));
    ctx.bindSamplers(prog);
    GLuint fbo = ctx.fbos.get({{GL_COLOR_ATTACHMENT0, ctx.texture("Final Radiance")},
                               {GL_COLOR_ATTACHMENT1, ctx.texture("Final Display")}}, "final");
    ctx.drawFullscreen(prog.id(), fbo, ctx.width, ctx.height);
}

}  // namespace deepgi
