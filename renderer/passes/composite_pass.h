#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Final image: linear radiance (Final Radiance) and the exposed, sRGB-encoded display image (Final Display).
class CompositePass final : public RenderPass {
public:
    const char* name() const override { return "Composite"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;

private:
    static std::vector<std::string> materialDefines(const PipelineConfig& c);  // OCCLUSION
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::Uniform<bool> hasEmission{*this, "uHasEmission"};
        gl::Uniform<bool> seedMode{*this, "uSeedMode"};
        gl::Uniform<float> exposure{*this, "uExposure"};
        gl::Uniform<int> tonemap{*this, "uTonemap"};
        gl::Uniform<glm::vec4> environment{*this, "uEnvironment"};
    };
    gl::ProgramSlot<Program> program_;
};

}  // namespace deepgi
