// glTF loader, materials: materials, textures, samplers and images.
// Images are decoded here (not by tinygltf) with stb_image, after stbi_info_from_memory has checked the claimed
// dimensions against GltfLoadOptions::maxImagePixels. Only images used by a base-colour or emissive texture are
// decoded. A missing/corrupt/refused image only drops the texture (warning naming the image), so the material falls
// back to its factor colour.
#include "renderer/scene/gltf_reader.h"

#include <stb_image.h>
#include <stb_image_resize.h>

#include <algorithm>
#include <climits>
#include <cmath>

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
    if (size == 0 || size > size_t(INT_MAX)) {
        warn("image '" + name + "' is empty or too large" + fallback);
        return -1;
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp) || w <= 0 || h <= 0) {
        warn("image '" + name + "' is corrupt or in an unsupported format" + fallback);
        return -1;
    }
    if (uint64_t(w) * uint64_t(h) > opt_.maxImagePixels) {
        warn("image '" + name + "' claims " + std::to_string(w) + "x" + std::to_string(h) +
             " pixels, more than the limit of " + std::to_string(opt_.maxImagePixels) + fallback);
        return -1;
    }
    const uint64_t decodedBytes = uint64_t(w) * uint64_t(h) * 4;
    const int limit = std::max(1, opt_.maxTextureSize);
    const bool downscale = w > limit || h > limit;
    // the longer side becomes the limit, the other keeps the aspect ratio (at least 1 texel)
    const auto side = [&](int v, int longest) {
        return v == longest ? limit : std::max(1, int(std::lround(double(v) * limit / double(longest))));
    };
    const int ow = downscale ? side(w, std::max(w, h)) : w, oh = downscale ? side(h, std::max(w, h)) : h;
    const uint64_t keptBytes = uint64_t(ow) * uint64_t(oh) * 4;
    // stb's buffer and our copy (or the downscaled one) exist at once
    reserveMemory(decodedBytes + keptBytes, "image '" + name + "' (" + std::to_string(w) + "x" + std::to_string(h) + ")",
                  false);
    int dw = 0, dh = 0, dc = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &dw, &dh, &dc, 4);
    if (!pixels) {
        const char* why = stbi_failure_reason();
        warn("image '" + name + "' could not be decoded (" + (why ? why : "unknown") + ")" + fallback);
        return -1;
    }
    Image out;
    out.name = name;
    if (downscale && dw == w && dh == h) {
        // Larger than a texture may be: it would render black. Colour textures are sRGB, alpha is linear (channel 3).
        out.rgba8.resize(size_t(keptBytes));
        stbir_resize_uint8_srgb(pixels, dw, dh, 0, out.rgba8.data(), ow, oh, 0, 4, 3, 0);
        warn("image '" + name + "' is " + std::to_string(w) + "x" + std::to_string(h) + ", larger than the " +
             std::to_string(limit) + " texel texture limit; downscaled to " + std::to_string(ow) + "x" +
             std::to_string(oh));
        out.width = ow;
        out.height = oh;
    } else {
        out.width = dw;
        out.height = dh;
        out.rgba8.assign(pixels, pixels + size_t(dw) * size_t(dh) * 4);
    }
    stbi_image_free(pixels);
    reserveMemory(out.rgba8.size(), "image '" + name + "'", true);
    scene_.images.push_back(std::move(out));
    imageMap_[size_t(gi)] = int(scene_.images.size()) - 1;
    return imageMap_[size_t(gi)];
}

int GltfReader::resolveTexture(const tinygltf::TextureInfo& info, const std::string& user) {
    const int ti = info.index;
    if (ti < 0) return -1;
    if (size_t(ti) >= model_.textures.size()) {
        warn(user + ": texture " + std::to_string(ti) + " does not exist; using the fallback colour");
        return -1;
    }
    if (info.texCoord != 0) warn(user + ": texture uses TEXCOORD_" + std::to_string(info.texCoord) +
                                 ", only TEXCOORD_0 is supported");
    if (textureMap_[size_t(ti)] != -2) return textureMap_[size_t(ti)];
    textureMap_[size_t(ti)] = -1;
    const auto& t = model_.textures[size_t(ti)];
    if (t.source < 0) {
        warn(user + ": texture " + std::to_string(ti) + " has no supported image source; using the fallback colour");
        return -1;
    }
    const int img = resolveImage(t.source, user);
    if (img < 0) return -1;
    Texture tex;
    tex.image = img;
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
    textureMap_[size_t(ti)] = int(scene_.textures.size()) - 1;
    return textureMap_[size_t(ti)];
}

void GltfReader::loadMaterials() {
    imageMap_.assign(model_.images.size(), -2);
    textureMap_.assign(model_.textures.size(), -2);
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

}  // namespace gltf
}  // namespace deepgi
