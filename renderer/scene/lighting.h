#pragma once
// The light model shared by the GL renderer (mirrored in shaders/lighting.glsl) and the reference path tracer.
// Lambertian surfaces: outgoing radiance = emission + albedo/pi * irradiance.
#include "renderer/core/settings.h"
#include "renderer/scene/scene.h"

#include <vector>

namespace deepgi {

// Most lights the GL renderer draws: MAX_LIGHTS of shaders/lighting.glsl, the constant bound of its light loop
// (the shadow-map layers, GL_MAX_ARRAY_TEXTURE_LAYERS, run out well before it). More is an error of the renderer.
inline constexpr int kMaxGpuLights = 16384;
// The first lights are also read through a uniform block (shaders/lighting.glsl MAX_BLOCK_LIGHTS): llvmpipe reads a
// uniform block once per draw's SIMD batch, a storage buffer per lane (the light loop was 2/3 of the input radiance).
inline constexpr int kBlockLights = 32;
// Up to this many lights the shaders get the count as a define, and their light loop a compile-time length that the
// compiler unrolls (shaders/lighting.glsl MAX_UNROLLED_LIGHTS).
inline constexpr int kUnrolledLights = 4;
inline constexpr int kGpuLightBytes = 128;  // sizeof(GpuLight), std430 = std140 for its vec4s and mat4

// The scene's lights scaled by light.intensity_scale, or the default sun from the settings when it has none.
std::vector<Light> effectiveLights(const Scene& scene, const Settings& s);

// Direction light travels for the default sun (azimuth measured from +Z towards +X, elevation above the XZ plane).
glm::vec3 defaultSunDirection(const Settings& s);

struct LightSample {
    glm::vec3 toLight{0.0f};  // unit vector from the point towards the light
    float distance = 0.0f;    // to the light; +inf for directional lights
    glm::vec3 irradiance{0.0f};  // unshadowed irradiance on a surface facing the light (no cosine at the receiver)
};

// glTF's recommended range window times inverse square falloff, and the spot cone falloff.
LightSample sampleLight(const Light& light, const glm::vec3& p);

// Irradiance on a surface at p with normal n from one light, unshadowed: sample.irradiance * max(0, n.l).
glm::vec3 lightIrradiance(const Light& light, const glm::vec3& p, const glm::vec3& n);

}  // namespace deepgi
