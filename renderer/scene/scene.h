#pragma once
// The CPU scene model shared by the GL renderer and the reference path tracer.
// Static scenes: the glTF node hierarchy is flattened at load time, so every vertex is in world space.
#include <glm/glm.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace deepgi {

struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};
    void extend(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
    glm::vec3 center() const { return (lo + hi) * 0.5f; }
    glm::vec3 extent() const { return hi - lo; }
    float radius() const { return valid() ? 0.5f * glm::length(hi - lo) : 0.0f; }
};

// 8-bit image decoded at load time. Colour textures are sRGB-encoded (decoded on sampling).
struct Image {
    std::string name;            // URI or "image[i]" for messages
    int width = 0, height = 0;
    std::vector<uint8_t> rgba8;  // width*height*4, row 0 = top of the image (glTF convention, uv (0,0) = top-left)
};

enum class WrapMode : uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class FilterMode : uint8_t { Nearest, Linear };

struct Texture {
    int image = -1;  // index into Scene::images
    WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
    FilterMode magFilter = FilterMode::Linear;
    bool mipmaps = true;  // trilinear minification
};

enum class AlphaMode : uint8_t { Opaque, Mask, Blend };  // Blend is rendered as Mask (with a warning at load)

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};  // linear RGBA
    int baseColorTexture = -1;        // index into Scene::textures, sRGB
    glm::vec3 emissiveFactor{0.0f};   // linear, already multiplied by KHR_materials_emissive_strength
    int emissiveTexture = -1;         // sRGB
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    bool masked() const { return alphaMode != AlphaMode::Opaque; }
    bool emissive() const { return emissiveFactor.x > 0.0f || emissiveFactor.y > 0.0f || emissiveFactor.z > 0.0f; }
};

struct Vertex {
    glm::vec3 position;  // world space
    glm::vec3 normal;    // world space, unit length (flat normals generated where the file has none)
    glm::vec2 uv;        // TEXCOORD_0, (0,0) where missing
};

// One glTF primitive instance, flattened to world space, triangles only.
struct MeshPart {
    std::string name;               // "mesh/primitive" for messages
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
    int material = -1;              // index into Scene::materials; -1 = the default material (white, opaque)
};

enum class LightType : uint8_t { Directional, Point, Spot };

// KHR_lights_punctual. Units follow the renderer: a directional light's intensity is the irradiance (W/m^2 in
// scene units) on a surface facing it; point and spot intensity is radiant intensity (W/sr).
struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 position{0.0f};              // world space (point, spot)
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // world space, unit, the direction light travels (directional, spot)
    float range = 0.0f;                    // 0 = infinite
    float innerConeAngle = 0.0f;           // radians (spot)
    float outerConeAngle = 0.7853982f;     // radians (spot)
};

struct CameraDesc {
    std::string name;
    bool perspective = true;
    float yfov = 0.8f;         // radians (perspective)
    float aspectRatio = 0.0f;  // 0 = use the image's
    float znear = 0.05f;
    float zfar = 0.0f;         // 0 = infinite (glTF) -> the renderer picks a far plane from the scene bounds
    float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents
    glm::mat4 cameraToWorld{1.0f};   // looks down -Z, +Y up (glTF convention)
};

struct EnvironmentMap;  // renderer/scene/environment_map.h

struct Scene {
    std::string sourcePath;  // file it came from ("" for scenes built in code)
    std::vector<MeshPart> parts;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Light> lights;  // empty: the renderer adds the default sun from its settings
    std::vector<CameraDesc> cameras;
    std::vector<std::string> warnings;
    Aabb bounds;
    // The equirectangular environment map (--environment FILE), null = none: what rays leaving the scene see
    // and are lit by, with environment.* (renderer/scene/environment_map.h).
    std::shared_ptr<const EnvironmentMap> environment;
    uint64_t loadPeakBytes = 0;  // most memory the loader held at once (its own count, see GltfLoadOptions)

    size_t triangleCount() const {
        size_t n = 0;
        for (const auto& p : parts) n += p.indices.size() / 3;
        return n;
    }
    bool hasLight(LightType t) const {
        for (const auto& l : lights) if (l.type == t) return true;
        return false;
    }
    bool hasMaskedMaterial() const {
        for (const auto& m : materials) if (m.masked()) return true;
        return false;
    }
    bool hasEmission() const {
        for (const auto& m : materials) if (m.emissive()) return true;
        return false;
    }
    void computeBounds() {
        bounds = Aabb{};
        // Finite positions only: one Inf/NaN vertex (possible in a Scene built in code; the loader skips them) would
        // make the framing camera, the clip planes and the sun's shadow box infinite, and the image black.
        for (const auto& p : parts)
            for (const auto& v : p.vertices)
                if (std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z)) bounds.extend(v.position);
    }
    const Material& material(int i) const {
        static const Material kDefault{};
        return (i >= 0 && i < (int)materials.size()) ? materials[i] : kDefault;
    }
};

}  // namespace deepgi
