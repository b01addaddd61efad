// glTF loader, materials: materials, textures, samplers and images.
// Images are decoded here (not by tinygltf) by decodeImage (scene_files.h), which checks the claimed dimensions
// against GltfLoadOptions::maxImagePixels first. Only images a material uses are decoded (base colour, emissive,
// metallic-roughness, normal, occlusion; the last three as linear data textures). A missing/corrupt/refused image
// only drops the texture (warning naming the image), so the material falls back to its factors.
#include "renderer/scene/gltf_reader.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <set>

namespace deepgi {
namespace gltf {
namespace {

WrapMode wrapMode(int w) {
    switch (w) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
        default: return WrapMode::Repeat;
    }
}

}  // namespace

// ---- images, textures, materials ----
int GltfReader::resolveImage(int gi, const std::string& user) {
    if (gi < 0 || size_t(gi) >= model_.images.size()) {
        warn(user + ": image " + std::to_string(gi) + " does not exist; using the fallback colour");
        return -1;
    }
    if (imageMap_[size_t(gi)] != -2) return imageMap_[size_t(gi)];
    imageMap_[size_t(gi)] = -1;
    const auto& img = model_.images[size_t(gi)];
    std::string name = !img.uri.empty() ? img.uri : !img.name.empty() ? img.name : "image[" + std::to_string(gi) + "]";
    if (name.compare(0, 5, "data:") == 0) name = "image[" + std::to_string(gi) + "] (data URI)";
    name = printable(name);
    const std::string fallback = "; texture dropped, using the material's fallback colour";

    const unsigned char* bytes = nullptr;
    size_t size = 0;
    if (img.bufferView >= 0) {
        try {
            const auto& v = model_.bufferViews.at(size_t(img.bufferView));
            Span s = viewSpan(img.bufferView, 0, v.byteLength ? 1 : 0, v.byteLength, false, "image");
            bytes = s.base;
            size = v.byteLength;
        } catch (const std::exception&) {
            warn("image '" + name + "': buffer view out of range" + fallback);
            return -1;
        }
    } else if (!img.image.empty()) {
        bytes = img.image.data();
        size = img.image.size();
    } else {
        auto problem = uriProblems_.find(img.uri);
        if (problem != uriProblems_.end())
            warn("image '" + name + "': URI " + problem->second + fallback);
        else if (img.uri.find("../") != std::string::npos || img.uri == ".." || (!img.uri.empty() && img.uri[0] == '/'))
            warn("image '" + name + "' refused: URI escapes the scene folder" + fallback);
        else
            warn("image '" + name + "' is missing or could not be read" + fallback);
        return -1;
    }
    Image out;
    const std::string why = decodeImage(bytes, size, name, opt_, budget_, out, scene_.warnings);
    if (!why.empty()) {
        warn("image '" + name + "' " + why + fallback);
        return -1;
    }
    scene_.images.push_back(std::move(out));
    imageMap_[size_t(gi)] = int(scene_.images.size()) - 1;
    return imageMap_[size_t(gi)];
}

int GltfReader::resolveTexture(int ti, const std::string& user, bool srgb) {
    if (ti < 0) return -1;
    if (size_t(ti) >= model_.textures.size()) {
        warn(user + ": texture " + std::to_string(ti) + " does not exist; using the fallback colour");
        return -1;
    }
    std::vector<int>& map = srgb ? textureMap_ : linearTextureMap_;
    if (map[size_t(ti)] != -2) return map[size_t(ti)];
    map[size_t(ti)] = -1;
    const auto& t = model_.textures[size_t(ti)];
    if (t.source < 0) {
        warn(user + ": texture " + std::to_string(ti) + " has no supported image source; using the fallback colour");
        return -1;
    }
    const int img = resolveImage(t.source, user);
    if (img < 0) return -1;
    Texture tex;
    tex.image = img;
    tex.srgb = srgb;
    if (t.sampler >= 0 && size_t(t.sampler) < model_.samplers.size()) {
        const auto& s = model_.samplers[size_t(t.sampler)];
        tex.wrapS = wrapMode(s.wrapS);
        tex.wrapT = wrapMode(s.wrapT);
        tex.magFilter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? FilterMode::Nearest : FilterMode::Linear;
        tex.mipmaps = !(s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST || s.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR);
    } else if (t.sampler >= 0) {
        warn(user + ": sampler " + std::to_string(t.sampler) + " does not exist; using defaults");
    }
    scene_.textures.push_back(tex);
    map[size_t(ti)] = int(scene_.textures.size()) - 1;
    return map[size_t(ti)];
}

GltfReader::UvSet GltfReader::textureUv(int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& user) {
    UvSet u;
    u.texCoord = std::max(0, texCoord);
    auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end() || !it->second.IsObject()) return u;
    const tinygltf::Value& t = it->second;
    auto number = [&](const tinygltf::Value& v, double fallback, bool& ok) {
        if (!v.IsNumber()) { ok = false; return fallback; }
        const double d = v.GetNumberAsDouble();
        if (!std::isfinite(d)) { ok = false; return fallback; }
        return d;
    };
    bool ok = true;
    glm::vec2 offset(0.0f), scale(1.0f);
    double rotation = 0.0;
    for (const char* key : {"offset", "scale"}) {
        if (!t.Has(key)) continue;
        const tinygltf::Value& a = t.Get(key);
        glm::vec2& dst = key[0] == 'o' ? offset : scale;
        if (!a.IsArray() || a.ArrayLen() != 2) { ok = false; continue; }
        for (int c = 0; c < 2; ++c) dst[c] = float(number(a.Get(c), dst[c], ok));
    }
    if (t.Has("rotation")) rotation = number(t.Get("rotation"), 0.0, ok);
    if (t.Has("texCoord")) {
        const double tc = number(t.Get("texCoord"), 0.0, ok);
        if (tc >= 0.0 && tc < 8.0 && tc == std::floor(tc)) u.texCoord = int(tc);
        else ok = false;
    }
    if (!ok) warn(user + ": KHR_texture_transform has a missing or invalid value; those values use their defaults");
    // The extension's matrix, translation * rotation * scale (columns). The rotation is counter-clockwise in glTF's
    // V-down uv space, u' = cos u + sin v, as the sample model TextureTransformTest and Blender, Babylon.js and
    // three.js have it; the spec's GLSL listing has the opposite sign (KhronosGroup/glTF issue 1563).
    const float c = float(std::cos(rotation)), s = float(std::sin(rotation));
    const glm::mat3 T(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(offset, 1));
    const glm::mat3 R(glm::vec3(c, -s, 0), glm::vec3(s, c, 0), glm::vec3(0, 0, 1));
    const glm::mat3 S(glm::vec3(scale.x, 0, 0), glm::vec3(0, scale.y, 0), glm::vec3(0, 0, 1));
    u.transform = T * R * S;
    return u;
}

