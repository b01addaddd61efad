// OBJ + MTL loader through tinyobjloader (Debian's libtinyobjloader-dev). tinyobjloader parses; this file confines
// what it opens to the scene folder (a MaterialReader of our own reads the MTL files), counts memory, checks every
// index (tinyobjloader only warns about out-of-range ones) and turns the materials into the renderer's model.
#include "renderer/scene/obj_loader.h"

#include "renderer/scene/scene_files.h"
#include "renderer/scene/scene_validation.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>

namespace deepgi {
namespace {

std::string oneLine(const std::string& s) {
    std::string out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
    }
    return out;
}

// A texture or library name as the file writes it -> a path relative to the scene folder ('\' is a separator:
// Crytek Sponza's MTL uses Windows paths).
std::string normalisedPath(std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    while (name.compare(0, 2, "./") == 0) name.erase(0, 2);
    return name;
}

// What tinyobjloader would allocate for the file, from a quick scan of its lines (an upper bound: every 'f' line's
// corners and the triangles its fan makes), so the budget is checked before tinyobjloader parses.
struct ObjCounts {
    uint64_t v = 0, vn = 0, vt = 0, faces = 0, corners = 0, triangles = 0;
    uint64_t parseBytes() const {
        // attrib: xyz + w + rgb per v, 3 per vn, uvw per vt (floats); faces: 3 ints per corner plus per-face vectors;
        // shapes: 3 ints per triangle corner and 9 bytes of per-face arrays.
        return v * 28 + vn * 12 + vt * 12 + corners * 12 + faces * 48 + triangles * (36 + 9);
    }
};

ObjCounts scanObj(const std::vector<unsigned char>& d) {
    ObjCounts c;
    size_t i = 0;
    const size_t n = d.size();
    while (i < n) {
        while (i < n && (d[i] == ' ' || d[i] == '\t')) ++i;
        const size_t start = i;
        while (i < n && d[i] != '\n') ++i;
        const size_t end = i++;
        if (end - start < 2) continue;
        const unsigned char a = d[start], b = d[start + 1];
        if (a == 'v' && (b == ' ' || b == '\t')) ++c.v;
        else if (a == 'v' && b == 'n') ++c.vn;
        else if (a == 'v' && b == 't') ++c.vt;
        else if (a == 'f' && (b == ' ' || b == '\t')) {
            uint64_t k = 0;
            bool inToken = false;
            for (size_t j = start + 1; j < end; ++j) {
                const bool space = d[j] == ' ' || d[j] == '\t' || d[j] == '\r';
                if (!space && !inToken) ++k;
                inToken = !space;
            }
            ++c.faces;
            c.corners += k;
            if (k >= 3) c.triangles += k - 2;
        }
    }
    return c;
}

// Reads the MTL libraries named by `mtllib` through the scene folder's checks (tinyobjloader's own reader would open
// any path, FIFOs included).
class FolderMaterialReader : public tinyobj::MaterialReader {
public:
    FolderMaterialReader(const SceneFolder& folder, LoadBudget& budget, std::vector<std::string>& warnings)
        : folder_(folder), budget_(budget), warnings_(warnings) {}
    bool operator()(const std::string& matId, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn, std::string* err) override {
        const std::string rel = normalisedPath(matId);
        std::vector<unsigned char> bytes;
        const std::string why = folder_.read(rel, bytes);
        if (!why.empty()) {
            warnings_.push_back("material library '" + rel + "' " + why + "; its materials fall back to white");
            return false;
        }
        budget_.reserve(bytes.size() * 2, "material library '" + rel + "'", false);
        std::istringstream in(std::string(bytes.begin(), bytes.end()));
        starts.emplace_back(materials->size(), std::filesystem::path(rel).parent_path().string());
        tinyobj::LoadMtl(matMap, materials, &in, warn, err);
        return true;
    }
    // (first material index, folder of its library relative to the scene folder) per library read
    std::vector<std::pair<size_t, std::string>> starts;

private:
    const SceneFolder& folder_;
    LoadBudget& budget_;
    std::vector<std::string>& warnings_;
};

class ObjReader {
public:
    ObjReader(const std::string& path, const GltfLoadOptions& opt)
        : path_(path), opt_(opt), folder_(path), budget_(path, opt.memoryBudget) {}
    Scene run();

private:
    std::string path_;
    GltfLoadOptions opt_;
    SceneFolder folder_;
    LoadBudget budget_;
    Scene scene_;
    std::map<std::string, int> images_;     // normalised path -> Scene::images index (-1 unusable)
    std::map<std::string, int> textures_;   // image key -> Scene::textures index
    std::map<std::string, std::vector<std::string>> unsupported_;  // feature -> material names

