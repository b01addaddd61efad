#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Two-layer ambient occlusion (AlchemyAO estimator, technique.md 1.10) with the radiosity gather's spiral taps,
// tap count, radius and mip levels, the max over the two layers per tap. An optional output (ao.enabled): the
// composite does not use it; it exists to be viewed and to time "GI vs an AO pass with the same taps".
class AmbientOcclusionPass final : public RenderPass {
public:
    const char* name() const override { return "Ambient occlusion"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Normal"}; }
    std::vector<std::string> writes() const override { return {"Ambient Occlusion"}; }
    bool enabled(const PipelineConfig& c) const override { return c.ao; }
    void execute(FrameContext& ctx) override;
};

}  // namespace deepgi