void GltfReader::loadMaterials() {
    imageMap_.assign(model_.images.size(), -2);
    materialUv_.clear();
    textureMap_.assign(model_.textures.size(), -2);
    linearTextureMap_.assign(model_.textures.size(), -2);
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const auto& gm = model_.materials[i];
        Material m;
        m.name = gm.name.empty() ? "material" + std::to_string(i) : gm.name;
        const std::string user = "material '" + m.name + "'";
        const auto& bcf = gm.pbrMetallicRoughness.baseColorFactor;
        for (int c = 0; c < 4 && size_t(c) < bcf.size(); ++c) m.baseColorFactor[c] = float(bcf[size_t(c)]);  // validateMaterial
        m.baseColorTexture = resolveTexture(gm.pbrMetallicRoughness.baseColorTexture, user);
        float strength = 1.0f;
        auto it = gm.extensions.find("KHR_materials_emissive_strength");
        if (it != gm.extensions.end() && it->second.IsObject() && it->second.Has("emissiveStrength")) {
            const auto& v = it->second.Get("emissiveStrength");
            if (v.IsNumber()) strength = std::max(0.0f, finiteOr(v.GetNumberAsDouble(), 1.0f));
        }
        for (int c = 0; c < 3 && size_t(c) < gm.emissiveFactor.size(); ++c)
            m.emissiveFactor[c] = float(gm.emissiveFactor[size_t(c)]) * strength;  // validateMaterial
        m.emissiveTexture = resolveTexture(gm.emissiveTexture, user);
        // One UV set per primitive (Vertex::uv), transformed at load: the base colour's, else the emissive's.
        const UvSet base = textureUv(gm.pbrMetallicRoughness.baseColorTexture, user + " base colour texture");
        const UvSet emissive = textureUv(gm.emissiveTexture, user + " emissive texture");
        if (m.baseColorTexture >= 0 && m.emissiveTexture >= 0 &&
            (base.texCoord != emissive.texCoord || base.transform != emissive.transform))
            warn(user + ": the emissive texture's UV set or KHR_texture_transform differs from the base colour "
                        "texture's; both are sampled with the base colour's");
        UvSet uv = m.baseColorTexture >= 0 ? base : m.emissiveTexture >= 0 ? emissive : UvSet{};
        loadPbrTextures(gm, m, uv, m.baseColorTexture >= 0 || m.emissiveTexture >= 0, user);
        materialUv_.push_back(uv);
        m.alphaCutoff = finiteOr(gm.alphaCutoff, 0.5f);
        if (gm.alphaMode == "MASK") {
            m.alphaMode = AlphaMode::Mask;
        } else if (gm.alphaMode == "BLEND") {
            m.alphaMode = AlphaMode::Mask;
            warn(user + ": alphaMode BLEND is not supported, rendered as MASK (cutoff " +
                 std::to_string(m.alphaCutoff) + ")");
        } else if (!gm.alphaMode.empty() && gm.alphaMode != "OPAQUE") {
            warn(user + ": unknown alphaMode '" + gm.alphaMode + "', treated as OPAQUE");
        }
        m.doubleSided = gm.doubleSided;
        scene_.materials.push_back(std::move(m));
    }
}

