#include "renderer/scene/scene_files.h"

#include <stb_image.h>
#include <stb_image_resize.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace deepgi {
namespace fs = std::filesystem;

namespace {
std::string mib(uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / double(1 << 20));
    return buf;
}
}  // namespace

std::string nonRegularKind(const fs::path& p) {
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);  // follows symlinks
    if (ec || !fs::exists(st)) return "";
    switch (st.type()) {
        case fs::file_type::regular: return "";
        case fs::file_type::directory: return "a directory";
        case fs::file_type::fifo: return "a FIFO (named pipe)";
        case fs::file_type::character: return "a character device";
        case fs::file_type::block: return "a block device";
        case fs::file_type::socket: return "a socket";
        default: return "not a regular file";
    }
}

std::vector<unsigned char> readSceneFile(const std::string& path, const std::string& kind) {
    auto fail = [&](const std::string& problem) { throw SceneLoadError(path + ": " + problem); };
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        if (fs::is_symlink(fs::symlink_status(path, ec))) fail("file not found (a symlink to a missing file)");
        fail("file not found");
    }
    if (fs::is_directory(path, ec)) fail("is a directory, not " + kind + " file");
    const std::string nonRegular = nonRegularKind(path);  // opening a FIFO would block forever
    if (!nonRegular.empty()) fail("is " + nonRegular + ", not a regular file");
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) fail("cannot open file");
    std::streamoff size = f.tellg();
    if (size < 0) fail("cannot determine the file size");
    if (uint64_t(size) >= uint64_t(UINT_MAX)) fail("file too large (4 GiB or more)");
    std::vector<unsigned char> data(static_cast<size_t>(size));
    f.seekg(0);
    if (size > 0 && !f.read(reinterpret_cast<char*>(data.data()), size)) fail("read error");
    return data;
}

SceneFolder::SceneFolder(const std::string& sceneFile) {
    std::error_code ec;
    const fs::path abs = fs::absolute(fs::path(sceneFile), ec);
    dir_ = (ec ? fs::path(sceneFile) : abs).lexically_normal().parent_path().string();
    while (dir_.size() > 1 && dir_.back() == '/') dir_.pop_back();
    if (dir_.empty()) dir_ = ".";
    canonical_ = fs::weakly_canonical(fs::path(dir_), ec);
    if (ec) canonical_ = fs::path(dir_);
}

std::string SceneFolder::problem(const std::string& rel) const {
    if (rel.find('\0') != std::string::npos)  // the OS would read the name only up to the NUL
        return "contains a NUL character (refused)";
    bool bad = rel.empty() || rel[0] == '/' || rel[0] == '\\';
    if (!bad) {
        for (const auto& part : fs::path(rel))
            if (part == "..") { bad = true; break; }
        if (rel.find('\\') != std::string::npos && rel.find("..") != std::string::npos) bad = true;
    }
    if (bad) return "escapes the scene folder (refused)";
    const fs::path full = fs::path(dir_ == "/" ? "" : dir_) / rel;
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(full, ec);
    if (!ec) {  // cannot resolve: reading it fails later with "cannot open"
        const fs::path relResolved = resolved.lexically_relative(canonical_);
        if (relResolved.empty() || *relResolved.begin() == "..")
            return "is a symlink that leads outside the scene folder, to '" + resolved.string() + "' (refused)";
    }
    const std::string kind = nonRegularKind(full);
    if (!kind.empty()) return "is " + kind + ", not a regular file (refused)";
    return "";
}

std::string SceneFolder::read(const std::string& rel, std::vector<unsigned char>& out) const {
    const std::string why = problem(rel);
    if (!why.empty()) return why;
    const fs::path full = fs::path(dir_) / rel;
    std::ifstream f(full, std::ios::binary | std::ios::ate);
    if (!f) return "is missing or cannot be opened";
    const std::streamoff size = f.tellg();
    if (size < 0 || uint64_t(size) > uint64_t(INT_MAX)) return "is too large (2 GiB or more)";
    out.resize(size_t(size));
    f.seekg(0);
    if (size > 0 && !f.read(reinterpret_cast<char*>(out.data()), size)) return "could not be read";
    return "";
}

void LoadBudget::reserve(uint64_t bytes, const std::string& what, bool kept) {
    if (bytes > limit_ || used_ > limit_ - bytes)
        throw SceneLoadError(path_ + ": " + what + " needs " + mib(bytes) + ", past the loading memory budget of " +
                             mib(limit_) + " (" + mib(used_) + " already in use; setting load.memory_budget)");
    peak_ = std::max(peak_, used_ + bytes);
    if (kept) used_ += bytes;
}

std::string decodeImage(const unsigned char* bytes, size_t size, const std::string& name,
                        const GltfLoadOptions& opt, LoadBudget& budget, Image& out,
                        std::vector<std::string>& warnings) {
    if (size == 0 || size > size_t(INT_MAX)) return "is empty or too large";
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp) || w <= 0 || h <= 0)
        return "is corrupt or in an unsupported format";
    if (uint64_t(w) * uint64_t(h) > opt.maxImagePixels)
        return "claims " + std::to_string(w) + "x" + std::to_string(h) + " pixels, more than the limit of " +
               std::to_string(opt.maxImagePixels);
    const uint64_t decodedBytes = uint64_t(w) * uint64_t(h) * 4;
    const int limit = std::max(1, opt.maxTextureSize);
    const bool downscale = w > limit || h > limit;
    // the longer side becomes the limit, the other keeps the aspect ratio (at least 1 texel)
    const auto side = [&](int v, int longest) {
        return v == longest ? limit : std::max(1, int(std::lround(double(v) * limit / double(longest))));
    };
    const int ow = downscale ? side(w, std::max(w, h)) : w, oh = downscale ? side(h, std::max(w, h)) : h;
    const uint64_t keptBytes = uint64_t(ow) * uint64_t(oh) * 4;
    // stb's buffer and our copy (or the downscaled one) exist at once
    budget.reserve(decodedBytes + keptBytes,
                   "image '" + name + "' (" + std::to_string(w) + "x" + std::to_string(h) + ")", false);
    int dw = 0, dh = 0, dc = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &dw, &dh, &dc, 4);
    if (!pixels) {
        const char* why = stbi_failure_reason();
        return std::string("could not be decoded (") + (why ? why : "unknown") + ")";
    }
    out = Image{};
    out.name = name;
    if (downscale && dw == w && dh == h) {
        // Larger than a texture may be: it would render black. Colour textures are sRGB, alpha is linear (channel 3).
        out.rgba8.resize(size_t(keptBytes));
        stbir_resize_uint8_srgb(pixels, dw, dh, 0, out.rgba8.data(), ow, oh, 0, 4, 3, 0);
        warnings.push_back("image '" + name + "' is " + std::to_string(w) + "x" + std::to_string(h) +
                           ", larger than the " + std::to_string(limit) + " texel texture limit; downscaled to " +
                           std::to_string(ow) + "x" + std::to_string(oh));
        out.width = ow;
        out.height = oh;
    } else {
        out.width = dw;
        out.height = dh;
        out.rgba8.assign(pixels, pixels + size_t(dw) * size_t(dh) * 4);
    }
    stbi_image_free(pixels);
    budget.reserve(out.rgba8.size(), "image '" + name + "'", true);
    return "";
}

}  // namespace deepgi