    [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(path_ + ": " + problem); }
    void warn(const std::string& w) { scene_.warnings.push_back(w); }
    std::string mtlDir_;  // folder of the library of the material being read ("" = the OBJ's)
    std::string texturePath(const std::string& name) const;
    int image(const std::string& rel, const std::string& user);
    int texture(const std::string& key, int image, bool clamp);
    int maskedImage(int colour, int mask, const std::string& user);
    Material material(const tinyobj::material_t& m);
};

// A texture named in a library: relative to the library's folder when it is there, else to the OBJ's.
std::string ObjReader::texturePath(const std::string& name) const {
    const std::string rel = normalisedPath(name);
    if (mtlDir_.empty()) return rel;
    const std::string nearLibrary = (std::filesystem::path(mtlDir_) / rel).lexically_normal().string();
    std::error_code ec;
    return std::filesystem::exists(std::filesystem::path(folder_.dir()) / nearLibrary, ec) ? nearLibrary : rel;
}

int ObjReader::image(const std::string& rel, const std::string& user) {
    auto it = images_.find(rel);
    if (it != images_.end()) return it->second;  // one warning per file, however many materials use it
    images_[rel] = -1;
    std::vector<unsigned char> bytes;
    std::string why = folder_.read(rel, bytes);
    Image img;
    if (why.empty()) why = decodeImage(bytes.data(), bytes.size(), rel, opt_, budget_, img, scene_.warnings);
    if (!why.empty()) {
        warn("texture '" + rel + "' (" + user + ") " + why + "; dropped, using the material's colour");
        return -1;
    }
    scene_.images.push_back(std::move(img));
    return images_[rel] = int(scene_.images.size()) - 1;
}

int ObjReader::texture(const std::string& key, int img, bool clamp) {
    const std::string k = key + (clamp ? "|clamp" : "");
    auto it = textures_.find(k);
    if (it != textures_.end()) return it->second;
    Texture t;
    t.image = img;
    if (clamp) t.wrapS = t.wrapT = WrapMode::ClampToEdge;
    scene_.textures.push_back(t);
    return textures_[k] = int(scene_.textures.size()) - 1;
}

// The colour image (or white where there is none) with its alpha replaced by the mask's luminance times the mask's
// alpha, the mask sampled at the nearest texel of the colour image's grid.
int ObjReader::maskedImage(int colour, int mask, const std::string& user) {
    const Image& m = scene_.images[size_t(mask)];
    const int w = colour >= 0 ? scene_.images[size_t(colour)].width : m.width;
    const int h = colour >= 0 ? scene_.images[size_t(colour)].height : m.height;
    budget_.reserve(uint64_t(w) * uint64_t(h) * 4, "alpha-masked copy of a texture (" + user + ")", true);
    Image out;
    out.name = (colour >= 0 ? scene_.images[size_t(colour)].name : std::string("white")) + " masked by " + m.name;
    out.width = w;
    out.height = h;
    if (colour >= 0) out.rgba8 = scene_.images[size_t(colour)].rgba8;
    else out.rgba8.assign(size_t(w) * size_t(h) * 4, 255);
    for (int y = 0; y < h; ++y) {
        const int my = std::min(m.height - 1, int((y + 0.5) * m.height / h));
        for (int x = 0; x < w; ++x) {
            const int mx = std::min(m.width - 1, int((x + 0.5) * m.width / w));
            const uint8_t* p = &m.rgba8[(size_t(my) * size_t(m.width) + size_t(mx)) * 4];
            const double lum = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            out.rgba8[(size_t(y) * size_t(w) + size_t(x)) * 4 + 3] = uint8_t(std::lround(lum * p[3] / 255.0));
        }
    }
    scene_.images.push_back(std::move(out));
    return int(scene_.images.size()) - 1;
}

Material ObjReader::material(const tinyobj::material_t& om) {
    Material m;
    m.name = om.name;
    const std::string user = "material '" + m.name + "'";
    m.baseColorFactor = glm::vec4(om.diffuse[0], om.diffuse[1], om.diffuse[2], om.dissolve);  // validateMaterial clamps
    m.emissiveFactor = glm::vec3(om.emission[0], om.emission[1], om.emission[2]);
    m.doubleSided = true;
    const std::string colourPath = texturePath(om.diffuse_texname), maskPath = texturePath(om.alpha_texname);
    const int colour = om.diffuse_texname.empty() ? -1 : image(colourPath, user + " map_Kd");
    const int mask = om.alpha_texname.empty() ? -1 : image(maskPath, user + " map_d");
    const bool clamp = om.diffuse_texopt.clamp;
    if (mask >= 0) {
        const std::string key = colourPath + "|mask:" + maskPath;
        auto it = textures_.find(key + (clamp ? "|clamp" : ""));
        m.baseColorTexture = it != textures_.end() ? it->second : texture(key, maskedImage(colour, mask, user), clamp);
        m.alphaMode = AlphaMode::Mask;
    } else if (colour >= 0) {
        m.baseColorTexture = texture(colourPath, colour, clamp);
    }
    if (!om.emissive_texname.empty()) {
        const std::string emissivePath = texturePath(om.emissive_texname);
        const int e = image(emissivePath, user + " map_Ke");
        if (e >= 0) {
            m.emissiveTexture = texture(emissivePath, e, om.emissive_texopt.clamp);
            if (!m.emissive()) m.emissiveFactor = glm::vec3(1.0f);  // map_Ke without Ke: the map is the emission
        }
    }
    if (om.dissolve < 1.0f) {
        m.alphaMode = AlphaMode::Mask;
        if (om.dissolve > 0.0f) unsupported_["partial transparency (d between 0 and 1; a mask with cutoff 0.5)"].push_back(m.name);
    }
    const auto nonDefault = [](const tinyobj::texture_option_t& t) {
        return t.origin_offset[0] != 0 || t.origin_offset[1] != 0 || t.scale[0] != 1 || t.scale[1] != 1;
    };
    if (nonDefault(om.diffuse_texopt) || nonDefault(om.alpha_texopt)) unsupported_["texture options -o/-s (ignored)"].push_back(m.name);
    if (!om.bump_texname.empty() || !om.normal_texname.empty() || !om.displacement_texname.empty())
        unsupported_["bump, normal and displacement maps (bump, map_bump, norm, disp)"].push_back(m.name);
    if (om.specular[0] > 0 || om.specular[1] > 0 || om.specular[2] > 0 || !om.specular_texname.empty())
        unsupported_["specular reflection (Ks, map_Ks; rendered diffuse)"].push_back(m.name);
    if (om.illum == 4 || om.illum == 6 || om.illum == 7 || om.illum == 9)
        unsupported_["refraction (illum " + std::to_string(om.illum) + ")"].push_back(m.name);
    if (!om.roughness_texname.empty() || !om.metallic_texname.empty() || om.metallic > 0)
        unsupported_["PBR metallic/roughness (Pm, Pr, map_Pm, map_Pr)"].push_back(m.name);
    return m;
}

Scene ObjReader::run() {
    scene_.sourcePath = path_;
    opt_.report("reading", 0.0);  // the file, then tinyobjloader's parse and the MTL's textures
    std::vector<unsigned char> data = readSceneFile(path_, "an OBJ");
    budget_.reserve(data.size(), "the file itself", true);
    const ObjCounts counts = scanObj(data);
    if (counts.corners > opt_.maxElements || counts.triangles * 3 > opt_.maxElements)
        fail(std::to_string(counts.triangles) + " triangles overflow the limit of " + std::to_string(opt_.maxElements) +
             " vertices + indices per file");
    // tinyobjloader's arrays, then ours: every corner its own vertex at worst, an index each, the dedup table.
    const uint64_t parseBytes = counts.parseBytes();
    const uint64_t convertBytes = counts.triangles * 3 * (sizeof(Vertex) + 4 + 48);
    budget_.reserve(parseBytes + convertBytes, "parsing " + std::to_string(counts.triangles) + " triangles", false);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnText, errText;
    FolderMaterialReader mtl(folder_, budget_, scene_.warnings);
    bool ok = false;
    {
        std::istringstream in(std::string(data.begin(), data.end()));
        std::vector<unsigned char>().swap(data);
        ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnText, &errText, &in, &mtl, /*triangulate=*/true,
                              /*default_vcols_fallback=*/false);
    }
    if (!ok) fail("OBJ parse error: " + (errText.empty() ? std::string("unknown error") : oneLine(errText)));
    {
        // tinyobjloader's warnings, one per line; its "Both `d` and `Tr`" note (3ds Max writes both on every
        // material) becomes one warning for all the materials it names.
        std::istringstream in(warnText + errText);
        std::string line;
        std::vector<std::string> bothDTr;
        while (std::getline(in, line)) {
            while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
            if (line.empty()) continue;
            const size_t q0 = line.find("for \""), q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 5);
            if (line.find("Both `d` and `Tr`") != std::string::npos && q1 != std::string::npos)
                bothDTr.push_back(line.substr(q0 + 5, q1 - q0 - 5));
            else
                warn("tinyobjloader: " + line);
        }
        if (!bothDTr.empty()) {
            std::string list;
            for (size_t i = 0; i < bothDTr.size() && i < 6; ++i) list += (i ? ", " : "") + bothDTr[i];
            if (bothDTr.size() > 6) list += ", ... (" + std::to_string(bothDTr.size()) + " materials)";
            warn("both d and Tr given (d is used) in " + list);
        }
    }

    for (size_t i = 0; i < materials.size(); ++i) {
        mtlDir_.clear();
        for (const auto& [first, dir] : mtl.starts)
            if (first <= i) mtlDir_ = dir;
        scene_.materials.push_back(material(materials[i]));
    }
    for (const auto& [feature, names] : unsupported_) {
        std::string list;
        for (size_t i = 0; i < names.size() && i < 6; ++i) list += (i ? ", " : "") + names[i];
        if (names.size() > 6) list += ", ... (" + std::to_string(names.size()) + " materials)";
        warn("unsupported MTL feature: " + feature + ", in " + list);
    }

    const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3, nt = attrib.texcoords.size() / 2;
    uint64_t skipped = 0;
    opt_.report("meshes", 0.6);
    for (const auto& shape : shapes) {
        opt_.report("meshes", 0.6 + 0.4 * double(&shape - shapes.data()) / double(shapes.size()));
        const auto& mesh = shape.mesh;
        const std::string shapeName = shape.name.empty() ? "object" + std::to_string(&shape - shapes.data()) : shape.name;
        if (mesh.num_face_vertices.size() != mesh.material_ids.size() || mesh.indices.size() != mesh.num_face_vertices.size() * 3)
            fail("object '" + shapeName + "': faces could not be triangulated");
        // One part per material used by the shape, in the order of first use.
        std::map<int, size_t> partOf;
        std::vector<MeshPart> parts;
        std::vector<std::unordered_map<uint64_t, uint32_t>> dedup;
        for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            int mat = mesh.material_ids[f];
            if (mat >= int(scene_.materials.size())) mat = -1;
            auto [it, fresh] = partOf.emplace(mat, parts.size());
            if (fresh) {
                parts.emplace_back();
                parts.back().name = shapeName + (mat >= 0 ? "/" + scene_.materials[size_t(mat)].name : std::string());
                parts.back().material = mat;
                dedup.emplace_back();
            }
            MeshPart& part = parts[it->second];
            Vertex corner[3];
            bool hasNormal[3];
            uint64_t key[3];
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& ix = mesh.indices[f * 3 + size_t(k)];
                if (ix.vertex_index < 0 || size_t(ix.vertex_index) >= nv)
                    fail("object '" + shapeName + "', face " + std::to_string(f + 1) + ": vertex index out of range (" +
                         std::to_string(nv) + " vertices)");
                if (ix.normal_index >= 0 && size_t(ix.normal_index) >= nn)
                    fail("object '" + shapeName + "', face " + std::to_string(f + 1) + ": normal index out of range (" +
                         std::to_string(nn) + " normals)");
                if (ix.texcoord_index >= 0 && size_t(ix.texcoord_index) >= nt)
                    fail("object '" + shapeName + "', face " + std::to_string(f + 1) +
                         ": texture coordinate index out of range (" + std::to_string(nt) + " coordinates)");
                const size_t vi = size_t(ix.vertex_index);
                Vertex& v = corner[k];
                v.position = glm::vec3(attrib.vertices[vi * 3], attrib.vertices[vi * 3 + 1], attrib.vertices[vi * 3 + 2]);
                v.uv = glm::vec2(0.0f);
                if (ix.texcoord_index >= 0) {
                    const size_t ti = size_t(ix.texcoord_index);
                    // OBJ's v runs up from the bottom of the image; the Scene's uv (0,0) is its top-left (glTF).
                    v.uv = glm::vec2(attrib.texcoords[ti * 2], 1.0f - attrib.texcoords[ti * 2 + 1]);
                    if (!std::isfinite(v.uv.x) || !std::isfinite(v.uv.y)) v.uv = glm::vec2(0.0f);
                }
                hasNormal[k] = false;
                if (ix.normal_index >= 0) {
                    const size_t ni = size_t(ix.normal_index);
                    const glm::vec3 n(attrib.normals[ni * 3], attrib.normals[ni * 3 + 1], attrib.normals[ni * 3 + 2]);
                    const float len = glm::length(n);
                    if (len > 1e-20f && std::isfinite(len)) {
                        v.normal = n / len;
                        hasNormal[k] = true;
                    }
                }
                key[k] = (uint64_t(uint32_t(ix.vertex_index)) << 40) ^ (uint64_t(uint32_t(ix.normal_index + 1)) << 20) ^
                         uint64_t(uint32_t(ix.texcoord_index + 1));
            }
            const glm::vec3 &a = corner[0].position, &b = corner[1].position, &c = corner[2].position;
            if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) {
                ++skipped;
                continue;
            }
            glm::vec3 fn = glm::cross(b - a, c - a);
            const float fl = glm::length(fn);
            fn = (fl > 0.0f && std::isfinite(fl)) ? fn / fl : glm::vec3(0.0f, 0.0f, 1.0f);
            for (int k = 0; k < 3; ++k) {
                if (!hasNormal[k]) {  // a per-triangle copy carrying the flat face normal
                    corner[k].normal = fn;
                    part.indices.push_back(uint32_t(part.vertices.size()));
                    part.vertices.push_back(corner[k]);
                    continue;
                }
                // the key packs 24/20/20 bits; a collision would only merge equal-looking corners, so compare them
                auto& table = dedup[it->second];
                auto found = table.find(key[k]);
                if (found != table.end()) {
                    const Vertex& o = part.vertices[found->second];
                    if (o.position == corner[k].position && o.normal == corner[k].normal && o.uv == corner[k].uv) {
                        part.indices.push_back(found->second);
                        continue;
                    }
                }
                table[key[k]] = uint32_t(part.vertices.size());
                part.indices.push_back(uint32_t(part.vertices.size()));
                part.vertices.push_back(corner[k]);
            }
        }
        int shapeNode = -1;  // one node per OBJ object, drawing its parts (one per material)
        for (auto& part : parts) {
            if (part.indices.empty()) continue;
            if (shapeNode < 0) shapeNode = scene_.addNode(shapeName);
            part.node = shapeNode;
            budget_.reserve(part.vertices.size() * sizeof(Vertex) + part.indices.size() * 4, "object '" + part.name + "'", true);
            part.vertices.shrink_to_fit();
            part.indices.shrink_to_fit();
            scene_.parts.push_back(std::move(part));
        }
    }
    if (skipped > 0) warn("skipped " + std::to_string(skipped) + " triangle(s) with NaN/Inf vertex positions");
    if (scene_.parts.empty()) warn("the file has no faces");
    validateScene(scene_);
    scene_.ensureNodes();
    scene_.computeBounds();
    scene_.loadPeakBytes = budget_.peak();
    opt_.report("done", 1.0);
    return std::move(scene_);
}

}  // namespace

Scene loadObj(const std::string& path, const GltfLoadOptions& options) {
    ObjReader reader(path, options);
    return runSceneReader(path, reader);
}

}  // namespace deepgi
