#include "renderer/passes/deep_gbuffer_pass.h"

namespace deepgi {

static constexpr int kGatherLevels = 6;  // mip levels 0..5 read by the radiosity gather

// Levels of the textures only the G-buffer writes: level L too where layer 2 may be drawn there.
static int materialLevels(const PipelineConfig& c) { return c.layer2 ? c.tapLevel + 1 : 1; }

void DeepGBufferPass::table(const PipelineConfig& c, PassTable& t) const {
    const int ml = materialLevels(c);
    const Levels written = c.layer2 && c.tapLevel > 0 ? Levels::All : Levels::Base;  // layer 2 at level L
    t.history("Depth").level(Levels::Base);  // layer 1 of last frame, copied into Last Depth before the draw
    t.write({"Depth", {"Depth 1", "Depth 2"}, GL_DEPTH_COMPONENT32, GL_TEXTURE_2D_ARRAY, SizeRule::screen(),
             kGatherLevels, MemoryGroup::GBuffer, Visualize::Depth,
             "Hyperbolic depth of both layers; layer 2 is the nearest surface at least min-separation behind layer 1. "
             "Where layer 2 is drawn alone (software GL's layer-2 prepass, depth peeling), it is drawn at the gather's "
             "finest tap level (radiosity.min_mip: the mip slider), the only level read, as are its other targets; "
             "its finer levels are then empty"})
        .level(written);
    t.write({"Albedo", {"Albedo 1", "Albedo 2"}, GL_RGB8, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), ml,
             MemoryGroup::GBuffer, Visualize::Color,
             "Diffuse albedo of both layers: base colour x texture x (1 - metallic) (the base colour with "
             "material.diffuse_only)"});
    t.write({"Normal", {"Normal 1", "Normal 2"}, GL_RG8_SNORM, GL_TEXTURE_2D_ARRAY, SizeRule::screen(),
             kGatherLevels, MemoryGroup::GBuffer, Visualize::Normal, "World-space shading normal of both layers (normal-mapped), oct16 encoded"})
        .level(written);
    t.write({"Last Depth", {"Last Depth"}, GL_DEPTH_COMPONENT32, GL_TEXTURE_2D, SizeRule::screen(), 1,
             MemoryGroup::GBuffer, Visualize::Depth, "Layer-1 depth of the previous frame (predicts layer 1 for the separation test)"},
            "uLastDepth");
    if (c.emission)
        t.write({"Emission", {"Emission 1", "Emission 2"}, GL_R11F_G11F_B10F, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), materialLevels(c),
                 MemoryGroup::Extra, Visualize::Radiance, "Emitted radiance of both layers (only for scenes with emissive materials)"});
    // Scene editing (issue 14): which node each pixel shows, and how far its surface moved since last frame; only
    // where a client picks, and once objects move (the two targets cost a still frame's G-buffer about a third).
    if (c.objectIds)
        t.write({"Object ID", {"Object ID 1", "Object ID 2"}, GL_R32UI, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), materialLevels(c),
                 MemoryGroup::Extra, Visualize::ObjectId, "Node index + 1 of the surface of each layer (0 = sky): picking"});
    if (c.objectMotion)
        t.write({"Motion", {"Motion 1", "Motion 2"}, GL_RGBA16F, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), materialLevels(c), MemoryGroup::Extra,
                 Visualize::Color, "World-space position change of each layer's surface since last frame (previous - current), in frames where an object moved"});
    writeMaterialTextures(c, t);
    if (c.depthPeel)
        t.write({"Peel Depth", {"Peel Depth"}, GL_DEPTH_COMPONENT32, GL_TEXTURE_2D, SizeRule::screen(), 1,
                 MemoryGroup::Extra, Visualize::Depth, "Copy of this frame's layer-1 depth for exact depth peeling (depth_peel mode only)"},
                "uPeelDepth");
}

// The metallic-roughness model's extras, only for scenes that have them (a Lambertian scene keeps the seed layout).
void DeepGBufferPass::writeMaterialTextures(const PipelineConfig& c, PassTable& t) const {
    if (c.specular)
        t.write({"Specular", {"Specular 1", "Specular 2"}, GL_RGBA8, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), materialLevels(c),
                 MemoryGroup::Extra, Visualize::Color,
                 "GGX specular of both layers: rgb = F0 = mix(0.04, base, metallic), a = perceptual roughness (the "
                 "composite shades layer 1's direct lights with it; 0 = no specular)"});
    if (c.occlusion)
        t.write({"Occlusion", {"Occlusion 1", "Occlusion 2"}, GL_R8, GL_TEXTURE_2D_ARRAY, SizeRule::screen(), materialLevels(c),
                 MemoryGroup::Extra, Visualize::Color,
                 "The occlusion texture (x strength) of both layers: scales indirect light only (1 = none)"});
}

