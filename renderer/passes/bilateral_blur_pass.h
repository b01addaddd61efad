#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Separable bilateral blur of Output Radiance: horizontal into Input Radiance 2 (scratch, as in the seed),
// vertical back into Output Radiance.
class BilateralBlurPass final : public RenderPass {
public:
    const char* name() const override { return "Bilateral blur"; }
    std::vector<std::string> reads() const override { return {"Depth", "Normal", "Output Radiance"}; }
    std::vector<std::string> writes() const override { return {"Input Radiance 2", "Output Radiance"}; }
    bool enabled(const PipelineConfig& c) const override { return c.indirect && c.blur; }
    void execute(FrameContext& ctx) override;

private:
    gl::TextureHandle scratchView_;  // 2D view of Input Radiance layer 2, level 0 (aliases memory, allocates none)
    GLuint viewOf_ = 0;
    uint64_t viewGeneration_ = 0;
};

// Gaussian weights kernel[0..radius] of G3D's blur for radius 1..6.
std::vector<float> blurKernel(int radius);

// A 2D texture view of layer 2 / level 0 of Input Radiance, re-created when the registry changes.
GLuint scratchView(FrameContext& ctx, gl::TextureHandle& view, GLuint& viewOf, uint64_t& generation);

}  // namespace deepgi
