#pragma once
// The metallic-roughness BRDF of glTF 2.0 (specification, appendix B), shared by the reference path tracer, the
// probe tracer and the tests; shaders/brdf.glsl is its GLSL twin (keep the two in step):
//   f = diffuse / pi + F * D * V
//   diffuse = base x (1 - metallic)                         (what the G-buffer stores and the GI uses)
//   F0 = mix(dielectricF0, base, metallic), F = Schlick, D = Trowbridge-Reitz (GGX), V = Smith height-correlated,
//   alpha = roughness^2 (clamped to kMinAlpha so a mirror stays a finite lobe for point lights).
// The diffuse lobe is not weighted by (1 - F): the G-buffer's albedo is view-independent (one value the gather
// reuses from every direction); the path tracer does the same so the two agree.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {
namespace brdf {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kMinAlpha = 0.002f;

inline float alphaOf(float roughness) { return std::max(kMinAlpha, std::clamp(roughness, 0.0f, 1.0f) * std::clamp(roughness, 0.0f, 1.0f)); }

// GGX normal distribution at cos(n, h).
inline float D(float nh, float alpha) {
    const float a2 = alpha * alpha;
    const float d = nh * nh * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}
// Smith height-correlated visibility V = G2 / (4 |n.l| |n.v|).
inline float V(float nl, float nv, float alpha) {
    const float a2 = alpha * alpha;
    const float gv = nl * std::sqrt(nv * nv * (1.0f - a2) + a2);
    const float gl = nv * std::sqrt(nl * nl * (1.0f - a2) + a2);
    const float s = gv + gl;
    return s > 0.0f ? 0.5f / s : 0.0f;
}
// Smith masking of one direction (for the visible-normal pdf).
inline float G1(float nv, float alpha) {
    const float a2 = alpha * alpha;
    return 2.0f * nv / (nv + std::sqrt(a2 + (1.0f - a2) * nv * nv));
}
inline glm::vec3 fresnel(const glm::vec3& f0, float vh) {
    const float m = std::clamp(1.0f - vh, 0.0f, 1.0f);
    const float m2 = m * m;
    return f0 + (glm::vec3(1.0f) - f0) * (m2 * m2 * m);
}

// The specular lobe F * D * V for unit n, v (towards the viewer), l (towards the light); 0 below either horizon.
inline glm::vec3 specular(const glm::vec3& n, const glm::vec3& v, const glm::vec3& l, const glm::vec3& f0, float alpha) {
    const float nl = glm::dot(n, l), nv = glm::dot(n, v);
    if (!(nl > 0.0f) || !(nv > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 h = glm::normalize(v + l);
    return fresnel(f0, glm::dot(v, h)) * (D(std::max(glm::dot(n, h), 0.0f), alpha) * V(nl, nv, alpha));
}

// Visible-normal sampling of GGX (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"), in the local
// frame where the normal is +z: v is the unit direction to the viewer (v.z > 0); returns a unit microfacet normal.
inline glm::vec3 sampleVisibleNormal(const glm::vec3& v, float alpha, float u1, float u2) {
    const glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));  // the hemisphere configuration
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    const float p1 = r * std::cos(phi);
    const float sw = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - sw) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + sw * r * std::sin(phi);
    const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));  // back to the ellipsoid
}
// Density (solid angle) of the reflected direction l = reflect(-v, h) for h from sampleVisibleNormal.
inline float reflectionPdf(float nv, float nh, float alpha) {
    return nv > 0.0f ? G1(nv, alpha) * D(nh, alpha) / (4.0f * nv) : 0.0f;
}

// What a surface point's material resolves to (textures sampled).
struct Params {
    glm::vec3 diffuse{0.0f};  // albedo of the Lambertian lobe
    glm::vec3 f0{0.0f};
    float alpha = 1.0f;
    bool specular = false;
};
// base: base colour (factor x texture), metallic/roughness: factor x texture; diffuseOnly (material.diffuse_only):
// a Lambertian lobe of albedo = base colour, no specular.
inline Params resolve(const glm::vec3& base, float metallic, float roughness, float dielectricF0, bool hasSpecular,
                      bool diffuseOnly) {
    Params p;
    metallic = std::clamp(metallic, 0.0f, 1.0f);
    if (diffuseOnly || !hasSpecular) {
        p.diffuse = diffuseOnly ? base : base * (1.0f - metallic);
        return p;
    }
    p.diffuse = base * (1.0f - metallic);
    p.f0 = glm::mix(glm::vec3(dielectricF0), base, metallic);
    p.alpha = alphaOf(roughness);
    p.specular = true;
    return p;
}

}  // namespace brdf
}  // namespace deepgi
