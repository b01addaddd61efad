#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Last frame's indirect irradiance reprojected into this frame (Reprojected Radiance); disoccluded pixels get 0.
class ReprojectRadiancePass final : public RenderPass {
public:
    const char* name() const override { return "Reproject radiance"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;

private:
    struct Program;
    gl::ProgramSlot<Program> program_;
};

// Uniforms of reprojection.glsl, shared by the reprojection, the temporal blend and the interleaved gather; U =
// gl::OptionalUniform for a program whose variants without reprojection (the gather without interleave) lack them.
template <template <class> class U>
struct BasicReprojectionUniforms {
    explicit BasicReprojectionUniforms(gl::Program& p)
        : falloffStart(p, "uFalloffStart"), falloffEnd(p, "uFalloffEnd"), historyValid(p, "uHistoryValid") {}
    void set(const FrameContext& ctx) const {
        const TemporalSettings& s = ctx.settings;
        falloffStart.set(s.falloffStart);
        falloffEnd.set(s.falloffEnd);
        historyValid.set(ctx.historyValid);
    }
    U<float> falloffStart, falloffEnd;
    U<bool> historyValid;
};
using ReprojectionUniforms = BasicReprojectionUniforms<gl::Uniform>;
using OptionalReprojectionUniforms = BasicReprojectionUniforms<gl::OptionalUniform>;
// The textures reprojection.glsl samples: this frame's layer-1 depth and last frame's (Last Depth).
void readReprojectionInputs(const PipelineConfig& c, PassTable& t);
// Its shader defines: OBJECT_MOTION where the Motion texture exists (else the camera's motion alone).
std::vector<std::string> reprojectionDefines(const PipelineConfig& c);

struct ReprojectRadiancePass::Program : gl::Program {
    using gl::Program::Program;
    ReprojectionUniforms reprojection{*this};
};

}  // namespace deepgi
