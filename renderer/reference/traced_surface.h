#pragma once
// What a CPU ray tracer (the reference path tracer, the probe tracer) knows of a hit triangle: its mesh part and
// material, and the material's textures sampled as the GL renderer samples them (mip 0, bilinear or nearest as the
// sampler asks, rgb sRGB-decoded, alpha linear). One definition, so the two tracers never disagree on a texel.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace deepgi {

struct TextureView {
    const uint8_t* texels = nullptr;
    int width = 0, height = 0;
    WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
    bool nearest = false;
    bool srgb = true;  // rgb sRGB-decoded (colour); false: data textures, linear

    bool valid() const { return texels != nullptr; }
    glm::vec4 sample(glm::vec2 uv) const;
};

// The view of scene.textures[textureIndex] (invalid for -1, a missing image or one without texels).
TextureView makeTextureView(const Scene& scene, int textureIndex);

struct TracedSurface {
    const MeshPart* part = nullptr;
    const Material* material = nullptr;
    TextureView baseTexture, emissiveTexture;
    TextureView metalRoughTexture, normalTexture, occlusionTexture;  // linear data (glTF metallic-roughness)

    TracedSurface() = default;
    TracedSurface(const Scene& scene, const MeshPart& p);

    glm::uvec3 triangle(unsigned prim) const {
        const uint32_t* i = &part->indices[size_t(prim) * 3];
        return {i[0], i[1], i[2]};
    }
    // Counter-clockwise (glTF front) face normal, not normalised.
    glm::vec3 faceNormal(const glm::uvec3& t) const {
        const glm::vec3& p0 = part->vertices[t.x].position;
        return glm::cross(part->vertices[t.y].position - p0, part->vertices[t.z].position - p0);
    }
    glm::vec2 uvAt(const glm::uvec3& t, float u, float v) const {
        return (1.0f - u - v) * part->vertices[t.x].uv + u * part->vertices[t.y].uv + v * part->vertices[t.z].uv;
    }
    float alphaAt(const glm::uvec3& t, float u, float v) const {
        float a = material->baseColorFactor.w;
        if (baseTexture.valid()) a *= baseTexture.sample(uvAt(t, u, v)).w;
        return a;
    }
    // The shading normal at barycentrics (u, v): n (unit, oriented to the ray's side; backFace = the hit was on the
    // back of a double-sided material) perturbed by the normal texture, as shaders/material.glsl mappedNormal.
    glm::vec3 mappedNormal(const glm::uvec3& t, float u, float v, const glm::vec3& n, bool backFace) const;
    // Base colour rgb, metallic, roughness, occlusion at uv (factors x textures).
    glm::vec3 baseColorAt(glm::vec2 uv) const;
    glm::vec2 metallicRoughnessAt(glm::vec2 uv) const;
    float occlusionAt(glm::vec2 uv) const;
    // A masked material's texel below its cutoff: rays pass through it.
    bool cutOut(const glm::uvec3& t, float u, float v) const {
        return material->masked() && alphaAt(t, u, v) < material->alphaCutoff;
    }
};

}  // namespace deepgi