void DeepGBufferPass::drawScene(FrameContext& ctx, int firstLayer, int layerCount, bool peel, const char* peelDepth,
                                Layer2Draw layer2) {
    const GBufferSettings& g = ctx.settings;
    for (bool masked : {false, true}) {
        if (masked ? !ctx.scene.hasMasked() : !ctx.scene.hasOpaque()) continue;
        std::vector<std::string> defs;
        if (masked) defs.push_back("MASKED");
        if (ctx.config.emission) defs.push_back("EMISSION");
        if (ctx.config.specular) defs.push_back("SPECULAR");
        if (ctx.config.occlusion) defs.push_back("OCCLUSION");
        if (ctx.config.normalMaps) defs.push_back("NORMAL_MAPS");
        if (ctx.config.objectIds) defs.push_back("OBJECT_IDS");
        if (ctx.config.objectMotion) defs.push_back("OBJECT_MOTION");
        // Layer 1 alone: no discard in the shader, so llvmpipe tests depth before shading (early z) and shades
        // each pixel's front surface only, not every surface behind it.
        if (firstLayer == 0 && layerCount == 1) defs.push_back("LAYER1_ONLY");
        if (layer2 == Layer2Draw::DepthPrepass) defs.push_back("LAYER2_PREPASS");
        if (layer2 == Layer2Draw::ShadeEqual) defs.push_back("LAYER2_SHADE");
        // gbuffer.layer_routing: instance i of each draw goes to layer firstLayer + i from the vertex stage (no
        // geometry shader: on llvmpipe it cost the heavy scene's pass 1.4 x), or the geometry shader emits it per layer.
        const bool layered = ctx.config.layeredVertex;
        if (layered) defs.push_back("LAYERED");
        ctx.scene.draw([&](unsigned textures) {
            std::vector<std::string> variant = defs;
            for (auto& d : SceneGpu::materialTextureDefines(textures)) variant.push_back(d);
            Program& prog = program_.get(ctx.shaders, {"deep_gbuffer.vert", layered ? "" : "deep_gbuffer.geom", "deep_gbuffer.frag", "", variant});
            glUseProgram(prog.id());
            prog.firstLayer.set(firstLayer);
            prog.layerCount.set(layerCount);
            prog.minSeparation.set(g.minSeparation);
            prog.peel.set(peel);
            prog.diffuseOnly.set(ctx.settings.diffuseOnly);
            prog.clipMap.set(clipMap_);
            prog.drawLevel.set(drawLevel_);
            ctx.bindSamplers(prog, {{"uPeelDepth", peelDepth}});
            return prog.id();
        }, masked, true, layered ? layerCount : 1, true);
    }
}

// Layer 2 alone. With gbuffer.layer2_prepass, its tests (separation, alpha) run in a depth-only draw, and the shading
// draw tests depth EQUAL with no discard: llvmpipe then tests depth before shading and shades one fragment per pixel,
// where a shader that may discard is tested after it, every fragment behind layer 1 shaded.
int DeepGBufferPass::layer2Level(const FrameContext& ctx) {
    const bool alone = ctx.config.layer2 && (ctx.config.layer2Prepass || ctx.config.depthPeel || !ctx.historyValid);
    return alone ? ctx.config.tapLevel : 0;
}

// Layer 2 alone, at level layer2Level(). At level 0 with gbuffer.layer2_prepass, its tests (separation, alpha) run
// in a depth-only draw, and the shading draw tests depth EQUAL with no discard: llvmpipe then tests depth before shading
// and shades one fragment per pixel, where a shader that may discard is tested after it, every fragment behind
// layer 1 shaded. At level L each pixel T is the ray through level-0 pixel T 2^L + tapSampleOffset(L), the sample
// layer 1's level L takes (sourcePixel): the clip map moves and scales the view onto that grid.
int DeepGBufferPass::drawLayer2(FrameContext& ctx, bool peel, const char* peelDepth) {
    const int level = layer2Level(ctx);
    if (level > 0) {
        const int s = 1 << level;
        const int wl = std::max(1, ctx.width >> level), hl = std::max(1, ctx.height >> level);
        const glm::ivec2 c = tapSampleOffset(level);
        const glm::vec2 scale(float(ctx.width) / float(s * wl), float(ctx.height) / float(s * hl));
        clipMap_ = glm::vec4(scale, scale.x - 1.0f + float(s - 1 - 2 * c.x) / float(s * wl),
                             scale.y - 1.0f + float(s - 1 - 2 * c.y) / float(s * hl));
        drawLevel_ = level;
        bindTargets(ctx, level);
    }
    // At level L one draw with the separation test's discard: its few fragments cost less than a second geometry
    // pass (atrium G-buffer 0.95 x).
    int passes = 1;
    if (!ctx.config.layer2Prepass || level > 0) {
        drawScene(ctx, 1, 1, peel, peelDepth);
    } else {
        passes = 2;
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        drawScene(ctx, 1, 1, peel, peelDepth, Layer2Draw::DepthPrepass);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthFunc(GL_EQUAL);
        glDepthMask(GL_FALSE);
        drawScene(ctx, 1, 1, peel, peelDepth, Layer2Draw::ShadeEqual);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
    }
    clipMap_ = glm::vec4(1.0f, 1.0f, 0.0f, 0.0f);
    drawLevel_ = 0;
    return passes;
}

