#include "renderer/passes/bilateral_blur_pass.h"

#include <algorithm>

namespace deepgi {

std::vector<float> blurKernel(int radius) {
    switch (std::clamp(radius, 1, 6)) {
    case 1: return {0.5f, 0.25f};
    case 2: return {0.153170f, 0.144893f, 0.122649f};
    case 3: return {0.153170f, 0.144893f, 0.122649f, 0.092902f};
    case 4: return {0.153170f, 0.144893f, 0.122649f, 0.092902f, 0.062970f};
    case 5: return {0.111220f, 0.107798f, 0.098151f, 0.083953f, 0.067458f, 0.050920f};
    default: return {0.111220f, 0.107798f, 0.098151f, 0.083953f, 0.067458f, 0.050920f, 0.036108f};
    }
}

GLuint scratchView(FrameContext& ctx, gl::TextureHandle& view, GLuint& viewOf, uint64_t& generation) {
    const GLuint radiance = ctx.textures.id("Input Radiance");
    if (!view || viewOf != radiance || generation != ctx.textures.generation()) {
        view.reset();
        GLuint id = 0;
        glGenTextures(1, &id);  // a view needs a name that has never been bound
        glTextureView(id, GL_TEXTURE_2D, radiance, GL_R11F_G11F_B10F, 0, 1, 1, 1);
        glObjectLabel(GL_TEXTURE, id, -1, "Input Radiance 2 (scratch view)");
        view = gl::TextureHandle(id);
        viewOf = radiance;
        generation = ctx.textures.generation();
    }
    return view.id();
}

void BilateralBlurPass::execute(FrameContext& ctx) {
    const Settings& s = ctx.settings;
    const GLuint scratch = scratchView(ctx, scratchView_, viewOf_, viewGeneration_);
    const GLuint output = ctx.textures.id("Output Radiance");
    GLuint prog = ctx.shaders.get({"fullscreen.vert", "", "bilateral_blur.frag", "", {}});
    std::vector<float> kernel = blurKernel(s.blurRadius);
    kernel.resize(7, 0.0f);
    glProgramUniform1fv(prog, glGetUniformLocation(prog, "uKernel"), 7, kernel.data());
    setUniform(prog, "uRadius", std::clamp(s.blurRadius, 1, 6));
    setUniform(prog, "uStep", std::max(1, s.blurStep));
    setUniform(prog, "uEdgeSharpness", s.edgeSharpness);
    setUniform(prog, "uMonotonic", s.monotonicWeights ? 1 : 0);
    const float eps = 0.025f * s.radius;  // "same surface" distance, relative to the gather radius
    setUniform(prog, "uPlaneEpsilon2", eps * eps);
    glBindTextureUnit(4, ctx.textures.id("Depth"));
    glBindTextureUnit(8, ctx.textures.id("Normal"));
    // Horizontal: Output -> scratch; vertical: scratch -> Output.
    setUniform(prog, "uAxis", glm::ivec2(1, 0));
    glBindTextureUnit(12, output);
    ctx.drawFullscreen(prog, ctx.fbos.get({{GL_COLOR_ATTACHMENT0, scratch}}, "blur scratch"), ctx.width, ctx.height);
    setUniform(prog, "uAxis", glm::ivec2(0, 1));
    glBindTextureUnit(12, scratch);
    ctx.drawFullscreen(prog, ctx.fbos.get({{GL_COLOR_ATTACHMENT0, output}}, "output radiance"), ctx.width, ctx.height);
}

}  // namespace deepgi
