#include "renderer/passes/probe_update_pass.h"

#include "renderer/probes/probe_volume.h"

namespace deepgi {

void ProbeUpdatePass::declare(const PipelineConfig& c, std::vector<TextureDecl>& out) const {
    if (!c.probes) return;
    auto fixed = [](TextureDecl d, const int size[2]) {
        d.size = SizeRule::Fixed;
        d.fixedWidth = size[0];
        d.fixedHeight = size[1];
        return d;
    };
    out.push_back(fixed({"Probe Irradiance", {"Probe Irradiance"}, GL_RGBA32F, GL_TEXTURE_2D, SizeRule::Fixed, 1,
                         MemoryGroup::Extra, Visualize::Radiance,
                         "Irradiance of each world-space probe over the sphere of directions (octahedral tiles with a "
                         "1-texel border), from rays traced on the CPU"},
                        c.probeIrradianceSize));
    out.push_back(fixed({"Probe Depth", {"Probe Depth"}, GL_RG32F, GL_TEXTURE_2D, SizeRule::Fixed, 1, MemoryGroup::Extra,
                         Visualize::Radiance,
                         "Mean and mean squared distance to the nearest surface per direction of each probe (octahedral "
                         "tiles): the Chebyshev visibility test against leaks"},
                        c.probeDepthSize));
    out.push_back(fixed({"Probe Data", {"Probe Data"}, GL_RGBA32F, GL_TEXTURE_2D, SizeRule::Fixed, 1, MemoryGroup::Extra,
                         Visualize::Radiance,
                         "Per probe: xyz = offset from its grid position (moved out of geometry), w = state (1 active, 0 "
                         "inside geometry, -1 unused: no surface near)"},
                        c.probeDataSize));
}

void ProbeUpdatePass::execute(FrameContext& ctx) {
    ProbeVolume& v = *ctx.probes;
    v.update(ctx.settings);
    const bool all = uploadedGeneration_ != ctx.textures.generation() || uploadedVolume_ != &v;
    v.uploadTextures(ctx.textures.id("Probe Irradiance"), ctx.textures.id("Probe Depth"), ctx.textures.id("Probe Data"), all);
    uploadedGeneration_ = ctx.textures.generation();
    uploadedVolume_ = &v;
    v.uploadUniforms(ctx.probeUniforms);
}

void bindProbeVolume(const FrameContext& ctx) {
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, ctx.probeUniforms);
    glBindTextureUnit(2, ctx.textures.id("Probe Irradiance"));
    glBindTextureUnit(3, ctx.textures.id("Probe Depth"));
    glBindTextureUnit(5, ctx.textures.id("Probe Data"));
}

}  // namespace deepgi
