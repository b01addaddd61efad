// glTF 2.0 loader: tinygltf parses the JSON and fetches buffers; everything that indexes into the data (accessors,
// buffer views, indices, node links, images) is validated by the reader, because tinygltf 2.7 trusts most of it.
// This file reads the file itself and the node hierarchy; see gltf_reader.h for where the rest lives.
//
// Decisions worth knowing:
//  * External URIs must stay inside the scene's folder: a URI that is absolute or has a ".." component is refused.
//    For a buffer that is an error (the geometry is unusable); for an image it is a warning and the texture is
//    dropped, so the material falls back to its factor colour.
//  * The node hierarchy must be a strict tree (glTF requirement): a node reached twice (cycle or shared child) is an
//    error, which also rules out exponential blow-up from DAG-shaped hierarchies.
#include "renderer/scene/gltf_reader.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "renderer/core/settings.h"
#include "renderer/scene/scene_files.h"
#include "renderer/scene/scene_validation.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace deepgi {
namespace gltf {
namespace {

namespace fs = std::filesystem;

// tinygltf's error text on one line, each of its lines shortened (it quotes whole data URIs).
std::string trimmed(const std::string& s) {
    std::string out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty()) out += (out.empty() ? "" : "; ") + printable(line);
    }
    return out;
}

std::vector<std::string> splitLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) if (!line.empty()) out.push_back(line);
    return out;
}

// ---- file system callbacks: confine external URIs to the scene's folder (scene_files.h) ----
struct FsContext {
    explicit FsContext(const std::string& scenePath) : folder(scenePath) {}
    SceneFolder folder;
    std::map<std::string, std::string> problems;  // URI (relative to the folder) -> why it was not read
    void record(const std::string& rel, const std::string& why) { problems.emplace(rel, why); }
};

// Returns true when `full` (as joined by tinygltf: folder + "/" + uri) may be read: inside the folder as written
// and after symlinks are resolved, and a regular file (or absent). Records why not.
bool insideBase(const std::string& full, FsContext* ctx, bool record) {
    const std::string& dir = ctx->folder.dir();
    const std::string prefix = dir == "/" ? dir : dir + "/";
    if (full.compare(0, prefix.size(), prefix) != 0) return false;  // e.g. tinygltf's "./uri" fallback
    const std::string rel = full.substr(prefix.size());
    const std::string why = ctx->folder.problem(rel);
    if (!why.empty()) {
        if (record) ctx->record(rel, why);
        return false;
    }
    return true;
}

bool fsFileExists(const std::string& path, void* user) {
    auto* ctx = static_cast<FsContext*>(user);
    if (!insideBase(path, ctx, true)) return false;
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

std::string fsExpand(const std::string& path, void*) { return path; }

bool fsReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* ctx = static_cast<FsContext*>(user);
    if (!insideBase(path, ctx, true) || !nonRegularKind(path).empty()) {  // never open a FIFO: it would block
        if (err) *err += "refused: " + printable(path) + "\n";
        return false;
    }
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) {
        if (err) *err += "cannot open " + printable(path) + "\n";
        return false;
    }
    std::streamoff size = f.tellg();
    if (size < 0 || uint64_t(size) > uint64_t(INT_MAX)) {
        if (err) *err += "file too large: " + printable(path) + "\n";
        return false;
    }
    out->resize(size_t(size));
    f.seekg(0);
    if (size > 0 && !f.read(reinterpret_cast<char*>(out->data()), size)) {
        if (err) *err += "read error: " + printable(path) + "\n";
        return false;
    }
    return true;
}

bool fsWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not supported by the loader\n";
    return false;
}

// Image callback: never decodes and never fails. URI/data-URI images get their encoded bytes stored (as_is);
// buffer-view images are left alone (tinygltf hands us an unchecked pointer for those) and read after parsing.
bool imageCallback(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                   const unsigned char* bytes, int size, void*) {
    if (image->bufferView < 0 && bytes && size > 0) {
        image->image.assign(bytes, bytes + size);
        image->as_is = true;
    }
    return true;
}

uint32_t le32(const unsigned char* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

Transform localTransform(const tinygltf::Node& n, bool* sheared);

glm::mat4 localMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        glm::mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = float(n.matrix[size_t(c * 4 + r)]);
        return m;
    }
    bool sheared = false;  // only a matrix can be sheared
    return localTransform(n, &sheared).matrix();  // the same products as Transform::matrix(), bit for bit
}