void GltfReader::loadPbrTextures(const tinygltf::Material& gm, Material& m, UvSet& uv, bool uvChosen,
                                 const std::string& user) {
    const auto& pbr = gm.pbrMetallicRoughness;
    m.metallic = finiteOr(pbr.metallicFactor, 1.0f);    // validateMaterial clamps to [0, 1]
    m.roughness = finiteOr(pbr.roughnessFactor, 1.0f);
    m.dielectricF0 = 0.04f;                             // glTF: a dielectric's ior is 1.5
    // KHR_materials_specular's scalar strength (what saveGltf writes for a Lambertian material: factor 0); its
    // colour and textures are not modelled and say so.
    auto spec = gm.extensions.find("KHR_materials_specular");
    if (spec != gm.extensions.end() && spec->second.IsObject()) {
        const auto& e = spec->second;
        if (e.Has("specularFactor") && e.Get("specularFactor").IsNumber())
            m.dielectricF0 = 0.04f * std::clamp(finiteOr(e.Get("specularFactor").GetNumberAsDouble(), 1.0f), 0.0f, 1.0f);
        if (e.Has("specularColorFactor") || e.Has("specularTexture") || e.Has("specularColorTexture"))
            warn(user + ": KHR_materials_specular's colour and textures are ignored (only specularFactor is used)");
    }
    m.metallicRoughnessTexture = resolveTexture(pbr.metallicRoughnessTexture.index, user, false);
    m.normalTexture = resolveTexture(gm.normalTexture.index, user, false);
    m.normalScale = finiteOr(gm.normalTexture.scale, 1.0f);
    m.occlusionTexture = resolveTexture(gm.occlusionTexture.index, user, false);
    m.occlusionStrength = finiteOr(gm.occlusionTexture.strength, 1.0f);
    // One UV set per primitive (Vertex::uv): a texture on another set or transform is sampled with the chosen one.
    const struct { int texture; int texCoord; const tinygltf::ExtensionMap& ext; const char* what; } refs[] = {
        {m.metallicRoughnessTexture, pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions,
         "metallic-roughness"},
        {m.normalTexture, gm.normalTexture.texCoord, gm.normalTexture.extensions, "normal"},
        {m.occlusionTexture, gm.occlusionTexture.texCoord, gm.occlusionTexture.extensions, "occlusion"}};
    for (const auto& r : refs) {
        if (r.texture < 0) continue;
        const UvSet u = textureUv(r.texCoord, r.ext, user + " " + r.what + " texture");
        if (!uvChosen) {
            uv = u;
            uvChosen = true;
        } else if (u.texCoord != uv.texCoord || u.transform != uv.transform) {
            warn(user + ": the " + std::string(r.what) + " texture's UV set or KHR_texture_transform differs from the "
                        "material's other textures; it is sampled with theirs");
        }
    }
}

void GltfReader::warnIgnoredMaterialExtensions() {
    // Material extensions (KHR_materials_*, the old spec-gloss one) deepgi does not implement: one warning each per
    // file, naming the first material that uses it (the others render with the core model alike).
    std::set<std::string> seen;
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const auto& gm = model_.materials[i];
        for (const auto& [ext, value] : gm.extensions) {
            (void)value;
            if (supportedExtensions().count(ext) || !seen.insert(ext).second) continue;
            const std::string name = gm.name.empty() ? "material" + std::to_string(i) : gm.name;
            warn(printable(std::filesystem::path(path_).filename().string()) + ": material '" + printable(name) + "' uses " + printable(ext) +
                 ", which deepgi ignores");
        }
    }
}

}  // namespace gltf
}  // namespace deepgi
