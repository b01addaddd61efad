#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Screen-space radiosity: irradiance at layer 1 gathered from both layers' input radiance (Output Radiance).
class RadiosityGatherPass final : public RenderPass {
public:
    const char* name() const override { return "Radiosity gather"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Normal", "Input Radiance"}; }
    std::vector<std::string> writes() const override { return {"Output Radiance"}; }
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;
};

// Discrepancy-minimising number of spiral turns for N taps (G3D's table, technique.md 1.6).
int spiralTurns(int numSamples);

}  // namespace deepgi
