#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Two-layer ambient occlusion (AlchemyAO estimator, technique.md 1.10) with the radiosity gather's spiral taps,
// tap count, radius and mip levels, the max over the two layers per tap. An optional output (ao.enabled): the
// composite does not use it; it exists to be viewed and to time "GI vs an AO pass with the same taps".
class AmbientOcclusionPass final : public RenderPass {
public:
    const char* name() const override { return "Ambient occlusion"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.ao; }
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
        gl::Uniform<bool> useLayer2{*this, "uUseLayer2"};
        gl::Uniform<float> time{*this, "uTime"};
        gl::Uniform<float> bias{*this, "uBias"};
        gl::Uniform<float> intensity{*this, "uIntensity"};
    };
    gl::ProgramSlot<Program> program_;
};

}  // namespace deepgi
