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
    // Number of geometry passes in the last execute (1 predicted, 2 peeled; one more with the layer-2 depth prepass).
    int lastGeometryPasses() const { return geometryPasses_; }

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
    };
    void writeMaterialTextures(const PipelineConfig& c, PassTable& t) const;
    // How a draw treats layer 2: tested and shaded at once (discard), or its depth prepass, or its shading after it.
    enum class Layer2Draw { Whole, DepthPrepass, ShadeEqual };
    void drawScene(FrameContext& ctx, int firstLayer, int layerCount, bool peel, const char* peelDepth,
                   Layer2Draw layer2 = Layer2Draw::Whole);
    void drawLayer2(FrameContext& ctx, bool peel, const char* peelDepth);
    gl::ProgramSlot<Program> program_;
    int geometryPasses_ = 0;
};

}  // namespace deepgi
