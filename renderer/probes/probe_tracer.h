#pragma once
// The Embree scene the irradiance probes trace, built from a Scene with the reference path tracer's conventions
// (renderer/reference/path_tracer.h): Lambertian albedo = baseColorFactor.rgb * sRGB-decoded base texture
// (bilinear, mip 0), emission = emissiveFactor * emissive texture, cut-out texels of masked materials let rays
// through, both faces block shadow rays, next-event estimation towards every light of effectiveLights().
// One difference, on purpose: probe rays see the back faces of single-sided surfaces (the path tracer's bounce
// rays pass through them), since a probe that sees back faces is inside geometry.
#include "renderer/scene/lighting.h"
#include "renderer/scene/scene.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace deepgi {

struct ProbeHit {
    bool hit = false;
    bool backFace = false;     // a single-sided surface seen from behind
    float distance = 0.0f;     // along the unit ray direction
    glm::vec3 position{0.0f};
    glm::vec3 geomNormal{0.0f}, normal{0.0f};  // unit, towards the side the ray came from (front faces)
    glm::vec3 albedo{0.0f}, emission{0.0f};
};

class ProbeTracer {
public:
    // The Scene must outlive the tracer. Throws std::runtime_error naming the mesh part on an index past its
    // vertices, or on an Embree failure.
    explicit ProbeTracer(const Scene& scene);
    ~ProbeTracer();
    ProbeTracer(const ProbeTracer&) = delete;
    ProbeTracer& operator=(const ProbeTracer&) = delete;

    // Follows a scene edit (moved or hidden parts): vertex buffers rewritten, Embree scene recommitted. Not thread-safe.
    void update(const Scene& scene);
    // Nearest surface along origin + t*dir, t in (tnear, tfar). Thread-safe.
    ProbeHit intersect(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;
    // Irradiance at a front-face hit from every light, with shadow rays (no albedo, no 1/pi), as the path tracer
    // computes it. Adds the shadow rays traced to `rays`. Thread-safe.
    glm::vec3 directIrradiance(const ProbeHit& hit, const std::vector<Light>& lights, uint64_t& rays) const;
    // Offset for ray origins leaving a surface: relative to the scene's size, so that any scale works.
    float epsilon() const { return epsilon_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    float epsilon_ = 1e-4f;
};

}  // namespace deepgi
