#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Final image: linear radiance (Final Radiance) and the exposed, sRGB-encoded display image (Final Display).
class CompositePass final : public RenderPass {
public:
    const char* name() const override { return "Composite"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Albedo", "Normal", "Emission", "Input Radiance 1", "Output Radiance", "Shadow Maps", "Shadow Cubes"}; }
    std::vector<std::string> writes() const override { return {"Final Radiance", "Final Display"}; }
    void execute(FrameContext& ctx) override;
};

}  // namespace deepgi
