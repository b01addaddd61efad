#pragma once
// Saves a Scene as glTF 2.0 with tinygltf's writer: the node tree (TRS), one mesh per node with parts (vertices in
// the node's local space), materials, textures and images (PNG), KHR_lights_punctual lights, cameras, animations.
// Hidden nodes carry KHR_node_visibility { "visible": false }.
#include "renderer/scene/scene.h"

#include <string>

namespace deepgi {

// .glb by extension (case-insensitive), else .gltf with a .bin beside it. Throws std::runtime_error naming the
// file and the problem.
void saveGltf(const Scene& scene, const std::string& path);

}  // namespace deepgi
