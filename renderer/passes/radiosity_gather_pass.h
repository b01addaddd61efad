#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Screen-space radiosity: irradiance at layer 1 gathered from both layers' input radiance (Output Radiance).
class RadiosityGatherPass final : public RenderPass {
public:
    const char* name() const override { return "Radiosity gather"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;

private:
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::Uniform<int> numSamples{*this, "uNumSamples"};
        gl::Uniform<float> spiralTurns{*this, "uSpiralTurns"};
        gl::Uniform<float> radius{*this, "uRadius"};
        gl::Uniform<int> maxMip{*this, "uMaxMip"};
        gl::Uniform<int> minMip{*this, "uMinMip"};
        gl::Uniform<int> logMaxOffset{*this, "uLogMaxOffset"};
        gl::Uniform<bool> tapNormalTest{*this, "uTapNormalTest"};
        gl::OptionalUniform<bool> useLayer2{*this, "uUseLayer2"};  // unused by the DEEPGI_SINGLE_LAYER variant
        gl::Uniform<float> time{*this, "uTime"};
        gl::Uniform<float> thickness{*this, "uThickness"};
        gl::Uniform<int> visibilitySteps{*this, "uVisibilitySteps"};
    };
    gl::ProgramSlot<Program> program_;
};

// Discrepancy-minimising number of spiral turns for N taps (G3D's table, technique.md 1.6); beyond it, a golden-angle
// step coprime with N.
int spiralTurns(int numSamples);

}  // namespace deepgi
