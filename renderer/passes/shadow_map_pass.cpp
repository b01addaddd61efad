#include "renderer/passes/shadow_map_pass.h"

namespace deepgi {

void ShadowMapPass::table(const PipelineConfig& c, PassTable& t) const {
    if (c.shadowMapLayers > 0) {
        TextureDecl d{"Shadow Maps", {}, GL_DEPTH_COMPONENT32F, GL_TEXTURE_2D_ARRAY, SizeRule::shadowMap(), 1,
                      MemoryGroup::Extra, Visualize::ShadowDepth, "Depth from each directional and spot light"};
        for (int i = 0; i < c.shadowMapLayers; ++i) d.layerNames.push_back("Shadow Map " + std::to_string(i + 1));
        t.write(d);
    }
    if (c.shadowCubeLayers > 0) {
        TextureDecl d{"Shadow Cubes", {}, GL_DEPTH_COMPONENT32F, GL_TEXTURE_CUBE_MAP_ARRAY, SizeRule::shadowMap(), 1,
                      MemoryGroup::Extra, Visualize::ShadowDepth, "Distance to each point light / far, 6 faces per light"};
        for (int i = 0; i < c.shadowCubeLayers; ++i) d.layerNames.push_back("Shadow Cube " + std::to_string(i + 1));
        t.write(d);
    }
}

void ShadowMapPass::execute(FrameContext& ctx) {
    // Kept until the lights or the scene change or the maps are allocated anew (a new map size or light count);
    // a new frame size (the viewer's dynamic resolution) keeps them.
    const uint64_t textures = ctx.writtenTexturesKey();
    if (renderedKey_ == ctx.shadowKey && renderedTextures_ == textures) return;
    renderedKey_ = ctx.shadowKey;
    renderedTextures_ = textures;
    ++renders_;
    for (const char* texName : {"Shadow Maps", "Shadow Cubes"}) {
        if (!ctx.table->uses(texName)) continue;
        GLuint t = ctx.texture(texName);
        glTextureParameteri(t, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(t, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    for (const auto& caster : ctx.shadowCasters) {
        const char* texName = caster.cube ? "Shadow Cubes" : "Shadow Maps";
        const auto& e = ctx.entry(texName);
        GLuint fbo = ctx.fbos.get({{GL_DEPTH_ATTACHMENT, e.texture.id(), 0, caster.layer}}, texName);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, e.width, e.height);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        // Both faces cast shadows (the reference's shadow rays are blocked by either side).
        for (bool masked : {false, true}) {
            if (masked ? !ctx.scene.hasMasked() : !ctx.scene.hasOpaque()) continue;
            std::vector<std::string> defs;
            if (masked) defs.push_back("MASKED");
            if (caster.cube) defs.push_back("CUBE");
            ctx.scene.draw([&](unsigned textures) {
                std::vector<std::string> variant = defs;
                if (masked && (textures & SceneGpu::kBaseTex)) variant.push_back("BASE_TEX");  // only the alpha test reads it
                Program& prog = program_.get(ctx.shaders, {"shadow_map.vert", "", "shadow_map.frag", "", variant});
                glUseProgram(prog.id());
                prog.lightViewProj.set(caster.viewProj);
                prog.lightPos.set(caster.position);
                prog.shadowFar.set(caster.far);
                ctx.bindSamplers(prog);
                return prog.id();
            }, masked, false);
        }
    }
}

}  // namespace deepgi
