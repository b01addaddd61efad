#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// Before the radiosity gather: each radiosity pixel's receiver (Radiosity Geometry) and, with the interleaved gather,
// which pixels gather this frame (Gather Mask, the gather's early depth test) and the reused irradiance of the
// others. It writes Output Radiance and Gather Coverage whole; the gather updates the pixels it gathers.
class GatherSelectPass final : public RenderPass {
public:
    const char* name() const override { return "Gather select"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.indirect; }
    void execute(FrameContext& ctx) override;

private:
    struct Program : gl::Program {
        using gl::Program::Program;
        gl::OptionalUniform<int> interleave{*this, "uInterleave"};  // DEEPGI_INTERLEAVE only
        gl::OptionalUniform<int> interleaveSlot{*this, "uInterleaveSlot"};
    };
    gl::ProgramSlot<Program> program_;
};

// This frame's blocks of the interleaved gather (radiosity.interleave = n > 1) after `frameIndex` frames: 2 = a
// checkerboard alternating; 4 = one corner of every 2x2 blocks, the diagonal ones first (slots 0, 3, 1, 2), so that
// consecutive frames gather far apart.
int interleaveSlot(int n, uint64_t frameIndex);

}  // namespace deepgi
