#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The world-space fallback (issue 9): one frame's bounded share of probe rays traced on the CPU with Embree
// (renderer/probes/probe_volume.h), then the changed probe texels uploaded. The gather fills the part of the
// hemisphere the screen did not cover from these probes; layer 2's input radiance takes its indirect light from
// them. With probes.overlap the rays start in begin(), on helper threads, while the passes before this one draw;
// execute() traces what is left, joins and uploads.
class ProbeUpdatePass final : public RenderPass {
public:
    const char* name() const override { return "Probe update"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.probes || c.sky; }
    void begin(FrameContext& ctx) override;
    void execute(FrameContext& ctx) override;

private:
    bool update_ = false;              // begin() found the volume not settled: this frame updates it
    bool upload_ = false;              // and this frame uploads (a settled volume's textures are uploaded once)
    bool allTexels_ = false;           // and that the whole atlas goes (new textures or volume)
    uint64_t uploadedTextures_ = 0;    // FrameContext::writtenTexturesKey() of the last full upload
    uint64_t lightKey_ = 0;            // what the probes' light follows: the lights (FrameContext::shadowKey) and the bounce damping
    const ProbeVolume* uploadedVolume_ = nullptr;
};

// The probe textures a pass that includes probe_volume.glsl reads (samplers uProbeIrradiance, uProbeDepth,
// uProbeData), and its uniform block (binding 2) bound for the next draw.
void readProbeVolume(PassTable& t);
// The probes' per-direction radiance (sampler uProbeRadiance, probe_volume.glsl's probeRadianceAt()).
void readProbeRadiance(PassTable& t);
void bindProbeUniforms(const FrameContext& ctx);
// The probe textures and the sky atlas ("Probe Sky Irradiance", sampler uProbeSky) of shaders/environment.glsl.
void readProbeSky(PassTable& t);

}  // namespace deepgi
