#include "renderer/passes/probe_update_pass.h"

#include "renderer/core/util.h"

#include "renderer/probes/probe_volume.h"

#include <algorithm>
#include <limits>

namespace deepgi {

void ProbeUpdatePass::table(const PipelineConfig& c, PassTable& t) const {
    if (!c.probes && !c.sky) return;
    auto size = [](const int s[2]) { return SizeRule::fixed(s[0], s[1]); };
    t.write({"Probe Irradiance", {"Probe Irradiance"}, GL_RGBA32F, GL_TEXTURE_2D, size(c.probeIrradianceSize), 1,
             MemoryGroup::Extra, Visualize::Radiance,
             "Irradiance of each world-space probe over the sphere of directions (octahedral tiles with a 1-texel "
             "border), from rays traced on the CPU"});
    t.write({"Probe Depth", {"Probe Depth"}, GL_RG32F, GL_TEXTURE_2D, size(c.probeDepthSize), 1, MemoryGroup::Extra,
             Visualize::Radiance,
             "Mean and mean squared distance to the nearest surface per direction of each probe (octahedral tiles): "
             "the Chebyshev visibility test against leaks"});
    t.write({"Probe Data", {"Probe Data"}, GL_RGBA32F, GL_TEXTURE_2D, size(c.probeDataSize), 1, MemoryGroup::Extra,
             Visualize::Radiance,
             "Per probe: xyz = offset from its grid position (moved out of geometry), w = state (1 active, 0 inside "
             "geometry, -1 unused: no surface near)"});
    if (c.sky)
        t.write({"Probe Sky Irradiance", {"Probe Sky Irradiance"}, GL_RGBA32F, GL_TEXTURE_2D, size(c.probeIrradianceSize), 1,
                 MemoryGroup::Extra, Visualize::Radiance,
                 "Irradiance from the environment of each probe over the sphere of directions (its rays that leave "
                 "the scene; octahedral tiles as Probe Irradiance): the sky's direct light with visibility"});
    if (c.probeDirectionalFill)
        t.write({"Probe Radiance", {"Probe Radiance"}, GL_RGBA32F, GL_TEXTURE_2D, size(c.probeRadianceSize), 1,
                 MemoryGroup::Extra, Visualize::Radiance,
                 "Radiance arriving at each probe per direction (octahedral tiles as Probe Irradiance; a = updates "
                 "with a ray through the texel): the gather fills the hemisphere sectors the screen did not cover"});
}

void ProbeUpdatePass::begin(FrameContext& ctx) {
    ProbeVolume& v = *ctx.probes;
    // New lights, another bounce damping (the probes' bounce is damped like the screen's), or a new volume: every
    // probe starts over; a settled volume would otherwise keep the old answer for good.
    const RadiositySettings& rs = ctx.settings;
    uint64_t key = fnv1a(ctx.shadowKey, &rs.damping, sizeof(rs.damping));
    if (ctx.config.sky) {  // and the environment, when it lights
        const EnvironmentSettings& es = ctx.settings;
        const void* map = ctx.environment;
        key = fnv1a(key, &es.skyRadiance, sizeof(es.skyRadiance));
        key = fnv1a(key, &es.environmentIntensity, sizeof(es.environmentIntensity));
        key = fnv1a(key, &es.environmentRotation, sizeof(es.environmentRotation));
        key = fnv1a(key, &map, sizeof(map));
    }
    key |= 1u;
    if (key != lightKey_) {
        if (lightKey_ != 0 && uploadedVolume_ == &v) v.resetHistory();
        lightKey_ = key;
    }
    const bool settled = v.settled(ctx.settings);
    allTexels_ = uploadedTextures_ != ctx.writtenTexturesKey() || uploadedVolume_ != &v;
    upload_ = !settled || allTexels_;  // settled and uploaded: converged under these lights, the textures hold
    // New textures (a resize, a pipeline change) only need the settled state uploaded again: another update would
    // make the probes, and so the image, depend on how many times the textures were reallocated.
    update_ = !settled;
    const ProbeSettings& ps = ctx.settings;
    if (update_ && ps.probeOverlap) v.startUpdate(ctx.settings, v.threads() - 1, true);  // this thread joins in execute()
}

void ProbeUpdatePass::execute(FrameContext& ctx) {
    ProbeVolume& v = *ctx.probes;
    if (update_) {
        const ProbeSettings& ps = ctx.settings;
        if (ps.probeOverlap) v.finishUpdate();  // the one begin() started
        else v.update(ctx.settings);            // all of it here (finishing one a failed frame left first)
    }
    if (upload_) {
        if (ctx.config.sky) v.uploadSkyTexture(ctx.texture("Probe Sky Irradiance"), allTexels_);
        v.uploadTextures(ctx.texture("Probe Irradiance"), ctx.texture("Probe Depth"), ctx.texture("Probe Data"),
                         ctx.config.probeDirectionalFill ? ctx.texture("Probe Radiance") : 0, allTexels_);
        uploadedTextures_ = ctx.writtenTexturesKey();
        uploadedVolume_ = &v;
    }
    v.uploadUniforms(ctx.probeUniforms);  // 80 bytes, every frame: the view bias may change on a settled volume
}

void readProbeVolume(PassTable& t) {
    t.read("Probe Irradiance", "uProbeIrradiance");
    t.read("Probe Depth", "uProbeDepth");
    t.read("Probe Data", "uProbeData");
}

void readProbeSky(PassTable& t) {
    readProbeVolume(t);
    t.read("Probe Sky Irradiance", "uProbeSky");
}
void readProbeRadiance(PassTable& t) { t.read("Probe Radiance", "uProbeRadiance"); }

void bindProbeUniforms(const FrameContext& ctx) { glBindBufferBase(GL_UNIFORM_BUFFER, 2, ctx.probeUniforms); }

}  // namespace deepgi
