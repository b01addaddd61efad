#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The one evaluation of direct light: layer 1's outgoing direct radiance (Direct Radiance, which the composite
// reads), and with indirect light the outgoing radiance of both layers (direct light + emission, plus last frame's
// indirect light on layer 1: one more bounce per frame), then the rotated-grid mip chains of depth, normal and
// radiance. Layer 2's radiance is read by the gather only from its finest tap level (radiosity.min_mip) up, whose
// texels are point samples of level 0 (gather_mips.frag): it is evaluated at that level, for those samples alone.
class InputRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Input radiance"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;

private:
    struct RadianceProgram : gl::Program {
        using gl::Program::Program;
        LightingUniforms lighting{*this};
        gl::Uniform<int> layer{*this, "uLayer"};
        gl::Uniform<bool> hasEmission{*this, "uHasEmission"};
        gl::OptionalUniform<float> damping{*this, "uDamping"};  // unused without indirect light
        gl::Uniform<int> sourceLevel{*this, "uSourceLevel"};
    };
    struct MipProgram : gl::Program {
        using gl::Program::Program;
        gl::Uniform<int> layer{*this, "uLayer"};
        gl::Uniform<int> srcLevel{*this, "uSrcLevel"};
    };
    gl::ProgramSlot<RadianceProgram> radiance_;
    gl::ProgramSlot<MipProgram> mips_;
};

}  // namespace deepgi
