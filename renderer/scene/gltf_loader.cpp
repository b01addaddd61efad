// glTF 2.0 loader: tinygltf parses the JSON and fetches buffers; everything that indexes into the data (accessors,
// buffer views, indices, node links, images) is validated here, because tinygltf 2.7 trusts most of it.
//
// Decisions worth knowing:
//  * External URIs must stay inside the scene's folder: a URI that is absolute or has a ".." component is refused.
//    For a buffer that is an error (the geometry is unusable); for an image it is a warning and the texture is
//    dropped, so the material falls back to its factor colour.
//  * Images are decoded here (not by tinygltf) with stb_image, after stbi_info_from_memory has checked the claimed
//    dimensions against GltfLoadOptions::maxImagePixels. Only images used by a base-colour or emissive texture are
//    decoded. A missing/corrupt/refused image only drops the texture (warning naming the image).
//  * Camera transforms keep rotation and translation only (any node scale is removed from cameraToWorld).
//  * The node hierarchy must be a strict tree (glTF requirement): a node reached twice (cycle or shared child) is an
//    error, which also rules out exponential blow-up from DAG-shaped hierarchies.
#include "renderer/scene/gltf_loader.h"

#include <tiny_gltf.h>
#include <stb_image.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <unordered_map>

namespace deepgi {
namespace {

namespace fs = std::filesystem;

constexpr int kCompByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kCompUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kCompShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kCompUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kCompUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kCompFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

const char* componentTypeName(int t) {
    switch (t) {
        case kCompByte: return "byte";
        case kCompUByte: return "unsigned byte";
        case kCompShort: return "short";
        case kCompUShort: return "unsigned short";
        case kCompUInt: return "unsigned int";
        case kCompFloat: return "float";
        default: return "unknown";
    }
}

size_t componentSize(int t) {
    switch (t) {
        case kCompByte: case kCompUByte: return 1;
        case kCompShort: case kCompUShort: return 2;
        case kCompUInt: case kCompFloat: return 4;
        default: return 0;
    }
}

int typeComponents(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    for (auto& c : s) if (c == '\n') c = ';';
    return s;
}

std::vector<std::string> splitLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) if (!line.empty()) out.push_back(line);
    return out;
}

// ---- file system callbacks: confine external URIs to the scene's folder ----
struct FsContext {
    std::string baseDir;               // absolute, no trailing '/'
    std::vector<std::string> refused;  // URIs refused because they escape baseDir
};