GLuint DeepGBufferPass::bindTargets(FrameContext& ctx, int level) {
    std::vector<FramebufferCache::Attachment> atts = {{GL_DEPTH_ATTACHMENT, ctx.texture("Depth"), level},
                                                      {GL_COLOR_ATTACHMENT0, ctx.texture("Albedo"), level},
                                                      {GL_COLOR_ATTACHMENT1, ctx.texture("Normal"), level}};
    if (ctx.config.emission) atts.push_back({GL_COLOR_ATTACHMENT2, ctx.texture("Emission"), level});
    if (ctx.config.objectIds) atts.push_back({GL_COLOR_ATTACHMENT5, ctx.texture("Object ID"), level});
    if (ctx.config.objectMotion) atts.push_back({GL_COLOR_ATTACHMENT6, ctx.texture("Motion"), level});
    if (ctx.config.specular) atts.push_back({GL_COLOR_ATTACHMENT3, ctx.texture("Specular"), level});
    if (ctx.config.occlusion) atts.push_back({GL_COLOR_ATTACHMENT4, ctx.texture("Occlusion"), level});
    GLuint fbo = ctx.fbos.get(atts, level == 0 ? "deep G-buffer" : "deep G-buffer layer 2");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, std::max(1, ctx.width >> level), std::max(1, ctx.height >> level));
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    if (ctx.config.emission) glClearBufferfv(GL_COLOR, 2, zero);
    const GLuint noObject[4] = {0, 0, 0, 0};
    if (ctx.config.objectIds) glClearBufferuiv(GL_COLOR, 5, noObject);
    if (ctx.config.objectMotion) glClearBufferfv(GL_COLOR, 6, zero);
    if (ctx.config.specular) glClearBufferfv(GL_COLOR, 3, zero);
    const float noOcclusion[4] = {1, 1, 1, 1};
    if (ctx.config.occlusion) glClearBufferfv(GL_COLOR, 4, noOcclusion);
    const float one = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &one);
    return fbo;
}

// The levels between 0 and L of the textures only the G-buffer writes hold nothing it draws: 0 (occlusion 1), once
// per allocation (depth and normal: the input radiance pass's clearUnbuiltLevels).
void DeepGBufferPass::clearUnusedLevels(const FrameContext& ctx) {
    if (clearedGeneration_ == ctx.textures.generation()) return;
    clearedGeneration_ = ctx.textures.generation();
    const float one[4] = {1, 1, 1, 1};
    for (int level = 1; level < materialLevels(ctx.config) - 1; ++level) {
        glClearTexImage(ctx.texture("Albedo"), level, GL_RGB, GL_FLOAT, nullptr);
        if (ctx.config.emission) glClearTexImage(ctx.texture("Emission"), level, GL_RGB, GL_FLOAT, nullptr);
        if (ctx.config.objectIds) glClearTexImage(ctx.texture("Object ID"), level, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        if (ctx.config.objectMotion) glClearTexImage(ctx.texture("Motion"), level, GL_RGBA, GL_FLOAT, nullptr);
        if (ctx.config.specular) glClearTexImage(ctx.texture("Specular"), level, GL_RGBA, GL_FLOAT, nullptr);
        if (ctx.config.occlusion) glClearTexImage(ctx.texture("Occlusion"), level, GL_RED, GL_FLOAT, one);
    }
}

void DeepGBufferPass::execute(FrameContext& ctx) {
    const int w = ctx.width, h = ctx.height;
    const GLuint depth = ctx.texture("Depth"), lastDepth = ctx.texture("Last Depth");
    // Before the draw: this frame's Last Depth is last frame's Depth 1.
    glCopyImageSubData(depth, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, lastDepth, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    clearUnusedLevels(ctx);
    const GLuint fbo = bindTargets(ctx, 0);
    layer2Level_ = layer2Level(ctx);

    const bool peel = ctx.config.depthPeel || !ctx.historyValid;
    if (!ctx.config.layer2) {
        drawScene(ctx, 0, 1, false, "Last Depth");
        geometryPasses_ = 1;
    } else if (!peel && !ctx.config.layer2Prepass) {
        drawScene(ctx, 0, 2, false, "Last Depth");  // one geometry pass, both layers
        geometryPasses_ = 1;
    } else if (!peel) {
        drawScene(ctx, 0, 1, false, "Last Depth");  // layer 1 with early z, then layer 2 predicted as above
        geometryPasses_ = 1 + drawLayer2(ctx, false, "Last Depth");
    } else {
        drawScene(ctx, 0, 1, false, "Last Depth");
        // Exact layer 1 for the peel: a separate copy in depth_peel mode; Last Depth on a history reset (its
        // content is then meaningless anyway, and the reprojection ignores it).
        const char* peelName = ctx.config.depthPeel ? "Peel Depth" : "Last Depth";
        GLuint peelTex = ctx.texture(peelName);
        glCopyImageSubData(depth, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, peelTex, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        geometryPasses_ = 1 + drawLayer2(ctx, true, peelName);
    }
    glDisable(GL_DEPTH_TEST);
}

}  // namespace deepgi
