#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The world-space fallback (issue 9): one frame's bounded share of probe rays traced on the CPU with Embree
// (renderer/probes/probe_volume.h), then the changed probe texels uploaded. The gather fills the part of the
// hemisphere the screen did not cover from these probes; layer 2's input radiance takes its indirect light from
// them.
class ProbeUpdatePass final : public RenderPass {
public:
    const char* name() const override { return "Probe update"; }
    void declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const override;
    std::vector<std::string> reads() const override { return {}; }
    std::vector<std::string> writes() const override { return {"Probe Irradiance", "Probe Depth", "Probe Data"}; }
    bool enabled(const PipelineConfig& c) const override { return c.probes; }
    void execute(FrameContext& ctx) override;

private:
    uint64_t uploadedGeneration_ = 0;  // registry generation of the last full upload
    const ProbeVolume* uploadedVolume_ = nullptr;
};

// Binds the probe textures and uniform block where probe_volume.glsl expects them (units 2, 3, 5; block 2).
void bindProbeVolume(const FrameContext& ctx);

}  // namespace deepgi
