#include "renderer/passes/composite_pass.h"

#include "renderer/passes/environment_pass.h"
#include "renderer/passes/probe_update_pass.h"
#include "renderer/scene/lighting.h"

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
    // Layer 1's direct light, evaluated here: the lights and their shadow maps, the specular lobe, the sky.
    t.read("Specular", "uSpecular").optional(!c.specular);
    readShadowMaps(t);
    if (c.sky) readProbeSky(t);
    readEnvironmentMap(c, t);                // the backdrop
    t.write({"Final Radiance", {"Final Radiance"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra,
             Visualize::Radiance, "Linear radiance of the final image (what final.exr holds)"});
    t.write({"Final Display", {"Final Display"}, GL_RGBA8, GL_TEXTURE_2D, SizeRule::screen(), 1, MemoryGroup::Extra,
             Visualize::Display, "Exposed, tone-mapped, sRGB-encoded final image (what final.png holds)"});
    // Half floats: the direct light keeps 11 bits of precision; as outgoing radiance it is bounded by the same clamp
    // as the final image (an irradiance could pass 65504).
    t.write({"Direct Radiance", {"Direct Radiance"}, GL_RGBA16F, GL_TEXTURE_2D, SizeRule::screen(), 1,
             MemoryGroup::Extra, Visualize::Radiance,
             "Outgoing direct radiance of layer 1 (albedo / pi x the shadowed direct irradiance from every light and "
             "the sky, plus the GGX specular of Specular), evaluated once at full resolution by the composite, which "
             "adds emission and indirect light to it"});
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
    if (ctx.config.specular) defines.push_back("SPECULAR");
    if (ctx.config.sky) defines.push_back("DEEPGI_SKY");
    if (ctx.config.seedComposite) defines.push_back("DEEPGI_SEED_COMPOSITE");
    addLightingDefines(ctx, defines);
    if (ctx.config.sky) bindProbeUniforms(ctx);
    // Direct light only: a variant without the upsample (llvmpipe ran it under the uniform test, 2/3 of the pass).
    if (!ctx.config.indirect) defines.push_back("DEEPGI_NO_INDIRECT");
    else if (ctx.config.radiosityDownsample == 1) defines.push_back("DEEPGI_RADIOSITY_FULL");  // no upsample
    if (ctx.config.compositeSkyDraw) defines.push_back("DEEPGI_SURFACE_PIXELS");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "composite.frag", "", defines});
    prog.environment.set(environmentUniform(ctx));
    prog.hasEmission.set(ctx.config.emission);
    prog.lighting.set(ctx);
    prog.exposure.set(std::exp2(s.exposure));
    prog.tonemap.set(int(s.tonemap));
    ctx.bindSamplers(prog);
    std::vector<FramebufferCache::Attachment> atts = {{GL_COLOR_ATTACHMENT0, ctx.texture("Final Radiance")},
                                                      {GL_COLOR_ATTACHMENT1, ctx.texture("Final Display")},
                                                      {GL_COLOR_ATTACHMENT2, ctx.texture("Direct Radiance")}};
    if (!ctx.config.compositeSkyDraw) {
        ctx.drawFullscreen(prog.id(), ctx.fbos.get(atts, "final"), ctx.width, ctx.height);
        return;
    }
    // Software GL: layer 1's depth as a read-only depth buffer (no depth writes: the shader's reads of it see what the
    // G-buffer wrote). The triangle at depth 1 passes GREATER on the surfaces, LEQUAL on the sky (cleared to 1), so
    // each draw's shader runs only on its own pixels.
    atts.push_back({GL_DEPTH_ATTACHMENT, ctx.texture("Depth"), 0, 0});
    const GLuint fbo = ctx.fbos.get(atts, "final + layer-1 depth");
    ctx.drawFullscreenDepthTested(prog.id(), fbo, ctx.width, ctx.height, GL_GREATER, false, 1.0f);
    std::vector<std::string> skyDefines;
    if (ctx.config.environmentMap) skyDefines.push_back("DEEPGI_ENVIRONMENT_MAP");
    SkyProgram& sky = skyProgram_.get(ctx.shaders, {"fullscreen.vert", "", "composite_sky.frag", "", skyDefines});
    sky.environment.set(environmentUniform(ctx));
    sky.exposure.set(std::exp2(s.exposure));
    sky.tonemap.set(int(s.tonemap));
    ctx.bindSamplers(sky);
    ctx.drawFullscreenDepthTested(sky.id(), fbo, ctx.width, ctx.height, GL_LEQUAL, false, 1.0f);
}

}  // namespace deepgi
