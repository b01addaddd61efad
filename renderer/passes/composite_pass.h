#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Final image: linear radiance (Final Radiance) and the exposed, sRGB-encoded display image (Final Display), from
// layer 1's direct light, evaluated here (Direct Radiance), emission and the upsampled indirect light.
class CompositePass final : public RenderPass {
public:
    const char* name() const override { return "Composite"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;

private:
    static std::vector<std::string> materialDefines(const PipelineConfig& c);  // OCCLUSION
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::OptionalUniform<bool> hasEmission{*this, "uHasEmission"};  // not in the seed composite
        LightingUniforms lighting{*this};
        gl::Uniform<float> exposure{*this, "uExposure"};
        gl::Uniform<int> tonemap{*this, "uTonemap"};
        gl::OptionalUniform<glm::vec4> environment{*this, "uEnvironment"};  // the backdrop: not in the surfaces' draw
    };
    // The sky's pixels alone (config.compositeSkyDraw): the backdrop, exposed and encoded.
    struct SkyProgram : gl::Program {
        using gl::Program::Program;
        gl::Uniform<float> exposure{*this, "uExposure"};
        gl::Uniform<int> tonemap{*this, "uTonemap"};
        gl::Uniform<glm::vec4> environment{*this, "uEnvironment"};
    };
    gl::ProgramSlot<Program> program_;
    gl::ProgramSlot<SkyProgram> skyProgram_;
};

}  // namespace deepgi
