#pragma once
// Internal to the glTF loader: the reader class whose methods are split by what they read:
//   gltf_loader.cpp        the file itself (GLB, JSON checks, URIs confined to the folder), the node hierarchy
//   gltf_geometry.cpp      buffers, buffer views, accessors (sparse included) and mesh primitives
//   gltf_materials.cpp     materials, textures, samplers and images
//   gltf_cameras_lights.cpp cameras and KHR_lights_punctual
// Only the loader's .cpp files include this header; everyone else uses gltf_loader.h.
#include "renderer/scene/gltf_loader.h"
#include "renderer/scene/scene_files.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace deepgi {
namespace gltf {

constexpr int kCompByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kCompUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kCompShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kCompUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kCompUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kCompFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

// `s` fit for a one-line message: control characters (a NUL would cut the message short) escaped as \xNN, and
// anything past `maxLen` bytes replaced by "... (N bytes)" (data URIs are megabytes of base64).
inline std::string printable(const std::string& s, size_t maxLen = 240) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (size_t i = 0; i < s.size() && i < maxLen; ++i) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        if (c < 0x20 || c == 0x7f) out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
        else out += char(c);
    }
    if (s.size() > maxLen) out += "... (" + std::to_string(s.size()) + " bytes)";
    return out;
}

// The extensions the loader reads; a file that requires any other is refused before tinygltf parses it.
const std::set<std::string>& supportedExtensions();

inline float finiteOr(double v, float fallback) { return std::isfinite(v) ? float(v) : fallback; }
inline bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Reads one glTF file into a Scene. Every method that finds the file unusable throws SceneLoadError via fail().
class GltfReader {
public:
    GltfReader(const std::string& path, const GltfLoadOptions& opt)
        : path_(path), opt_(opt), budget_(path, opt.memoryBudget) {}
    Scene run();

private:
    std::string path_;
    GltfLoadOptions opt_;
    tinygltf::Model model_;
    Scene scene_;
    uint64_t elements_ = 0;
    std::vector<int> imageMap_;    // glTF image -> Scene::images index, -1 unusable, -2 not decoded yet
    std::vector<int> textureMap_;  // glTF texture -> Scene::textures index, -1 unusable, -2 not resolved yet
    std::map<std::string, std::string> uriProblems_;  // URI -> why it was not read (escapes, FIFO, ...)
    uint64_t skippedNonFinite_ = 0;
    int currentNode_ = -1;                    // the Scene node being placed (addMesh/addCamera/addLight tag with it)
    std::vector<int> sceneNodeOf_;            // glTF node -> Scene node (-1: not in the scene)
    LoadBudget budget_;  // GltfLoadOptions::memoryBudget
    std::vector<uint32_t> meshInstances_;     // glTF mesh -> instances placed so far (for messages)
    bool quantized_ = false;                  // KHR_mesh_quantization: integer positions, normals, texcoords
    std::map<std::pair<int, int>, int> dracoIndices_;  // (mesh, primitive) -> index accessor, hidden from tinygltf
    std::set<int> meshoptFallbacks_;          // buffers that are EXT_meshopt_compression placeholders
    struct UvSet {                            // per glTF material: the TEXCOORD_n its textures read, transformed
        int texCoord = 0;
        glm::mat3 transform{1.0f};            // KHR_texture_transform, applied to the UVs at load
    };
    std::vector<UvSet> materialUv_;

    [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(path_ + ": " + problem); }
    void warn(const std::string& w) { scene_.warnings.push_back(w); }

    // ---- the file (gltf_loader.cpp) ----
    std::vector<unsigned char> readMainFile();
    void checkGlb(const std::vector<unsigned char>& d) const;
    void checkJsonDepth(const unsigned char* p, size_t n) const;
    // Returns the JSON tinygltf is to parse when it had to be changed (Draco indices, meshopt placeholders), else "".
    std::string checkJson(const unsigned char* p, size_t n, bool binary);  // gltf_json_checks.cpp
    std::vector<unsigned char> replacedGlbJson(const std::vector<unsigned char>& glb, const std::string& json) const;
    // Counts `bytes` against the memory budget before they are allocated, or fails naming `what` and the size.
    // kept: they stay for the rest of the load (buffers, the Scene's geometry and images); otherwise they are a
    // transient peak on top of what is kept.
    void reserveMemory(uint64_t bytes, const std::string& what, bool kept);
    void parse();
    void checkExtensions();
    void traverse();

    // ---- buffers, accessors, meshes (gltf_geometry.cpp) ----
    struct Span {  // `count` elements located in a buffer view, every range checked
        const unsigned char* base = nullptr;
        size_t stride = 0;
    };
    Span viewSpan(int viewIndex, size_t byteOffset, size_t count, size_t elemSize, bool allowStride,
                  const std::string& what) const;
    const tinygltf::Accessor& accessor(int index, const std::string& what) const;
    void checkAccessorFits(int index, const std::string& what) const;
    void reserveElements(size_t count, const std::string& what);
    template <class Write>
    void applySparse(const tinygltf::Accessor& acc, const std::string& what, size_t elemSize, Write write);
    std::vector<float> readFloats(int index, int expectedType, std::initializer_list<int> allowed,
                                  bool requireNormalizedInts, bool countTowardsLimit, const std::string& what);
    std::vector<uint32_t> readIndices(int index, const std::string& what);
    uint64_t primitiveBytesBound(const tinygltf::Primitive& prim, int mode) const;
    void addMesh(int meshIndex, const glm::mat4& world);

    // ---- compressed geometry (gltf_compression.cpp): decoded into buffers of their own before meshes are read ----
    int appendBuffer(std::vector<unsigned char>&& bytes, size_t byteStride);  // returns the new buffer view
    void decodeMeshopt();  // EXT_meshopt_compression buffer views
    void decodeDraco();    // KHR_draco_mesh_compression primitives: their accessors get plain float/uint32 views

    // ---- materials and images (gltf_materials.cpp) ----
    int resolveImage(int gi, const std::string& user);
    int resolveTexture(const tinygltf::TextureInfo& info, const std::string& user);
    // The UV set and KHR_texture_transform of a texture reference (an identity, set 0, when it has none).
    UvSet textureUv(const tinygltf::TextureInfo& info, const std::string& user);
    void loadMaterials();

    // ---- animations (gltf_animation.cpp): node TRS channels; skins and morph targets warned about once each ----
    void loadAnimations();

    // ---- cameras and lights (gltf_cameras_lights.cpp) ----
    void addCamera(const tinygltf::Node& node, const glm::mat4& world);
    void addLight(const tinygltf::Node& node, int li, const glm::mat4& world);
};

}  // namespace gltf
}  // namespace deepgi
