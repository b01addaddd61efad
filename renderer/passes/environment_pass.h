#pragma once
#include "renderer/passes/pass.h"

namespace deepgi {

// The scene's environment map (renderer/scene/environment_map.h) as the GL texture "Environment Map"
// (equirectangular, RGBA16F with mip levels, repeating in u), uploaded when the map or the texture changes; the
// composite shows it as the backdrop (shaders/environment.glsl). Its light reaches the scene through the probes
// (Probe Sky Irradiance), which the CPU computes from the same map.
class EnvironmentPass final : public RenderPass {
public:
    const char* name() const override { return "Environment"; }
    void table(const PipelineConfig& c, PassTable& t) const override;
    bool enabled(const PipelineConfig& c) const override { return c.environmentMap; }
    void execute(FrameContext& ctx) override;

private:
    const EnvironmentMap* uploadedMap_ = nullptr;
    uint64_t uploadedTextures_ = 0;  // FrameContext::writtenTexturesKey() of the last upload
};

// What shaders/environment.glsl's uniforms hold for this frame: uEnvironment = (sky radiance x intensity,
// intensity, 1 when the map is bound, environment.rotation in radians).
glm::vec4 environmentUniform(const FrameContext& ctx);
// The environment map a pass that shows the backdrop reads (sampler uEnvironmentMap), optional without a map.
void readEnvironmentMap(const PipelineConfig& c, PassTable& t);

}  // namespace deepgi
