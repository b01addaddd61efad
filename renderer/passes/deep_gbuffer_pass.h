#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The 2-layer deep G-buffer with minimum separation, in one geometry pass: layer 1 of the previous frame
// (Last Depth, copied before the draw) predicts this frame's layer 1 for the layer-2 separation test.
// depth_peel mode (and any frame without history) renders layer 1 first and peels exactly against it.
class DeepGBufferPass final : public RenderPass {
public:
    const char* name() const override { return "Deep G-buffer"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    void execute(FrameContext& ctx) override;
    // Number of geometry passes in the last execute (1 predicted, 2 peeled or layer 2 alone; one more with the layer-2
    // depth prepass at level 0).
    int lastGeometryPasses() const { return geometryPasses_; }
    // The level of the G-buffer's textures layer 2 is drawn at this frame: the gather's finest tap level L where layer
    // 2 is drawn alone (the layer-2 prepass, depth peeling, a frame without history), since nothing reads it finer;
    // 0 where one draw fills both layers. Its finer levels then hold the clear values (far, 0).
    static int layer2Level(const FrameContext& ctx);
    int lastLayer2Level() const { return layer2Level_; }

private:
    struct Program : gl::Program {
        Program(GLuint id, std::string name) : gl::Program(id, std::move(name)) {
            for (const char* s : {"uBaseTex", "uEmissiveTex", "uMetalRoughTex", "uNormalTex", "uOcclusionTex"}) externalSampler(s);
        }
        gl::Uniform<int> firstLayer{*this, "uFirstLayer"};
        gl::Uniform<int> layerCount{*this, "uLayerCount"};
        gl::OptionalUniform<float> minSeparation{*this, "uMinSeparation"};  // not in LAYER1_ONLY
        gl::OptionalUniform<bool> peel{*this, "uPeel"};
        gl::OptionalUniform<bool> diffuseOnly{*this, "uDiffuseOnly"};  // not in LAYER2_PREPASS
        gl::Uniform<glm::vec4> clipMap{*this, "uClipMap"};
        gl::OptionalUniform<int> drawLevel{*this, "uDrawLevel"};  // only where layer 2's separation test is compiled in
    };
    void writeMaterialTextures(const PipelineConfig& c, PassTable& t) const;
    // How a draw treats layer 2: tested and shaded at once (discard), or its depth prepass, or its shading after it.
    enum class Layer2Draw { Whole, DepthPrepass, ShadeEqual };
    void drawScene(FrameContext& ctx, int firstLayer, int layerCount, bool peel, const char* peelDepth,
                   Layer2Draw layer2 = Layer2Draw::Whole);
    int drawLayer2(FrameContext& ctx, bool peel, const char* peelDepth);  // returns its geometry passes
    // The framebuffer of every target at one level (all layers), cleared.
    GLuint bindTargets(FrameContext& ctx, int level);
    void clearUnusedLevels(const FrameContext& ctx);
    gl::ProgramSlot<Program> program_;
    int geometryPasses_ = 0;
    int layer2Level_ = 0;
    glm::vec4 clipMap_{1.0f, 1.0f, 0.0f, 0.0f};  // for the draws being issued
    int drawLevel_ = 0;
    uint64_t clearedGeneration_ = ~uint64_t(0);  // the levels between 0 and L of the targets, cleared once
};

}  // namespace deepgi
