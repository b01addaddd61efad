#pragma once
// Internal to the glTF loader: the reader class whose methods are split by what they read:
//   gltf_loader.cpp        the file itself (GLB, JSON checks, URIs confined to the folder), the node hierarchy
//   gltf_geometry.cpp      buffers, buffer views, accessors (sparse included) and mesh primitives
//   gltf_materials.cpp     materials, textures, samplers and images
//   gltf_cameras_lights.cpp cameras and KHR_lights_punctual
// Only the loader's .cpp files include this header; everyone else uses gltf_loader.h.
#include "renderer/scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <map>
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

inline float finiteOr(double v, float fallback) { return std::isfinite(v) ? float(v) : fallback; }
inline bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Reads one glTF file into a Scene. Every method that finds the file unusable throws SceneLoadError via fail().
class GltfReader {
public:
    GltfReader(const std::string& path, const GltfLoadOptions& opt) : path_(path), opt_(opt) {}
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
    uint64_t usedBytes_ = 0, peakBytes_ = 0;  // counted against GltfLoadOptions::memoryBudget
    std::vector<uint32_t> meshInstances_;     // glTF mesh -> instances placed so far (for messages)

    [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(path_ + ": " + problem); }
    void warn(const std::string& w) { scene_.warnings.push_back(w); }

    // ---- the file (gltf_loader.cpp) ----
    std::vector<unsigned char> readMainFile();
    void checkGlb(const std::vector<unsigned char>& d) const;
    void checkJsonDepth(const unsigned char* p, size_t n) const;
    void checkJson(const unsigned char* p, size_t n, bool binary);  // gltf_json_checks.cpp
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

    // ---- materials and images (gltf_materials.cpp) ----
    int resolveImage(int gi, const std::string& user);
    int resolveTexture(const tinygltf::TextureInfo& info, const std::string& user);
    void loadMaterials();

    // ---- cameras and lights (gltf_cameras_lights.cpp) ----
    void addCamera(const tinygltf::Node& node, const glm::mat4& world);
    void addLight(const tinygltf::Node& node, int li, const glm::mat4& world);
};

}  // namespace gltf
}  // namespace deepgi
