#include "renderer/scene/lighting.h"

#include "renderer/scene/scene_validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi {

glm::vec3 defaultSunDirection(const Settings& s) {
    const float az = glm::radians(s.sunAzimuth), el = glm::radians(s.sunElevation);
    const glm::vec3 toSun(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    return -glm::normalize(toSun);
}

std::vector<Light> effectiveLights(const Scene& scene, const Settings& s) {
    std::vector<Light> lights = scene.lights;
    const bool fileLights = !lights.empty();
    if (fileLights)  // a light under a hidden node is off
        lights.erase(std::remove_if(lights.begin(), lights.end(), [&](const Light& l) { return !scene.nodeVisible(l.node); }), lights.end());
    if (!fileLights) {
        Light sun;
        sun.name = "default sun";
        sun.type = LightType::Directional;
        sun.intensity = s.sunIntensity;
        sun.direction = defaultSunDirection(s);
        lights.push_back(sun);
    }
    // The same corrections the loader made (with warnings) for scenes built in code, so renderer and path tracer agree.
    std::vector<Light> valid;
    for (auto& l : lights)
        if (validateLight(l, nullptr)) valid.push_back(l);
    for (auto& l : valid) l.intensity *= s.lightScale;
    return valid;
}

LightSample sampleLight(const Light& light, const glm::vec3& p) {
    LightSample out;
    const glm::vec3 radiance = light.color * light.intensity;
    if (light.type == LightType::Directional) {
        out.toLight = -light.direction;
        out.distance = std::numeric_limits<float>::infinity();
        out.irradiance = radiance;
        return out;
    }
    glm::vec3 d = light.position - p;
    float dist2 = glm::dot(d, d);
    float dist = std::sqrt(dist2);
    out.distance = dist;
    out.toLight = dist > 0.0f ? d / dist : glm::vec3(0.0f, 1.0f, 0.0f);
    float atten = 1.0f / std::max(dist2, 1e-20f);  // guards only 0; no length unit (a 1e-4 floor broke 1 mm scenes)
    if (light.range > 0.0f) {
        float r = dist / light.range;
        float w = std::min(std::max(1.0f - r * r * r * r, 0.0f), 1.0f);
        atten *= w * w;
    }
    if (light.type == LightType::Spot) {
        float cosOuter = std::cos(light.outerConeAngle), cosInner = std::cos(light.innerConeAngle);
        float cd = glm::dot(light.direction, -out.toLight);
        float t = (cd - cosOuter) / std::max(cosInner - cosOuter, 1e-4f);
        t = std::min(std::max(t, 0.0f), 1.0f);
        atten *= t * t;
    }
    out.irradiance = radiance * atten;
    return out;
}

glm::vec3 lightIrradiance(const Light& light, const glm::vec3& p, const glm::vec3& n) {
    LightSample s = sampleLight(light, p);
    return s.irradiance * std::max(0.0f, glm::dot(n, s.toLight));
}

}  // namespace deepgi
