#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The 2-layer deep G-buffer with minimum separation, in one geometry pass: layer 1 of the previous frame
// (Last Depth, copied before the draw) predicts this frame's layer 1 for the layer-2 separation test.
// depth_peel mode (and any frame without history) renders layer 1 first and peels exactly against it.
class DeepGBufferPass final : public RenderPass {
public:
    const char* name() const override { return "Deep G-buffer"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Peel Depth"}; }
    std::vector<std::string> writes() const override { return {"Depth", "Albedo", "Normal", "Emission", "Last Depth"}; }
    void execute(FrameContext& ctx) override;
    // Number of geometry passes in the last execute (1 predicted, 2 peeled).
    int lastGeometryPasses() const { return geometryPasses_; }

private:
    void drawScene(FrameContext& ctx, int firstLayer, int layerCount, bool peel, GLuint peelDepth);
    int geometryPasses_ = 0;
};

}  // namespace deepgi
