#pragma once
#include "renderer/passes/pass.h"
#include "renderer/passes/pass.h"

namespace deepgi {

// E = w * E_reprojected + (1 - w) * E_output, w = alpha * History Weight (the rejection by world distance). Written to the radiosity
// scratch and copied back into Output Radiance (and into Temporal History in temporal_first order).
class TemporalBlendPass final : public RenderPass {
public:
    const char* name() const override { return "Temporal blend"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect && c.temporal; }
    void execute(FrameContext& ctx) override;

private:
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::Uniform<float> alpha{*this, "uAlpha"};
    };
    gl::ProgramSlot<Program> program_;
};

// The ping-pong target of the blur and the temporal blend: content never outlives either pass.
TextureDecl radiosityScratch(const PipelineConfig& c);

}  // namespace deepgi
