#pragma once
#include "renderer/passes/pass.h"

#include <array>
#include <cstdint>

namespace deepgi {

// The outgoing radiance of both layers that the gather collects (direct light + emission, plus last frame's indirect
// light on layer 1: one more bounce per frame), then the mip chains of depth, normal and radiance. The gather reads
// them only from its finest tap level L (radiosity.min_mip) up, whose texels are point samples of level 0
// (sourcePixel): both layers' radiance is evaluated at that level, for those samples alone, and that level's depth and
// normal are taken straight from level 0 (layer 2's drawn there where the G-buffer drew it there); the finer levels
// are not built. Layer 1's direct light at full resolution is the composite's (Direct Radiance).
class InputRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Input radiance"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;
    // What the gather reads, or the seed composite (layer 1's level 0); the direct light alone is the composite's.
    bool enabled(const PipelineConfig& c) const override { return c.indirect || c.seedComposite; }

private:
    void clearUnbuiltLevels(const FrameContext& ctx, GLuint radiance, GLuint depth, GLuint normal, int coarse,
                            bool layer1Coarse, int layers);
    std::array<uint64_t, 4> clearedKey_{};
    struct RadianceProgram : gl::Program {
        using gl::Program::Program;
        LightingUniforms lighting{*this};
        gl::Uniform<int> layer{*this, "uLayer"};
        gl::Uniform<bool> hasEmission{*this, "uHasEmission"};
        gl::OptionalUniform<float> damping{*this, "uDamping"};  // unused without indirect light
        gl::Uniform<int> sourceLevel{*this, "uSourceLevel"};
        gl::Uniform<int> gbufferLevel{*this, "uGBufferLevel"};
    };
    struct MipProgram : gl::Program {
        using gl::Program::Program;
        gl::Uniform<int> layer{*this, "uLayer"};
        gl::Uniform<int> srcLevel{*this, "uSrcLevel"};
    };
    struct MipFromBaseProgram : MipProgram {  // MIP_FROM_BASE
        using MipProgram::MipProgram;
        gl::Uniform<int> level{*this, "uLevel"};
    };
    gl::ProgramSlot<RadianceProgram> radiance_;
    gl::ProgramSlot<MipProgram> mips_;
    gl::ProgramSlot<MipFromBaseProgram> mipsFromBase_;
};

}  // namespace deepgi
