#pragma once
// Opens a scene file by its extension: .obj through loadObj (obj_loader.h), anything else (.gltf, .glb) through
// loadGltf (gltf_loader.h). Every command that opens a scene path goes through here.
#include "renderer/scene/gltf_loader.h"

#include <string>

namespace deepgi {

// True when `path` ends in .obj (any case).
bool isObjPath(const std::string& path);

Scene loadScene(const std::string& path, const GltfLoadOptions& options = {});

}  // namespace deepgi
