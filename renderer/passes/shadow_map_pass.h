#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Depth maps for the lights that need them: one 2D layer per directional/spot light, a cube per point light.
// Re-rendered only when the lights or the scene change or the maps are allocated anew (static scenes).
class ShadowMapPass final : public RenderPass {
public:
    const char* name() const override { return "Shadow maps"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.shadowMapLayers + c.shadowCubeLayers > 0; }
    void execute(FrameContext& ctx) override;
    uint64_t renders() const { return renders_; }  // frames that drew the maps

private:
    struct Program : gl::Program {
        Program(GLuint id, std::string name) : gl::Program(id, std::move(name)) { externalSampler("uBaseTex"); externalSampler("uEmissiveTex"); }
        gl::Uniform<glm::mat4> lightViewProj{*this, "uLightViewProj"};
        gl::OptionalUniform<glm::vec3> lightPos{*this, "uLightPos"};     // CUBE variant only
        gl::OptionalUniform<float> shadowFar{*this, "uShadowFar"};       // CUBE variant only
    };
    gl::ProgramSlot<Program> program_;
    uint64_t renderedKey_ = 0;
    uint64_t renderedTextures_ = 0;  // FrameContext::writtenTexturesKey() of the maps drawn
    uint64_t renders_ = 0;
};

}  // namespace deepgi
