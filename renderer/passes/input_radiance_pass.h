#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Outgoing radiance of both layers (shadowed direct light + emission, plus last frame's indirect light on
// layer 1: one more bounce per frame), then the rotated-grid mip chains of depth, normal and radiance.
class InputRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Input radiance"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Albedo", "Normal", "Emission", "Reprojected Radiance", "Shadow Maps", "Shadow Cubes"}; }
    std::vector<std::string> writes() const override { return {"Input Radiance", "Depth mips", "Normal mips", "Input Radiance mips"}; }
    bool enabled(const PipelineConfig& c) const override { return c.indirect || c.seedComposite; }
    void execute(FrameContext& ctx) override;
};

}  // namespace deepgi