// The node's local transform as TRS: the file's own TRS (rotation normalised), or its matrix
// decomposed (a sheared matrix loses its shear: *sheared is set).
Transform localTransform(const tinygltf::Node& n, bool* sheared) {
    Transform t;
    *sheared = false;
    if (n.matrix.size() == 16) {
        const glm::mat4 m = localMatrix(n);
        t.translation = glm::vec3(m[3]);
        glm::mat3 r(m);
        for (int k = 0; k < 3; ++k) t.scale[k] = glm::length(r[k]);
        if (glm::determinant(r) < 0.0f) t.scale.x = -t.scale.x;
        for (int k = 0; k < 3; ++k) r[k] = t.scale[k] != 0.0f ? r[k] / t.scale[k] : glm::vec3(float(k == 0), float(k == 1), float(k == 2));
        const float skew = std::abs(glm::dot(r[0], r[1])) + std::abs(glm::dot(r[1], r[2])) + std::abs(glm::dot(r[0], r[2]));
        *sheared = !(skew < 1e-3f);
        t.rotation = glm::normalize(glm::quat_cast(r));
        if (!std::isfinite(t.rotation.w)) t.rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
        return t;
    }
    if (n.translation.size() == 3) t.translation = glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
    if (n.rotation.size() == 4) {
        glm::quat q;
        q.x = float(n.rotation[0]);
        q.y = float(n.rotation[1]);
        q.z = float(n.rotation[2]);
        q.w = float(n.rotation[3]);
        const float len = glm::length(q);
        if (std::isfinite(len) && len > 0.0f) t.rotation = q / len;
    }
    if (n.scale.size() == 3) t.scale = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
    return t;
}

}  // namespace

Scene GltfReader::run() {
    scene_.sourcePath = path_;
    opt_.report("reading", 0.0);  // the file, its buffers and images (tinygltf decodes the images while parsing)
    parse();
    checkExtensions();
    decodeMeshopt();
    decodeDraco();
    opt_.report("materials", 0.5);
    loadMaterials();
    warnIgnoredMaterialExtensions();
    opt_.report("meshes", 0.55);
    traverse();
    loadAnimations();
    validateScene(scene_);
    scene_.ensureNodes();
    scene_.computeBounds();
    scene_.loadPeakBytes = budget_.peak();
    opt_.report("done", 1.0);
    return std::move(scene_);
}

void GltfReader::reserveMemory(uint64_t bytes, const std::string& what, bool kept) {
    budget_.reserve(bytes, what, kept);
}

std::vector<unsigned char> GltfReader::readMainFile() { return readSceneFile(path_, "a glTF"); }

// Structural GLB checks done before tinygltf sees the data (tinygltf 2.7 lets the BIN chunk overrun by 8 bytes).
void GltfReader::checkGlb(const std::vector<unsigned char>& d) const {
    if (d.size() < 12) fail("truncated GLB: " + std::to_string(d.size()) + " bytes, header needs 12");
    if (std::memcmp(d.data(), "glTF", 4) != 0) fail("not a GLB file (bad magic)");
    const uint32_t version = le32(&d[4]), length = le32(&d[8]);
    if (version != 2) fail("unsupported GLB version " + std::to_string(version));
    if (length > d.size())
        fail("truncated GLB: header says " + std::to_string(length) + " bytes, file has " +
             std::to_string(d.size()));
    if (length < 20) fail("truncated GLB: no JSON chunk");
    const uint64_t jsonLen = le32(&d[12]);
    if (le32(&d[16]) != 0x4E4F534Au) fail("invalid GLB: first chunk is not JSON");
    if (20 + jsonLen > length) fail("truncated GLB: JSON chunk runs past the end of the file");
    const uint64_t binStart = 20 + jsonLen;
    if (binStart < length) {
        if (binStart + 8 > length) fail("truncated GLB: incomplete BIN chunk header");
        const uint64_t binLen = le32(&d[size_t(binStart)]);
        if (binStart + 8 + binLen > length) fail("truncated GLB: BIN chunk runs past the end of the file");
    }
}

