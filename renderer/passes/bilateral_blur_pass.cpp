#include "renderer/passes/bilateral_blur_pass.h"

#include "renderer/passes/temporal_blend_pass.h"

#include <algorithm>

namespace deepgi {

std::vector<float> blurKernel(int radius) {
    switch (std::clamp(radius, 1, kMaxBlurTaps)) {
    case 1: return {0.5f, 0.25f};
    case 2: return {0.153170f, 0.144893f, 0.122649f};
    case 3: return {0.153170f, 0.144893f, 0.122649f, 0.092902f};
    case 4: return {0.153170f, 0.144893f, 0.122649f, 0.092902f, 0.062970f};
    case 5: return {0.111220f, 0.107798f, 0.098151f, 0.083953f, 0.067458f, 0.050920f};
    default: return {0.111220f, 0.107798f, 0.098151f, 0.083953f, 0.067458f, 0.050920f, 0.036108f};
    }
}

int blurTaps(int radius, int radiosityDownsample) {
    const int d = std::max(1, radiosityDownsample);
    return std::clamp((radius + d - 1) / d, 1, kMaxBlurTaps);
}

void BilateralBlurPass::table(const PipelineConfig& c, PassTable& t) const {
    t.read("Radiosity Geometry", "uGeometry");
    t.update("Output Radiance", "uSource").after(c.temporalFirst && c.temporal ? "Temporal blend" : "Radiosity gather");
    t.scratch(radiosityScratch(c), "uSource");  // the vertical step reads the horizontal result
}

void BilateralBlurPass::execute(FrameContext& ctx) {
    const BlurSettings& b = ctx.settings;
    const RadiositySettings& r = ctx.settings;
    const GLuint scratch = ctx.texture("Radiosity Scratch"), output = ctx.texture("Output Radiance");
    Program& prog = program_.get(ctx.shaders, {"fullscreen.vert", "", "bilateral_blur.frag", "", {}});
    const int taps = blurTaps(b.blurRadius, ctx.config.radiosityDownsample);
    std::vector<float> kernel = blurKernel(taps);
    kernel.resize(kMaxBlurTaps + 1, 0.0f);
    prog.kernel.set(kernel.data());
    prog.radius.set(taps);
    prog.step.set(std::max(1, b.blurStep));
    prog.edgeSharpness.set(b.edgeSharpness);
    prog.monotonic.set(b.monotonicWeights);
    const float eps = 0.025f * r.radius;  // "same surface" distance, relative to the gather radius
    prog.planeEpsilon2.set(eps * eps);
    // Horizontal: Output -> scratch; vertical: scratch -> Output.
    prog.axis.set(glm::ivec2(1, 0));
    ctx.bindSamplers(prog, {{"uSource", "Output Radiance"}});
    ctx.drawFullscreen(prog.id(), ctx.fbos.get({{GL_COLOR_ATTACHMENT0, scratch}}, "radiosity scratch"), ctx.radiosityWidth(), ctx.radiosityHeight());
    prog.axis.set(glm::ivec2(0, 1));
    ctx.bindSamplers(prog, {{"uSource", "Radiosity Scratch"}});
    ctx.drawFullscreen(prog.id(), ctx.fbos.get({{GL_COLOR_ATTACHMENT0, output}}, "output radiance"), ctx.radiosityWidth(), ctx.radiosityHeight());
}

}  // namespace deepgi
