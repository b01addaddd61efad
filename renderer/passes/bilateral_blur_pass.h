#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Separable bilateral blur of Output Radiance: horizontal into the radiosity scratch, vertical back into Output
// Radiance.
class BilateralBlurPass final : public RenderPass {
public:
    const char* name() const override { return "Bilateral blur"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect && c.blur; }
    void execute(FrameContext& ctx) override;

private:
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::UniformFloatArray<7> kernel{*this, "uKernel"};
        gl::Uniform<int> radius{*this, "uRadius"};
        gl::Uniform<int> step{*this, "uStep"};
        gl::Uniform<float> edgeSharpness{*this, "uEdgeSharpness"};
        gl::Uniform<bool> monotonic{*this, "uMonotonic"};
        gl::Uniform<float> planeEpsilon2{*this, "uPlaneEpsilon2"};
        gl::Uniform<glm::ivec2> axis{*this, "uAxis"};
    };
    gl::ProgramSlot<Program> program_;
};

// Most taps on each side of the centre: the shader's MAX_BLUR_RADIUS (ShaderLoops.BoundsCoverTheSettingsRanges).
inline constexpr int kMaxBlurTaps = 6;

// Gaussian weights kernel[0..radius] of G3D's blur for radius 1..kMaxBlurTaps.
std::vector<float> blurKernel(int radius);

// Taps on each side at the radiosity resolution: blur.radius counts full-resolution pixels, so a grid of
// 1/downsample takes ceil(radius / downsample) taps of its own pixels (half: 5 -> 3) and keeps about the same
// footprint on screen; the radius's taps at half resolution spread twice as far and flatten the indirect light's
// peaks (hidden_emitter's ceiling by the crease, docs/BENCHMARKS.md sessions 23-24) for 1.35 x the blur's time.
int blurTaps(int radius, int radiosityDownsample);

}  // namespace deepgi
