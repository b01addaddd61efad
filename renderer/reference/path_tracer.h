#pragma once
// Reference path tracer on Embree 3: the ground truth for the Deep G-Buffer renderer, with the same light
// transport (renderer/scene/lighting.h):
//   - glTF metallic-roughness (renderer/scene/brdf.h): a Lambertian lobe of albedo base x (1 - metallic), base =
//     baseColorFactor.rgb * sRGB-decoded base texture (bilinear, mip 0), plus GGX specular; normal maps with the
//     vertices' tangents; the occlusion texture scales the light of every bounce. material.diffuse_only: Lambertian,
//     albedo = base colour. Masked materials (Mask, Blend) are transparent where factor.a * texture.a < alphaCutoff.
//   - Bounces choose the diffuse or the GGX lobe (visible-normal sampling) and weight by both lobes' density.
//   - Emission (emissiveFactor * sRGB-decoded emissive texture) is added wherever a camera or bounce ray hits.
//   - Single-sided surfaces are invisible from behind to camera and bounce rays (the rasterizer culls back
//     faces) but block shadow rays from both sides (the shadow maps are rendered without culling).
//   - Next-event estimation towards every light of effectiveLights(); bounces sampled from the BRDF (diffuse, or
//     diffuse + GGX by a lobe choice); Russian roulette after the third bounce. Camera rays that miss see
//     light.background + the environment; bounce rays that miss get the environment (renderer/scene/environment_map.h)
//     unless a back face was in the way (both faces block the sky, as they block shadow rays and the probes' rays),
//     whose map is importance-sampled (luminance x sin(theta)) for next-event estimation at every hit, combined with
//     the BRDF sampling of the bounces by the power heuristic; a uniform sky alone is left to the BRDF sampling.
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/core/util.h"  // parseImageSize (moved there; kept reachable for existing callers)
#include "renderer/scene/scene.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

namespace deepgi {

struct ReferenceOptions {
    int width = 320, height = 180;
    int spp = 256;         // samples per pixel, jittered within the pixel (box filter)
    int maxBounces = 16;   // bounce rays after the camera ray; 0 = direct light only
    uint64_t seed = 1;     // the image depends only on the seed, never on the thread count
    int threads = 0;       // 0 = std::thread::hardware_concurrency()
    bool progress = true;  // progress bar on stderr (a line every 10% when stderr is not a terminal)
};

struct ReferenceResult {
    // RGB linear radiance. final = direct + indirect (accumulated separately, not subtracted).
    // direct = emission seen by the camera + direct light at the first hit (lights and environment) + backdrop.
    FloatImage final, direct, indirect;
    FloatImage stdError;          // per pixel and channel: standard error of the mean of `final`
    double seconds = 0.0;         // wall time of the render (without the BVH build)
    double meanRelStdError = 0.0; // mean over pixels with mean grey value > 1e-3 of stderr / mean (grey)
    uint64_t rays = 0;            // camera, bounce and shadow rays traced
    double raysPerSecond() const { return seconds > 0.0 ? double(rays) / seconds : 0.0; }
};

// The Embree scene built once from a Scene, reusable for many renders. The Scene must outlive the tracer
// (shading reads its vertices, materials and images). Throws std::runtime_error on Embree failures or on
// index buffers that point outside their vertices.
class ReferenceTracer {
public:
    explicit ReferenceTracer(const Scene& scene);
    ~ReferenceTracer();
    ReferenceTracer(const ReferenceTracer&) = delete;
    ReferenceTracer& operator=(const ReferenceTracer&) = delete;

    // Throws std::invalid_argument for a bad size, spp, bounce count or thread count.
    ReferenceResult render(const Camera& camera, const Settings& settings, const ReferenceOptions& options) const;
    // Follows an edit of the Scene (moved or hidden parts; lights are read by every render): vertex buffers
    // rewritten and the Embree scene recommitted.
    void update();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// One-shot convenience: build the tracer and render.
ReferenceResult renderReference(const Scene& scene, const Camera& camera, const Settings& settings,
                                const ReferenceOptions& options);

}  // namespace deepgi
