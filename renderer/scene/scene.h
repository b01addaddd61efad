#pragma once
// The CPU scene model shared by the GL renderer and the reference path tracer.
// Vertices stay as loaded (world space of the rest pose, the file's node transforms applied once); the node tree
// is kept, and each part is drawn and traced with its current model matrix partModel() = node world * inverse(rest).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <algorithm>
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
    bool srgb = true;     // colour (base, emissive) is sRGB-encoded; data (normal, metallic-roughness, occlusion) is linear
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
    // glTF metallic-roughness (the core model; renderer/scene/brdf.h): diffuse albedo = base x (1 - metallic), GGX
    // specular with F0 = mix(dielectricF0, base, metallic). Built in code (and OBJ): Lambertian, dielectricF0 0;
    // the glTF loader sets dielectricF0 to 0.04 (glTF's ior 1.5).
    float metallic = 0.0f, roughness = 1.0f;
    float dielectricF0 = 0.0f;
    int metallicRoughnessTexture = -1;  // linear: G = roughness, B = metallic (multiplying the factors)
    int normalTexture = -1;             // linear, tangent space (+Y up); needs Vertex::tangent
    float normalScale = 1.0f;
    int occlusionTexture = -1;          // linear, R; darkens indirect light only
    float occlusionStrength = 1.0f;
    bool masked() const { return alphaMode != AlphaMode::Opaque; }
    bool emissive() const { return emissiveFactor.x > 0.0f || emissiveFactor.y > 0.0f || emissiveFactor.z > 0.0f; }
    // Any specular reflection at all (a pure Lambertian material has none).
    bool specular() const { return metallic > 0.0f || metallicRoughnessTexture >= 0 || dielectricF0 > 0.0f; }
    bool occluded() const { return occlusionTexture >= 0 && occlusionStrength > 0.0f; }
};

struct Vertex {
    glm::vec3 position;  // world space of the rest pose (partModel() moves it)
    glm::vec3 normal;    // world space, unit length (flat normals generated where the file has none)
    glm::vec2 uv;        // TEXCOORD_0, (0,0) where missing
    // World-space unit tangent (direction of increasing u) and handedness w: bitangent = cross(normal, xyz) * w
    // points to decreasing v (glTF's +Y up). glTF TANGENT, else generated at load for normal-mapped materials.
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};
};

// One glTF primitive instance, flattened to world space, triangles only.
struct MeshPart {
    std::string name;               // "mesh/primitive" for messages
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
    int material = -1;              // index into Scene::materials; -1 = the default material (white, opaque)
    int node = -1;                  // index into Scene::nodes (-1: a scene built in code without nodes: never moves)
    glm::mat4 restWorld{1.0f};      // the node's world matrix the vertices were placed with
};

// Extends b by a part's vertex positions (as loaded) moved by model, leaving out those that are not finite (possible
// in a Scene built in code; the loaders skip them: one would make the framing camera, the clip planes and the sun's
// shadow box infinite). Returns how many were left out. scene_graph.cpp.
size_t extendByVertices(Aabb& b, const MeshPart& part, const glm::mat4& model = glm::mat4(1.0f));

// A node's local transform, glTF's TRS (a file's matrix is decomposed at load).
struct Transform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; unit
    glm::vec3 scale{1.0f};
    glm::mat4 matrix() const;  // T * R * S
};

struct SceneNode {
    std::string name;                 // glTF node name ("node[i]" when unnamed)
    int parent = -1;
    std::vector<int> children;
    Transform local;                  // editable
    glm::mat4 world{1.0f};            // derived: Scene::updateWorldTransforms()
    std::vector<int> parts;           // MeshPart indices drawn by this node (derived from MeshPart::node)
    int light = -1, camera = -1;      // indices into Scene::lights / cameras (derived from their node)
    bool visible = true;              // hidden (or under a hidden node): not drawn, not traced, casts nothing, lights nothing
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
    int node = -1;                         // the node that places it (-1: fixed, e.g. a light built in code)
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
    int node = -1;                   // the node that places it
};

// glTF animation of node TRS (renderer/scene/animation.h samples it).
enum class AnimationPath : uint8_t { Translation, Rotation, Scale };
enum class Interpolation : uint8_t { Linear, Step, CubicSpline };
struct AnimationChannel {
    int node = -1;  // index into Scene::nodes
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;   // seconds, increasing
    // Per key: 3 floats (translation, scale) or 4 (rotation quaternion x, y, z, w); CUBICSPLINE: in-tangent, value,
    // out-tangent per key (glTF's order).
    std::vector<float> values;
};
struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
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
    std::vector<SceneNode> nodes;  // the tree: parents before children is not required
    std::vector<int> roots;        // nodes without a parent, in file order
    std::vector<Animation> animations;
    Aabb bounds;                   // of the vertices as loaded (rest pose): the scene's size for lengths
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
    bool hasSpecular() const {
        for (const auto& m : materials) if (m.specular()) return true;
        return false;
    }
    bool hasOcclusion() const {
        for (const auto& m : materials) if (m.occluded()) return true;
        return false;
    }
    bool hasNormalMaps() const {
        for (const auto& m : materials) if (m.normalTexture >= 0) return true;
        return false;
    }
    bool hasEmission() const {
        for (const auto& m : materials) if (m.emissive()) return true;
        return false;
    }
    void computeBounds() {
        bounds = Aabb{};
        for (const auto& p : parts) extendByVertices(bounds, p);
    }
    // ---- The node tree (scene_graph.cpp) ----
    // Recomputes every node's world matrix from the local transforms, then each light's position and direction and
    // each camera's cameraToWorld from its node. Call after editing Transform::local.
    void updateWorldTransforms();
    // The world matrices alone (lights and cameras untouched): what the loaders call once.
    void computeNodeWorlds();
    // Current model matrix of a part's vertices: identity (exactly) while its node is where it was at load.
    glm::mat4 partModel(int part) const;
    // World bounds of a node's parts (and its children's) now; a node without parts: its origin.
    Aabb nodeBounds(int node) const;
    // Bounds of every visible part now (the shadow box of the sun follows moved objects).
    Aabb currentBounds() const;
    // The node and all its ancestors are visible (-1: visible).
    bool nodeVisible(int node) const;
    bool partVisible(int part) const { return part >= 0 && part < int(parts.size()) && nodeVisible(parts[size_t(part)].node); }
    // Rebuilds nodes' children / parts / light / camera lists and roots from the parent and node fields.
    void linkNodes();
    // Gives every part, light and camera without a node its own root node (OBJ, built-in scenes), sets each
    // part's restWorld to its node's world, and links the tree.
    void ensureNodes();
    int addNode(const std::string& name, int parent = -1, const Transform& local = {});
    // The last key time of every animation (0 without animations).
    float animationDuration() const {
        float d = 0.0f;
        for (const auto& a : animations)
            for (const auto& c : a.channels)
                if (!c.times.empty()) d = std::max(d, c.times.back());
        return d;
    }

    const Material& material(int i) const {
        static const Material kDefault{};
        return (i >= 0 && i < (int)materials.size()) ? materials[i] : kDefault;
    }
};

}  // namespace deepgi
