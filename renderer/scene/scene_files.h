#pragma once
// The file rules every scene loader (glTF, OBJ) applies, in one place so the formats never disagree:
//   * the scene file itself must be a regular file (a FIFO would block the read forever), under 4 GiB;
//   * every file it refers to (buffers, images, MTL libraries, textures) must lie inside the scene's folder, both as
//     written (no absolute path, no "..") and after every symlink on the way is resolved, and be a regular file;
//   * memory is counted against GltfLoadOptions::memoryBudget before each large allocation;
//   * images are decoded with stb_image after their header is checked against the pixel limit, and downscaled
//     (with a warning) past the texture size limit.
#include "renderer/scene/gltf_loader.h"

#include <cstdint>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

namespace deepgi {

// "a FIFO (named pipe)" etc. for anything that is not a regular file; "" for a regular file or one that is absent.
// Runs a loader: a failure becomes one SceneLoadError naming the file (running out of memory included).
template <class Reader>
Scene runSceneReader(const std::string& path, Reader& reader) {
    try {
        return reader.run();
    } catch (const SceneLoadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw SceneLoadError(path + ": out of memory while loading");
    } catch (const std::exception& e) {
        throw SceneLoadError(path + ": " + e.what());
    }
}

std::string nonRegularKind(const std::filesystem::path& p);

// Reads the scene file `path` whole; throws SceneLoadError("<path>: <problem>") when it is absent, a directory,
// not a regular file, 4 GiB or larger, or unreadable. `kind` names the format in messages ("a glTF", "an OBJ").
std::vector<unsigned char> readSceneFile(const std::string& path, const std::string& kind);

// The folder a scene file lives in, and the check that confines the files it names to it.
class SceneFolder {
public:
    explicit SceneFolder(const std::string& sceneFile);
    const std::string& dir() const { return dir_; }  // absolute, no trailing '/'
    // "" when `rel` (relative to dir(); '/' separated) may be read; otherwise why not, ending in "(refused)".
    // An absent file is not refused here (reading it reports "cannot open").
    std::string problem(const std::string& rel) const;
    // Reads dir()/rel into `out`; "" on success, otherwise why not (refused, missing, unreadable, too large).
    std::string read(const std::string& rel, std::vector<unsigned char>& out) const;

private:
    std::string dir_;
    std::filesystem::path canonical_;  // dir_ with every symlink resolved
};

// Bytes a load may hold, counted before each allocation; past the budget the load fails naming `what`.
class LoadBudget {
public:
    LoadBudget(std::string path, uint64_t limit) : path_(std::move(path)), limit_(limit) {}
    // kept: the bytes stay for the rest of the load; otherwise they are a transient peak on top of what is kept.
    void reserve(uint64_t bytes, const std::string& what, bool kept);
    uint64_t peak() const { return peak_; }

private:
    std::string path_;
    uint64_t limit_, used_ = 0, peak_ = 0;
};

// Decodes an encoded image (PNG, JPEG, ... through stb_image) named `name` into `out` (RGBA8, row 0 the top).
// Returns "" on success, otherwise why it could not be used (corrupt, too many pixels, ...); a downscale to
// options.maxTextureSize is reported in `warnings`. The decoded bytes are counted against `budget`.
std::string decodeImage(const unsigned char* bytes, size_t size, const std::string& name,
                        const GltfLoadOptions& options, LoadBudget& budget, Image& out,
                        std::vector<std::string>& warnings);

}  // namespace deepgi
