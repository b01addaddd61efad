#pragma once
// glTF 2.0 (.gltf and .glb) -> Scene, through tinygltf. Every error names the file and the problem.
#include "renderer/scene/scene.h"

#include <stdexcept>
#include <functional>
#include <string>

namespace deepgi {

struct SceneLoadError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The loading limits of every scene format (loadObj takes the same, see scene_loader.h).
struct GltfLoadOptions {
    // Images whose header claims more pixels than this are refused before any allocation.
    uint64_t maxImagePixels = uint64_t(16384) * 16384;
    // Total vertices + indices accepted from one file (guards counts that overflow).
    uint64_t maxElements = uint64_t(1) << 28;
    // Bytes the load may hold at once (buffers, decoded images, geometry of every mesh instance), counted before
    // each allocation; past it the load fails naming the element and the size it would need. The setting
    // load.memory_budget (MiB) feeds this through gltfLoadOptions().
    uint64_t memoryBudget = uint64_t(4096) << 20;
    // Larger textures are downscaled at load (with a warning) to fit; 16384 is GL_MAX_TEXTURE_SIZE on llvmpipe
    // and the most common limit on GPUs.
    int maxTextureSize = 16384;
    // Called as the load advances: a stage ("reading", "materials", "meshes", "done") and the fraction of the whole
    // load done (0..1, never decreasing). Empty = quiet. For the commands' progress line on big scenes.
    std::function<void(const char* stage, double fraction)> progress;
    void report(const char* stage, double fraction) const {
        if (progress) progress(stage, fraction);
    }
};

struct Settings;
// The options that come from the settings (load.memory_budget).
GltfLoadOptions gltfLoadOptions(const Settings& settings);

// Throws SceneLoadError("<path>: <problem>") for anything that makes the scene unusable; recoverable problems
// (missing/corrupt image -> fallback colour, BLEND -> MASK, NaN vertices skipped, ...) go to Scene::warnings.
Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});

}  // namespace deepgi