// tinygltf converts "extras"/"extensions" JSON recursively, so deeply nested JSON would overflow the stack.
void GltfReader::checkJsonDepth(const unsigned char* p, size_t n) const {
    constexpr int kMaxDepth = 256;
    int depth = 0;
    bool inString = false, escaped = false;
    for (size_t i = 0; i < n; ++i) {
        const unsigned char c = p[i];
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxDepth)
                fail("invalid JSON: nesting deeper than " + std::to_string(kMaxDepth) + " levels");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

// The GLB with its JSON chunk replaced by `json` (padded with spaces to 4 bytes) and its BIN chunk kept.
std::vector<unsigned char> GltfReader::replacedGlbJson(const std::vector<unsigned char>& d, const std::string& json) const {
    const uint32_t length = le32(&d[8]);
    const uint64_t binStart = 20 + uint64_t(le32(&d[12]));
    std::string chunk = json;
    while (chunk.size() % 4) chunk += ' ';
    const uint64_t total = 20 + chunk.size() + (length - binStart);
    if (total >= UINT32_MAX) fail("file too large (4 GiB or more)");
    std::vector<unsigned char> out;
    out.reserve(size_t(total));
    auto put32 = [&](uint32_t v) { for (int k = 0; k < 4; ++k) out.push_back((unsigned char)(v >> (8 * k))); };
    out.insert(out.end(), d.begin(), d.begin() + 8);  // magic, version
    put32(uint32_t(total));
    put32(uint32_t(chunk.size()));
    put32(0x4E4F534Au);
    out.insert(out.end(), chunk.begin(), chunk.end());
    out.insert(out.end(), d.begin() + std::ptrdiff_t(binStart), d.begin() + std::ptrdiff_t(length));
    return out;
}

void GltfReader::parse() {
    std::vector<unsigned char> data = readMainFile();
    std::string ext = fs::path(path_).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const bool binary = ext == ".glb" || (data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0);
    reserveMemory(data.size(), "the file itself", true);
    if (binary) {
        checkGlb(data);
        checkJsonDepth(data.data() + 20, le32(&data[12]));
        const std::string json = checkJson(data.data() + 20, le32(&data[12]), true);
        if (!json.empty()) data = replacedGlbJson(data, json);
    } else {
        if (data.empty()) fail("empty file (invalid JSON)");
        checkJsonDepth(data.data(), data.size());
        const std::string json = checkJson(data.data(), data.size(), false);
        if (!json.empty()) data.assign(json.begin(), json.end());
    }

    FsContext ctx(path_);

    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks(tinygltf::FsCallbacks{&fsFileExists, &fsExpand, &fsReadWholeFile, &fsWriteWholeFile, &ctx});
    gltf.SetImageLoader(&imageCallback, nullptr);
    std::string err, warnStr;
    bool ok = false;
    try {
        if (binary)
            ok = gltf.LoadBinaryFromMemory(&model_, &err, &warnStr, data.data(), unsigned(data.size()),
                                           ctx.folder.dir());
        else
            ok = gltf.LoadASCIIFromString(&model_, &err, &warnStr, reinterpret_cast<const char*>(data.data()),
                                          unsigned(data.size()), ctx.folder.dir());
    } catch (const std::exception& e) {
        ok = false;
        err = e.what();
    }
    if (!ok) {
        std::string msg;
        for (const auto& [uri, why] : ctx.problems) msg += "URI '" + printable(uri) + "' " + why + "; ";
        std::string e = trimmed(err);
        if (e.find("JSON") == std::string::npos && e.find("json") != std::string::npos) e += " (invalid JSON)";
        if (e.find("parse_error") != std::string::npos || e.find("syntax error") != std::string::npos)
            e = "invalid JSON: " + e;
        fail(msg + "glTF parse error: " + (e.empty() ? std::string("unknown error") : e));
    }
    uriProblems_ = ctx.problems;
    for (const auto& line : splitLines(err)) warn("tinygltf: " + printable(line));
    for (const auto& line : splitLines(warnStr)) warn("tinygltf: " + printable(line));
}

const std::set<std::string>& supportedExtensions() {
    static const std::set<std::string> supported = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_node_visibility", "KHR_mesh_quantization", "KHR_texture_transform",
        "KHR_draco_mesh_compression", "EXT_meshopt_compression"};
    return supported;
}

