#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Last frame's indirect irradiance reprojected into this frame (Reprojected Radiance); disoccluded pixels get 0.
class ReprojectRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Reproject radiance"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {"Depth", "Last Depth", "Output Radiance", "Temporal History"}; }
    std::vector<std::string> writes() const override { return {"Reprojected Radiance"}; }
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;
};

// Shared by the reprojection and the temporal blend (reprojection.glsl).
void setReprojectionUniforms(FrameContext& ctx, GLuint program);

}  // namespace deepgi