// Returns true when `full` (as joined by tinygltf: baseDir + "/" + uri) names a file inside baseDir.
bool insideBase(const std::string& full, FsContext* ctx, bool record) {
    const std::string prefix = ctx->baseDir == "/" ? ctx->baseDir : ctx->baseDir + "/";
    if (full.compare(0, prefix.size(), prefix) != 0) return false;  // e.g. tinygltf's "./uri" fallback
    const std::string rel = full.substr(prefix.size());
    bool bad = rel.empty() || rel[0] == '/' || rel[0] == '\\';
    if (!bad) {
        for (const auto& part : fs::path(rel)) {
            if (part == "..") { bad = true; break; }
        }
        if (rel.find('\\') != std::string::npos && rel.find("..") != std::string::npos) bad = true;
    }
    if (bad && record) {
        if (std::find(ctx->refused.begin(), ctx->refused.end(), rel) == ctx->refused.end())
            ctx->refused.push_back(rel);
    }
    return !bad;
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
    if (!insideBase(path, ctx, true)) {
        if (err) *err += "refused: " + path + "\n";
        return false;
    }
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) {
        if (err) *err += "cannot open " + path + "\n";
        return false;
    }
    std::streamoff size = f.tellg();
    if (size < 0 || uint64_t(size) > uint64_t(INT_MAX)) {
        if (err) *err += "file too large: " + path + "\n";
        return false;
    }
    out->resize(size_t(size));
    f.seekg(0);
    if (size > 0 && !f.read(reinterpret_cast<char*>(out->data()), size)) {
        if (err) *err += "read error: " + path + "\n";
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

// ---- the loader proper ----
class Loader {
public:
    Loader(const std::string& path, const GltfLoadOptions& opt) : path_(path), opt_(opt) {}

    Scene run() {
        scene_.sourcePath = path_;
        parse();
        checkExtensions();
        loadMaterials();
        traverse();
        scene_.computeBounds();
        return std::move(scene_);
    }

private:
    std::string path_;
    GltfLoadOptions opt_;
    tinygltf::Model model_;
    Scene scene_;
    uint64_t elements_ = 0;
    std::vector<int> imageMap_;    // glTF image -> Scene::images index, -1 unusable, -2 not decoded yet
    std::vector<int> textureMap_;  // glTF texture -> Scene::textures index, -1 unusable, -2 not resolved yet
    std::vector<std::string> refusedImages_;
    uint64_t skippedNonFinite_ = 0;

    [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(path_ + ": " + problem); }
    void warn(const std::string& w) { scene_.warnings.push_back(w); }

    // ---- parsing ----
    std::vector<unsigned char> readMainFile() {
        std::error_code ec;
        if (!fs::exists(path_, ec)) fail("file not found");
        if (fs::is_directory(path_, ec)) fail("is a directory, not a glTF file");
        std::ifstream f(path_, std::ios::binary | std::ios::ate);
        if (!f) fail("cannot open file");
        std::streamoff size = f.tellg();
        if (size < 0) fail("cannot determine the file size");
        if (uint64_t(size) >= uint64_t(UINT_MAX)) fail("file too large (4 GiB or more)");
        std::vector<unsigned char> data(static_cast<size_t>(size));
        f.seekg(0);
        if (size > 0 && !f.read(reinterpret_cast<char*>(data.data()), size)) fail("read error");
        return data;
    }

    static uint32_t le32(const unsigned char* p) {
        return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
    }

    // Structural GLB checks done before tinygltf sees the data (tinygltf 2.7 lets the BIN chunk overrun by 8 bytes).
    void checkGlb(const std::vector<unsigned char>& d) const {
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
    void checkJsonDepth(const unsigned char* p, size_t n) const {
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

    void parse() {
        std::vector<unsigned char> data = readMainFile();
        std::string ext = fs::path(path_).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        const bool binary = ext == ".glb" || (data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0);
        if (binary) {
            checkGlb(data);
            checkJsonDepth(data.data() + 20, le32(&data[12]));
        } else {
            if (data.empty()) fail("empty file (invalid JSON)");
            checkJsonDepth(data.data(), data.size());
        }

        FsContext ctx;
        std::error_code ec;
        fs::path abs = fs::absolute(fs::path(path_), ec);
        ctx.baseDir = (ec ? fs::path(path_) : abs).lexically_normal().parent_path().string();
        while (ctx.baseDir.size() > 1 && ctx.baseDir.back() == '/') ctx.baseDir.pop_back();
        if (ctx.baseDir.empty()) ctx.baseDir = ".";

        tinygltf::TinyGLTF gltf;
        gltf.SetFsCallbacks(tinygltf::FsCallbacks{&fsFileExists, &fsExpand, &fsReadWholeFile, &fsWriteWholeFile, &ctx});
        gltf.SetImageLoader(&imageCallback, nullptr);
        std::string err, warnStr;
        bool ok = false;
        try {
            if (binary)
                ok = gltf.LoadBinaryFromMemory(&model_, &err, &warnStr, data.data(), unsigned(data.size()),
                                               ctx.baseDir);
            else
                ok = gltf.LoadASCIIFromString(&model_, &err, &warnStr, reinterpret_cast<const char*>(data.data()),
                                              unsigned(data.size()), ctx.baseDir);
        } catch (const std::exception& e) {
            ok = false;
            err = e.what();
        }
        if (!ok) {
            std::string msg;
            for (const auto& r : ctx.refused) msg += "URI '" + r + "' escapes the scene folder (refused); ";
            std::string e = trimmed(err);
            if (e.find("JSON") == std::string::npos && e.find("json") != std::string::npos) e += " (invalid JSON)";
            if (e.find("parse_error") != std::string::npos || e.find("syntax error") != std::string::npos)
                e = "invalid JSON: " + e;
            fail(msg + "glTF parse error: " + (e.empty() ? std::string("unknown error") : e));
        }
        for (const auto& r : ctx.refused)
            if (std::find(refusedImages_.begin(), refusedImages_.end(), r) == refusedImages_.end())
                refusedImages_.push_back(r);
        for (const auto& line : splitLines(err)) warn("tinygltf: " + line);
        for (const auto& line : splitLines(warnStr)) warn("tinygltf: " + line);
    }

    void checkExtensions() {
        static const std::set<std::string> supported = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
        for (const auto& e : model_.extensionsRequired)
            if (!supported.count(e)) fail("required extension '" + e + "' is not supported");
        std::string ignored;
        for (const auto& e : model_.extensionsUsed)
            if (!supported.count(e)) ignored += (ignored.empty() ? "" : ", ") + e;
        if (!ignored.empty()) warn("ignoring unsupported optional extension(s): " + ignored);
    }

    // ---- accessors ----
    // Locates `count` elements of `elemSize` bytes in a buffer view, with every range checked.
    struct Span {
        const unsigned char* base = nullptr;
        size_t stride = 0;
    };

    Span viewSpan(int viewIndex, size_t byteOffset, size_t count, size_t elemSize, bool allowStride,
                  const std::string& what) const {
        if (viewIndex < 0 || size_t(viewIndex) >= model_.bufferViews.size())
            fail(what + ": buffer view " + std::to_string(viewIndex) + " out of range");
        const auto& view = model_.bufferViews[size_t(viewIndex)];
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            fail(what + ": buffer " + std::to_string(view.buffer) + " out of range");
        const auto& buf = model_.buffers[size_t(view.buffer)];
        if (view.byteOffset > buf.data.size() || view.byteLength > buf.data.size() - view.byteOffset)
            fail(what + ": buffer view " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) +
                 ", length " + std::to_string(view.byteLength) + ") out of range of its buffer (" +
                 std::to_string(buf.data.size()) + " bytes)");
        if (byteOffset > view.byteLength)
            fail(what + ": byte offset " + std::to_string(byteOffset) + " out of range of buffer view " +
                 std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) + " bytes)");
        size_t stride = elemSize;
        if (allowStride && view.byteStride != 0) {
            if (view.byteStride < elemSize || view.byteStride > 252)
                fail(what + ": invalid byte stride " + std::to_string(view.byteStride));
            stride = view.byteStride;
        }
        if (count > 0) {
            // needed = byteOffset + (count-1)*stride + elemSize, overflow-checked
            unsigned long long span = 0, needed = 0;
            if (__builtin_mul_overflow((unsigned long long)(count - 1), (unsigned long long)stride, &span) ||
                __builtin_add_overflow(span, (unsigned long long)elemSize, &span) ||
                __builtin_add_overflow(span, (unsigned long long)byteOffset, &needed) || needed > view.byteLength)
                fail(what + ": " + std::to_string(count) + " elements out of range of buffer view " +
                     std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) + " bytes)");
        }
        Span s;
        s.base = buf.data.data() + view.byteOffset + byteOffset;
        s.stride = stride;
        return s;
    }

    static double readComponent(const unsigned char* p, int type, bool normalized) {
        switch (type) {
            case kCompFloat: { float f; std::memcpy(&f, p, 4); return f; }
            case kCompUByte: return normalized ? p[0] / 255.0 : double(p[0]);
            case kCompByte: {
                int8_t v; std::memcpy(&v, p, 1);
                return normalized ? std::max(v / 127.0, -1.0) : double(v);
            }
            case kCompUShort: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : double(v); }
            case kCompShort: {
                int16_t v; std::memcpy(&v, p, 2);
                return normalized ? std::max(v / 32767.0, -1.0) : double(v);
            }
            case kCompUInt: { uint32_t v; std::memcpy(&v, p, 4); return double(v); }
            default: return 0.0;
        }
    }

    static uint32_t readIndex(const unsigned char* p, int type) {
        switch (type) {
            case kCompUByte: return p[0];
            case kCompUShort: { uint16_t v; std::memcpy(&v, p, 2); return v; }
            default: { uint32_t v; std::memcpy(&v, p, 4); return v; }
        }
    }

    const tinygltf::Accessor& accessor(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= model_.accessors.size())
            fail(what + ": accessor " + std::to_string(index) + " out of range");
        return model_.accessors[size_t(index)];
    }

    void reserveElements(size_t count, const std::string& what) {
        if (count > opt_.maxElements || elements_ + count > opt_.maxElements)
            fail(what + ": element count " + std::to_string(count) + " overflows the limit of " +
                 std::to_string(opt_.maxElements) + " vertices + indices per file");
        elements_ += count;
    }

    // Applies the sparse substitution of `acc` to `out` (numComp values per element), through `write`.
    template <class Write>
    void applySparse(const tinygltf::Accessor& acc, const std::string& what, size_t elemSize, Write write) {
        if (!acc.sparse.isSparse) return;
        if (acc.sparse.count < 0 || size_t(acc.sparse.count) > acc.count)
            fail(what + ": sparse count " + std::to_string(acc.sparse.count) + " out of range");
        const size_t n = size_t(acc.sparse.count);
        const int itype = acc.sparse.indices.componentType;
        if (itype != kCompUByte && itype != kCompUShort && itype != kCompUInt)
            fail(what + ": sparse indices have invalid component type " + std::to_string(itype));
        if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
            fail(what + ": negative sparse byte offset");
        Span is = viewSpan(acc.sparse.indices.bufferView, size_t(acc.sparse.indices.byteOffset), n,
                           componentSize(itype), false, what + " (sparse indices)");
        Span vs = viewSpan(acc.sparse.values.bufferView, size_t(acc.sparse.values.byteOffset), n, elemSize, false,
                           what + " (sparse values)");
        for (size_t i = 0; i < n; ++i) {
            uint32_t target = readIndex(is.base + i * is.stride, itype);
            if (target >= acc.count)
                fail(what + ": sparse index " + std::to_string(target) + " out of range (count " +
                     std::to_string(acc.count) + ")");
            write(size_t(target), vs.base + i * vs.stride);
        }
    }

    // Reads a float attribute with `numComp` components (VEC2/VEC3). Allowed component types listed in `allowed`.
    std::vector<float> readFloats(int index, int expectedType, std::initializer_list<int> allowed,
                                  bool requireNormalizedInts, bool countTowardsLimit, const std::string& what) {
        const auto& acc = accessor(index, what);
        const int numComp = typeComponents(expectedType);
        if (acc.type != expectedType)
            fail(what + ": accessor " + std::to_string(index) + " has the wrong type (expected " +
                 std::to_string(numComp) + " components)");
        if (std::find(allowed.begin(), allowed.end(), acc.componentType) == allowed.end() ||
            (requireNormalizedInts && acc.componentType != kCompFloat && !acc.normalized))
            fail(what + ": accessor " + std::to_string(index) + " has unsupported component type " +
                 componentTypeName(acc.componentType) + (acc.normalized ? " (normalized)" : ""));
        if (countTowardsLimit) reserveElements(acc.count, what);
        else if (acc.count > opt_.maxElements) reserveElements(acc.count, what);  // fails
        const size_t csize = componentSize(acc.componentType);
        const size_t elemSize = csize * size_t(numComp);
        Span s;
        if (acc.bufferView >= 0)  // range check before allocating anything
            s = viewSpan(acc.bufferView, acc.byteOffset, acc.count, elemSize, true,
                         what + " (accessor " + std::to_string(index) + ")");
        std::vector<float> out(acc.count * size_t(numComp), 0.0f);
        auto writeElem = [&](size_t i, const unsigned char* p) {
            for (int c = 0; c < numComp; ++c)
                out[i * size_t(numComp) + size_t(c)] =
                    float(readComponent(p + size_t(c) * csize, acc.componentType, acc.normalized));
        };
        if (acc.bufferView >= 0) {
            for (size_t i = 0; i < acc.count; ++i) writeElem(i, s.base + i * s.stride);
        } else if (!acc.sparse.isSparse) {
            warn(what + ": accessor " + std::to_string(index) + " has no data; using zeros");
        }
        applySparse(acc, what, elemSize, writeElem);
        return out;
    }

    std::vector<uint32_t> readIndices(int index, const std::string& what) {
        const auto& acc = accessor(index, what);
        if (acc.type != TINYGLTF_TYPE_SCALAR)
            fail(what + ": index accessor " + std::to_string(index) + " is not SCALAR");
        const int ct = acc.componentType;
        if (ct != kCompUByte && ct != kCompUShort && ct != kCompUInt)
            fail(what + ": index accessor " + std::to_string(index) + " has unsupported component type " +
                 componentTypeName(ct));
        reserveElements(acc.count, what);
        const size_t csize = componentSize(ct);
        Span s;
        if (acc.bufferView >= 0)
            s = viewSpan(acc.bufferView, acc.byteOffset, acc.count, csize, true,
                         what + " (accessor " + std::to_string(index) + ")");
        std::vector<uint32_t> out(acc.count, 0u);
        auto writeElem = [&](size_t i, const unsigned char* p) { out[i] = readIndex(p, ct); };
        if (acc.bufferView >= 0) {
            for (size_t i = 0; i < acc.count; ++i) writeElem(i, s.base + i * s.stride);
        }
        applySparse(acc, what, csize, writeElem);
        return out;
    }

    // ---- images, textures, materials ----
    int resolveImage(int gi, const std::string& user) {
        if (gi < 0 || size_t(gi) >= model_.images.size()) {
            warn(user + ": image " + std::to_string(gi) + " does not exist; using the fallback colour");
            return -1;
        }
        if (imageMap_[size_t(gi)] != -2) return imageMap_[size_t(gi)];
        imageMap_[size_t(gi)] = -1;
        const auto& img = model_.images[size_t(gi)];
        std::string name = !img.uri.empty() ? img.uri : !img.name.empty() ? img.name : "image[" + std::to_string(gi) + "]";
        if (name.compare(0, 5, "data:") == 0) name = "image[" + std::to_string(gi) + "] (data URI)";
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
            const bool refused =
                std::find(refusedImages_.begin(), refusedImages_.end(), img.uri) != refusedImages_.end() ||
                img.uri.find("../") != std::string::npos || img.uri == ".." || (!img.uri.empty() && img.uri[0] == '/');
            if (refused)
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
        int dw = 0, dh = 0, dc = 0;
        unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &dw, &dh, &dc, 4);
        if (!pixels) {
            const char* why = stbi_failure_reason();
            warn("image '" + name + "' could not be decoded (" + (why ? why : "unknown") + ")" + fallback);
            return -1;
        }
        Image out;
        out.name = name;
        out.width = dw;
        out.height = dh;
        out.rgba8.assign(pixels, pixels + size_t(dw) * size_t(dh) * 4);
        stbi_image_free(pixels);
        scene_.images.push_back(std::move(out));
        imageMap_[size_t(gi)] = int(scene_.images.size()) - 1;
        return imageMap_[size_t(gi)];
    }

    static WrapMode wrapMode(int w) {
        switch (w) {
            case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
            case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
            default: return WrapMode::Repeat;
        }
    }

    int resolveTexture(const tinygltf::TextureInfo& info, const std::string& user) {
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

    static float finiteOr(double v, float fallback) {
        return std::isfinite(v) ? float(v) : fallback;
    }

    void loadMaterials() {
        imageMap_.assign(model_.images.size(), -2);
        textureMap_.assign(model_.textures.size(), -2);
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            const auto& gm = model_.materials[i];
            Material m;
            m.name = gm.name.empty() ? "material" + std::to_string(i) : gm.name;
            const std::string user = "material '" + m.name + "'";
            const auto& bcf = gm.pbrMetallicRoughness.baseColorFactor;
            for (int c = 0; c < 4 && size_t(c) < bcf.size(); ++c) m.baseColorFactor[c] = finiteOr(bcf[size_t(c)], 1.0f);
            m.baseColorTexture = resolveTexture(gm.pbrMetallicRoughness.baseColorTexture, user);
            float strength = 1.0f;
            auto it = gm.extensions.find("KHR_materials_emissive_strength");
            if (it != gm.extensions.end() && it->second.IsObject() && it->second.Has("emissiveStrength")) {
                const auto& v = it->second.Get("emissiveStrength");
                if (v.IsNumber()) strength = std::max(0.0f, finiteOr(v.GetNumberAsDouble(), 1.0f));
            }
            for (int c = 0; c < 3 && size_t(c) < gm.emissiveFactor.size(); ++c)
                m.emissiveFactor[c] = std::max(0.0f, finiteOr(gm.emissiveFactor[size_t(c)], 0.0f)) * strength;
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

    // ---- node hierarchy ----
    static glm::mat4 localMatrix(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) {
            glm::mat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = float(n.matrix[size_t(c * 4 + r)]);
            return m;
        }
        glm::mat4 t(1.0f), r(1.0f), s(1.0f);
        if (n.translation.size() == 3)
            t = glm::translate(glm::mat4(1.0f), glm::vec3(float(n.translation[0]), float(n.translation[1]),
                                                          float(n.translation[2])));
        if (n.rotation.size() == 4) {
            glm::quat q;
            q.x = float(n.rotation[0]);
            q.y = float(n.rotation[1]);
            q.z = float(n.rotation[2]);
            q.w = float(n.rotation[3]);
            const float len = glm::length(q);
            if (std::isfinite(len) && len > 0.0f) r = glm::mat4_cast(q / len);
        }
        if (n.scale.size() == 3)
            s = glm::scale(glm::mat4(1.0f), glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
        return t * r * s;
    }

    void traverse() {
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
        // Iterative depth-first walk (no recursion: deep hierarchies cannot overflow the stack).
        std::vector<std::pair<int, glm::mat4>> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
        while (!stack.empty()) {
            auto [ni, parent] = stack.back();
            stack.pop_back();
            if (ni < 0 || size_t(ni) >= model_.nodes.size()) fail("node " + std::to_string(ni) + " out of range");
            if (visited[size_t(ni)])
                fail("node " + std::to_string(ni) + " is reached twice (cycle or shared child in the node hierarchy)");
            visited[size_t(ni)] = 1;
            const auto& node = model_.nodes[size_t(ni)];
            const glm::mat4 world = parent * localMatrix(node);
            if (node.mesh >= 0) addMesh(node.mesh, world);
            if (node.camera >= 0) addCamera(node, world);
            auto lit = node.extensions.find("KHR_lights_punctual");
            if (lit != node.extensions.end() && lit->second.IsObject() && lit->second.Has("light")) {
                const auto& v = lit->second.Get("light");
                const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
                if (d >= 0.0 && d < double(model_.lights.size())) addLight(node, int(d), world);
                else warn("node '" + node.name + "': KHR_lights_punctual light index out of range");
            }
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.emplace_back(*c, world);
        }
        if (skippedNonFinite_ > 0)
            warn("skipped " + std::to_string(skippedNonFinite_) + " triangle(s) with NaN/Inf vertex positions");
    }

    void addCamera(const tinygltf::Node& node, const glm::mat4& world) {
        if (size_t(node.camera) >= model_.cameras.size()) {
            warn("node '" + node.name + "': camera " + std::to_string(node.camera) + " does not exist");
            return;
        }
        const auto& gc = model_.cameras[size_t(node.camera)];
        CameraDesc c;
        c.name = gc.name.empty() ? "camera" + std::to_string(scene_.cameras.size()) : gc.name;
        if (gc.type == "orthographic") {
            c.perspective = false;
            c.xmag = finiteOr(gc.orthographic.xmag, 1.0f);
            c.ymag = finiteOr(gc.orthographic.ymag, 1.0f);
            c.znear = finiteOr(gc.orthographic.znear, 0.0f);
            c.zfar = finiteOr(gc.orthographic.zfar, 0.0f);
        } else {
            c.perspective = true;
            c.yfov = finiteOr(gc.perspective.yfov, 0.8f);
            c.aspectRatio = std::max(0.0f, finiteOr(gc.perspective.aspectRatio, 0.0f));
            c.znear = finiteOr(gc.perspective.znear, 0.05f);
            c.zfar = std::max(0.0f, finiteOr(gc.perspective.zfar, 0.0f));
            if (!(c.yfov > 0.0f && c.yfov < 3.14159f)) {
                warn("camera '" + c.name + "': invalid yfov, using 0.8");
                c.yfov = 0.8f;
            }
            if (!(c.znear > 0.0f)) c.znear = 0.05f;
        }
        if (!finite3(glm::vec3(world[0])) || !finite3(glm::vec3(world[1])) || !finite3(glm::vec3(world[2])) ||
            !finite3(glm::vec3(world[3]))) {
            warn("camera '" + c.name + "': non-finite node transform, skipped");
            return;
        }
        glm::mat4 m = world;
        for (int i = 0; i < 3; ++i) {
            const float len = glm::length(glm::vec3(m[i]));
            if (len > 0.0f && std::isfinite(len)) m[i] /= len;
        }
        c.cameraToWorld = m;
        scene_.cameras.push_back(std::move(c));
    }

    void addLight(const tinygltf::Node& node, int li, const glm::mat4& world) {
        if (li < 0 || size_t(li) >= model_.lights.size()) {
            warn("node '" + node.name + "': light " + std::to_string(li) + " does not exist");
            return;
        }
        const auto& gl = model_.lights[size_t(li)];
        Light l;
        l.name = !gl.name.empty() ? gl.name : !node.name.empty() ? node.name : "light" + std::to_string(li);
        if (gl.type == "directional") l.type = LightType::Directional;
        else if (gl.type == "point") l.type = LightType::Point;
        else if (gl.type == "spot") l.type = LightType::Spot;
        else {
            warn("light '" + l.name + "': unknown type '" + gl.type + "', skipped");
            return;
        }
        for (int c = 0; c < 3 && size_t(c) < gl.color.size(); ++c) l.color[c] = std::max(0.0f, finiteOr(gl.color[size_t(c)], 1.0f));
        l.intensity = std::max(0.0f, finiteOr(gl.intensity, 1.0f));
        l.range = std::max(0.0f, finiteOr(gl.range, 0.0f));
        l.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        if (!finite3(l.position)) {
            warn("light '" + l.name + "': non-finite node transform, skipped");
            return;
        }
        glm::vec3 d = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
        const float len = glm::length(d);
        l.direction = (len > 0.0f && std::isfinite(len)) ? d / len : glm::vec3(0.0f, 0.0f, -1.0f);
        if (l.type == LightType::Spot) {
            l.outerConeAngle = glm::clamp(finiteOr(gl.spot.outerConeAngle, 0.7853982f), 0.0f, 1.5707963f);
            l.innerConeAngle = glm::clamp(finiteOr(gl.spot.innerConeAngle, 0.0f), 0.0f, l.outerConeAngle);
        }
        scene_.lights.push_back(std::move(l));
    }

    // ---- meshes ----
    static glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        glm::vec3 n = glm::cross(b - a, c - a);
        const float len = glm::length(n);
        return (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }

    static bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

    void addMesh(int meshIndex, const glm::mat4& world) {
        if (size_t(meshIndex) >= model_.meshes.size()) fail("mesh " + std::to_string(meshIndex) + " out of range");
        const auto& mesh = model_.meshes[size_t(meshIndex)];
        const std::string meshName = mesh.name.empty() ? "mesh" + std::to_string(meshIndex) : mesh.name;
        const glm::mat3 m3(world);
        const float det = glm::determinant(m3);
        // Inverse-transpose up to a positive scale: the cofactor matrix, sign-corrected by the determinant.
        glm::mat3 normalMat(glm::cross(m3[1], m3[2]), glm::cross(m3[2], m3[0]), glm::cross(m3[0], m3[1]));
        if (det < 0.0f) normalMat = -normalMat;
        const bool flip = det < 0.0f;

        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const auto& prim = mesh.primitives[pi];
            const std::string name = meshName + "/" + std::to_string(pi);
            const std::string what = "mesh '" + name + "'";
            const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                warn(what + ": primitive mode " + std::to_string(mode) + " is not triangles, skipped");
                continue;
            }
            auto posIt = prim.attributes.find("POSITION");
            if (posIt == prim.attributes.end()) {
                warn(what + ": primitive has no POSITION, skipped");
                continue;
            }
            std::vector<float> pos = readFloats(posIt->second, TINYGLTF_TYPE_VEC3, {kCompFloat}, false, true,
                                          what + " POSITION");
            const size_t nv = pos.size() / 3;
            std::vector<float> nrm, uv;
            auto nIt = prim.attributes.find("NORMAL");
            if (nIt != prim.attributes.end()) {
                nrm = readFloats(nIt->second, TINYGLTF_TYPE_VEC3, {kCompFloat}, false, false, what + " NORMAL");
                if (nrm.size() != pos.size()) fail(what + ": NORMAL count differs from POSITION count");
            }
            auto tIt = prim.attributes.find("TEXCOORD_0");
            if (tIt != prim.attributes.end()) {
                uv = readFloats(tIt->second, TINYGLTF_TYPE_VEC2, {kCompFloat, kCompUByte, kCompUShort}, true,
                                false, what + " TEXCOORD_0");
                if (uv.size() / 2 != nv) fail(what + ": TEXCOORD_0 count differs from POSITION count");
            }

            std::vector<uint32_t> idx;
            if (prim.indices >= 0) {
                idx = readIndices(prim.indices, what + " indices");
                for (uint32_t i : idx)
                    if (i >= nv)
                        fail(what + ": index " + std::to_string(i) + " out of range (vertex count " +
                             std::to_string(nv) + ")");
            } else {
                if (nv > UINT32_MAX) fail(what + ": too many vertices");
                idx.resize(nv);
                for (size_t i = 0; i < nv; ++i) idx[i] = uint32_t(i);
            }

            // Triangle list in source winding.
            std::vector<uint32_t> tris;
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                if (idx.size() % 3 != 0) warn(what + ": index count not a multiple of 3, trailing indices ignored");
                tris.assign(idx.begin(), idx.begin() + std::ptrdiff_t(idx.size() / 3 * 3));
            } else if (idx.size() >= 3) {
                tris.reserve((idx.size() - 2) * 3);
                for (size_t i = 0; i + 2 < idx.size(); ++i) {
                    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                        if (i % 2 == 0) tris.insert(tris.end(), {idx[i], idx[i + 1], idx[i + 2]});
                        else tris.insert(tris.end(), {idx[i + 1], idx[i], idx[i + 2]});
                    } else {
                        tris.insert(tris.end(), {idx[i + 1], idx[i + 2], idx[0]});
                    }
                }
            }
            if (tris.empty()) continue;

            MeshPart part;
            part.name = name;
            if (prim.material >= 0 && size_t(prim.material) >= scene_.materials.size())
                warn(what + ": material " + std::to_string(prim.material) + " does not exist; using the default");
            else
                part.material = prim.material;

            // World-space vertices.
            std::vector<Vertex> verts(nv);
            std::vector<char> badNormal(nv, 0);
            for (size_t i = 0; i < nv; ++i) {
                Vertex& v = verts[i];
                v.position = glm::vec3(world * glm::vec4(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2], 1.0f));
                v.uv = uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[i * 2], uv[i * 2 + 1]);
                if (!finite3(glm::vec3(v.uv, 0.0f))) v.uv = glm::vec2(0.0f);
                if (nrm.empty()) {
                    badNormal[i] = 1;
                    continue;
                }
                glm::vec3 n = normalMat * glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
                const float len = glm::length(n);
                if (len > 1e-20f && std::isfinite(len)) v.normal = n / len;
                else badNormal[i] = 1;
            }

            // Emit triangles: skip non-finite ones, flip winding for mirroring transforms, give vertices without a
            // usable normal a per-triangle copy carrying the flat face normal.
            std::vector<int64_t> remap(nv, -1);
            uint64_t skipped = 0;
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                uint32_t tri[3] = {tris[t], tris[t + 1], tris[t + 2]};
                if (flip) std::swap(tri[1], tri[2]);
                const glm::vec3 &a = verts[tri[0]].position, &b = verts[tri[1]].position, &c = verts[tri[2]].position;
                if (!finite3(a) || !finite3(b) || !finite3(c)) {
                    ++skipped;
                    continue;
                }
                const glm::vec3 fn = faceNormal(a, b, c);
                for (uint32_t k : tri) {
                    if (badNormal[k]) {
                        Vertex v = verts[k];
                        v.normal = fn;
                        part.indices.push_back(uint32_t(part.vertices.size()));
                        part.vertices.push_back(v);
                    } else {
                        if (remap[k] < 0) {
                            remap[k] = int64_t(part.vertices.size());
                            part.vertices.push_back(verts[k]);
                        }
                        part.indices.push_back(uint32_t(remap[k]));
                    }
                }
            }
            skippedNonFinite_ += skipped;
            if (part.indices.empty()) continue;
            scene_.parts.push_back(std::move(part));
        }
    }
};

}  // namespace

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
    Loader loader(path, options);
    try {
        return loader.run();
    } catch (const SceneLoadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw SceneLoadError(path + ": out of memory while loading");
    } catch (const std::exception& e) {
        throw SceneLoadError(path + ": " + e.what());
    }
}

}  // namespace deepgi
