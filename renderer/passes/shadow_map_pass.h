#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Depth maps for the lights that need them: one 2D layer per directional/spot light, a cube per point light.
// Re-rendered only when the lights, the scene or the map size change (static scenes).
class ShadowMapPass final : public RenderPass {
public:
    const char* name() const override { return "Shadow maps"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {}; }
    std::vector<std::string> writes() const override { return {"Shadow Maps", "Shadow Cubes"}; }
    bool enabled(const PipelineConfig& c) const override { return c.shadowMapLayers + c.shadowCubeLayers > 0; }
    void execute(FrameContext& ctx) override;

private:
    uint64_t renderedKey_ = 0;
    uint64_t renderedGeneration_ = 0;
};

}  // namespace deepgi