void GltfReader::checkExtensions() {
    for (const auto& e : model_.extensionsRequired)
        if (!supportedExtensions().count(e)) fail("required extension '" + e + "' is not supported");
    std::string ignored;
    for (const auto& e : model_.extensionsUsed) {
        // Material extensions are named with the material that uses them (warnIgnoredMaterialExtensions).
        if (!supportedExtensions().count(e) && e.rfind("KHR_materials_", 0) != 0) ignored += (ignored.empty() ? "" : ", ") + e;
        if (e == "KHR_mesh_quantization") quantized_ = true;
    }
    if (!ignored.empty()) warn("ignoring unsupported optional extension(s): " + ignored);
}

void GltfReader::traverse() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
        int si = model_.defaultScene;
        if (si < 0 || size_t(si) >= model_.scenes.size()) {
            if (si >= 0) warn("default scene " + std::to_string(si) + " does not exist; using scene 0");
            si = 0;
        }
        roots = model_.scenes[size_t(si)].nodes;
    } else {
        // No scenes: every node that is nobody's child is a root.
        std::vector<char> isChild(model_.nodes.size(), 0);
        for (const auto& n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < model_.nodes.size()) isChild[size_t(c)] = 1;
        for (size_t i = 0; i < model_.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    }
    std::vector<char> visited(model_.nodes.size(), 0);
    size_t visitedCount = 0;
    // Iterative depth-first walk (no recursion: deep hierarchies cannot overflow the stack).
    struct Visit { int node; glm::mat4 parentWorld; int parentSceneNode; };
    std::vector<Visit> stack;
    sceneNodeOf_.assign(model_.nodes.size(), -1);
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f), -1});
    while (!stack.empty()) {
        auto [ni, parent, parentNode] = stack.back();
        stack.pop_back();
        if (ni < 0 || size_t(ni) >= model_.nodes.size()) fail("node " + std::to_string(ni) + " out of range");
        if (visited[size_t(ni)])
            fail("node " + std::to_string(ni) + " is reached twice (cycle or shared child in the node hierarchy)");
        visited[size_t(ni)] = 1;
        opt_.report("meshes", 0.55 + 0.45 * double(visitedCount++) / double(model_.nodes.size()));
        const auto& node = model_.nodes[size_t(ni)];
        const glm::mat4 world = parent * localMatrix(node);
        bool sheared = false;
        const Transform local = localTransform(node, &sheared);
        currentNode_ = scene_.addNode(node.name.empty() ? "node[" + std::to_string(ni) + "]" : node.name, parentNode, local);
        sceneNodeOf_[size_t(ni)] = currentNode_;
        auto vis = node.extensions.find("KHR_node_visibility");  // what saveGltf writes for hidden nodes
        if (vis != node.extensions.end() && vis->second.IsObject() && vis->second.Has("visible") &&
            vis->second.Get("visible").IsBool() && !vis->second.Get("visible").Get<bool>())
            scene_.nodes[size_t(currentNode_)].visible = false;
        if (sheared) warn("node '" + scene_.nodes[size_t(currentNode_)].name + "': its matrix has shear, which moving it drops");
        if (node.mesh >= 0) addMesh(node.mesh, world);
        if (node.camera >= 0) addCamera(node, world);
        auto lit = node.extensions.find("KHR_lights_punctual");
        if (lit != node.extensions.end() && lit->second.IsObject() && lit->second.Has("light")) {
            const auto& v = lit->second.Get("light");
            const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
            if (d >= 0.0 && d < double(model_.lights.size())) addLight(node, int(d), world);
            else warn("node '" + node.name + "': KHR_lights_punctual light index out of range");
        }
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world, currentNode_});
    }
    if (skippedNonFinite_ > 0)
        warn("skipped " + std::to_string(skippedNonFinite_) + " triangle(s) with NaN/Inf vertex positions");
}

}  // namespace gltf

GltfLoadOptions gltfLoadOptions(const Settings& settings) {
    GltfLoadOptions o;
    o.memoryBudget = uint64_t(settings.loadMemoryBudget) << 20;
    return o;
}

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
    gltf::GltfReader reader(path, options);
    return runSceneReader(path, reader);
}

}  // namespace deepgi
