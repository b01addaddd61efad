#pragma once
// What a CPU ray tracer (the reference path tracer, the probe tracer) knows of a hit triangle: its mesh part and
// material, and the material's textures sampled as the GL renderer samples them (mip 0, bilinear or nearest as the
// sampler asks, rgb sRGB-decoded, alpha linear). One definition, so the two tracers never disagree on a texel.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace deepgi {

struct TextureView {
    const uint8_t* texels = nullptr;
    int width = 0, height = 0;
    WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
    bool nearest = false;

    bool valid() const { return texels != nullptr; }
    glm::vec4 sample(glm::vec2 uv) const;
};

// The view of scene.textures[textureIndex] (invalid for -1, a missing image or one without texels).
TextureView makeTextureView(const Scene& scene, int textureIndex);

struct TracedSurface {
    const MeshPart* part = nullptr;
    const Material* material = nullptr;
    TextureView baseTexture, emissiveTexture;
    // The part's current placement (Scene::partModel): the Embree buffer holds moved positions; positions and
    // normals interpolated from part->vertices (rest pose) go through toWorld / toWorldNormal.
    bool moved = false;
    glm::mat4 model{1.0f};
    glm::mat3 normalMatrix{1.0f};  // cofactor of mat3(model): inverse transpose up to a positive scale

    TracedSurface() = default;
    TracedSurface(const Scene& scene, const MeshPart& p);  // also takes the part's current model matrix

    void setModel(const glm::mat4& m);
    glm::vec3 toWorld(const glm::vec3& p) const { return moved ? glm::vec3(model * glm::vec4(p, 1.0f)) : p; }
    glm::vec3 toWorldNormal(const glm::vec3& n) const { return moved ? normalMatrix * n : n; }
    // The Embree vertex buffer: 3 floats per vertex, moved.
    void writePositions(float* xyz) const;

    glm::uvec3 triangle(unsigned prim) const {
        const uint32_t* i = &part->indices[size_t(prim) * 3];
        return {i[0], i[1], i[2]};
    }
    // Counter-clockwise (glTF front) face normal in world space now, not normalised.
    glm::vec3 faceNormal(const glm::uvec3& t) const {
        const glm::vec3& p0 = part->vertices[t.x].position;
        return toWorldNormal(glm::cross(part->vertices[t.y].position - p0, part->vertices[t.z].position - p0));
    }
    glm::vec2 uvAt(const glm::uvec3& t, float u, float v) const {
        return (1.0f - u - v) * part->vertices[t.x].uv + u * part->vertices[t.y].uv + v * part->vertices[t.z].uv;
    }
    float alphaAt(const glm::uvec3& t, float u, float v) const {
        float a = material->baseColorFactor.w;
        if (baseTexture.valid()) a *= baseTexture.sample(uvAt(t, u, v)).w;
        return a;
    }
    // A masked material's texel below its cutoff: rays pass through it.
    bool cutOut(const glm::uvec3& t, float u, float v) const {
        return material->masked() && alphaAt(t, u, v) < material->alphaCutoff;
    }
};

// After a scene edit: each geometry's vertex buffer rewritten where its part moved, hidden parts disabled, and the
// Embree scene recommitted (geometry id i = geoms[i]). `rtcScene` is an RTCScene.
void refitTracedScene(void* rtcScene, std::vector<TracedSurface>& geoms, const Scene& scene);

}  // namespace deepgi
