#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// E = w * E_reprojected + (1 - w) * E_output, w = alpha * rejection(world distance). Written to the scratch
// (Input Radiance 2) and copied back into Output Radiance (and the history in temporal_first order).
class TemporalBlendPass final : public RenderPass {
public:
    const char* name() const override { return "Temporal blend"; }
    std::vector<std::string> reads() const override { return {"Depth", "Last Depth", "Output Radiance", "Reprojected Radiance"}; }
    std::vector<std::string> writes() const override { return {"Input Radiance 2", "Output Radiance", "Temporal History"}; }
    bool enabled(const PipelineConfig& c) const override { return c.indirect && c.temporal; }
    void execute(FrameContext& ctx) override;

private:
    gl::TextureHandle scratchView_;
    GLuint viewOf_ = 0;
    uint64_t viewGeneration_ = 0;
};

}  // namespace deepgi
