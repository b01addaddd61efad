#pragma once
// Wavefront OBJ + MTL -> Scene, through tinyobjloader. The same rules as glTF (scene_files.h): the MTL libraries
// and textures must lie inside the OBJ's folder, non-regular files are refused, memory is counted against the
// budget, and every error names the file.
//
// What is read: Kd (diffuse colour) and map_Kd, Ke and map_Ke (emission), d and map_d as an alpha mask (cutoff
// 0.5; map_d's luminance times its alpha becomes the base-colour texture's alpha). Backslashes in paths are folder
// separators. A missing texture drops it with one warning naming the file. Unsupported MTL features (bump and
// normal maps, specular, transmission, ...) get one warning each, naming the materials. OBJ has no face culling
// convention, so every material is double-sided. The file has no lights and no cameras: the renderer adds the
// default sun and a framing camera, as for a glTF without them.
#include "renderer/scene/gltf_loader.h"

#include <string>

namespace deepgi {

Scene loadObj(const std::string& path, const GltfLoadOptions& options = {});

}  // namespace deepgi
