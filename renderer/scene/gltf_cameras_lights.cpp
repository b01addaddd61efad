// glTF loader, cameras and lights: glTF cameras and KHR_lights_punctual, placed by their node's world transform.
// Values are copied as the file has them; validateScene() (scene_validation.h) corrects or refuses bad ones once
// for the renderer and the path tracer alike. Camera transforms keep rotation and translation only.
#include "renderer/scene/gltf_reader.h"

#include <algorithm>

namespace deepgi {
namespace gltf {

void GltfReader::addCamera(const tinygltf::Node& node, const glm::mat4& world) {
    if (size_t(node.camera) >= model_.cameras.size()) {
        warn("node '" + node.name + "': camera " + std::to_string(node.camera) + " does not exist");
        return;
    }
    const auto& gc = model_.cameras[size_t(node.camera)];
    CameraDesc c;
    c.name = gc.name.empty() ? "camera" + std::to_string(scene_.cameras.size()) : gc.name;
    // Raw values: scene_validation.cpp decides what bad ones mean (shared with the path tracer's checks).
    if (gc.type == "orthographic") {
        c.perspective = false;
        c.xmag = float(gc.orthographic.xmag);
        c.ymag = float(gc.orthographic.ymag);
        c.znear = float(gc.orthographic.znear);
        c.zfar = float(gc.orthographic.zfar);
    } else {
        c.perspective = true;
        c.yfov = float(gc.perspective.yfov);
        c.aspectRatio = float(gc.perspective.aspectRatio);
        c.znear = float(gc.perspective.znear);
        c.zfar = float(gc.perspective.zfar);
    }
    c.cameraToWorld = world;
    c.node = currentNode_;
    scene_.cameras.push_back(std::move(c));
}

void GltfReader::addLight(const tinygltf::Node& node, int li, const glm::mat4& world) {
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
    for (int c = 0; c < 3 && size_t(c) < gl.color.size(); ++c) l.color[c] = float(gl.color[size_t(c)]);
    l.intensity = float(gl.intensity);
    l.range = float(gl.range);
    l.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    l.direction = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));  // normalised by validateLight
    l.node = currentNode_;
    if (l.type == LightType::Spot) {
        l.outerConeAngle = float(gl.spot.outerConeAngle);
        l.innerConeAngle = float(gl.spot.innerConeAngle);
    }
    scene_.lights.push_back(std::move(l));
}

}  // namespace gltf
}  // namespace deepgi
