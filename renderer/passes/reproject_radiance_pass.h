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

// Uniforms of reprojection.glsl, shared by the reprojection and the temporal blend.
struct ReprojectionUniforms {
    explicit ReprojectionUniforms(gl::Program& p)
        : falloffStart(p, "uFalloffStart"), falloffEnd(p, "uFalloffEnd"), historyValid(p, "uHistoryValid") {}
    void set(const FrameContext& ctx) const;
    gl::Uniform<float> falloffStart, falloffEnd;
    gl::Uniform<bool> historyValid;
};
// The same for a program whose variants without reprojection (the gather without interleave) lack them.
struct OptionalReprojectionUniforms {
    explicit OptionalReprojectionUniforms(gl::Program& p)
        : falloffStart(p, "uFalloffStart"), falloffEnd(p, "uFalloffEnd"), historyValid(p, "uHistoryValid") {}
    void set(const FrameContext& ctx) const;
    gl::OptionalUniform<float> falloffStart, falloffEnd;
    gl::OptionalUniform<bool> historyValid;
};
// The textures reprojection.glsl samples: this frame's layer-1 depth and last frame's (Last Depth).
void readReprojectionInputs(const PipelineConfig& c, PassTable& t);
// Its shader defines: OBJECT_MOTION where the Motion texture exists (else the camera's motion alone).
std::vector<std::string> reprojectionDefines(const PipelineConfig& c);

struct ReprojectRadiancePass::Program : gl::Program {
    using gl::Program::Program;
    ReprojectionUniforms reprojection{*this};
};

}  // namespace deepgi
