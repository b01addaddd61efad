#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Last frame's indirect irradiance reprojected into this frame (Reprojected Radiance); disoccluded pixels get 0. The
// reprojection's weight goes to History Weight, which the gather's selection and the temporal blend read: the test
// runs once per frame.
class ReprojectRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Reproject radiance"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;

private:
    struct Program : gl::Program {  // reprojection.glsl's uniforms
        using gl::Program::Program;
        gl::Uniform<float> falloffStart{*this, "uFalloffStart"}, falloffEnd{*this, "uFalloffEnd"};
        gl::Uniform<bool> historyValid{*this, "uHistoryValid"};
    };
    gl::ProgramSlot<Program> program_;
};

}  // namespace deepgi
