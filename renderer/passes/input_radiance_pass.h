#pragma once
#include "renderer/passes/pass.h"

#include <array>
#include <cstdint>

namespace deepgi {

// The one evaluation of direct light: layer 1's outgoing direct radiance (Direct Radiance, which the composite
// reads), and with indirect light the outgoing radiance of both layers (direct light + emission, plus last frame's
// indirect light on layer 1: one more bounce per frame), then the rotated-grid mip chains of depth, normal and
// radiance. The gather reads radiance, depth and normal only from its finest tap level (radiosity.min_mip) up, whose
// texels are point samples of level 0 (gather_mips.frag): both layers' radiance is evaluated at that level, for those
// samples alone (layer 1's full-resolution draw writes Direct Radiance only), and that level's depth and normal are
// taken straight from level 0; the finer levels are not built.
class InputRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Input radiance"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;

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
    struct DirectProgram : gl::Program {  // DEEPGI_DIRECT_ONLY: Direct Radiance alone
        using gl::Program::Program;
        LightingUniforms lighting{*this};
        gl::Uniform<int> layer{*this, "uLayer"};
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
    gl::ProgramSlot<DirectProgram> direct_;
    gl::ProgramSlot<MipProgram> mips_;
    gl::ProgramSlot<MipFromBaseProgram> mipsFromBase_;
};

}  // namespace deepgi
