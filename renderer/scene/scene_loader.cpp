#include "renderer/scene/scene_loader.h"

#include "renderer/scene/obj_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace deepgi {

bool isObjPath(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".obj";
}

Scene loadScene(const std::string& path, const GltfLoadOptions& options) {
    return isObjPath(path) ? loadObj(path, options) : loadGltf(path, options);
}

}  // namespace deepgi
