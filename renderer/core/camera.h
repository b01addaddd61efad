#pragma once
// Camera shared by the rasterizer and the path tracer: the same view, projection and pixel centres.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace deepgi {

struct Camera {
    std::string name;             // "" for the default framing camera
    glm::mat4 cameraToWorld{1.0f};  // looks down -Z, +Y up
    bool perspective = true;
    float yfov = glm::radians(60.0f);  // perspective
    float orthoHalfHeight = 1.0f;      // orthographic
    float znear = 0.05f, zfar = 100.0f;

    glm::vec3 position() const { return glm::vec3(cameraToWorld[3]); }
    glm::vec3 forward() const { return -glm::normalize(glm::vec3(cameraToWorld[2])); }
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;  // OpenGL clip space, depth in [-1, 1]

    // Ray through the centre of pixel (x, y), y = 0 the top row, for an image of width x height.
    void primaryRay(float x, float y, int width, int height, glm::vec3& origin, glm::vec3& dir) const;
};

// A camera that frames the whole scene from a 3/4 view.
Camera framingCamera(const Aabb& bounds);
// From a glTF camera; an infinite far plane becomes one past the scene bounds.
Camera cameraFromDesc(const CameraDesc& desc, const Aabb& bounds);
// name "" = the scene's first camera, or the framing camera when it has none. Unknown name throws
// std::runtime_error listing the available names.
Camera selectCamera(const Scene& scene, const std::string& name);
// A camera file (the viewer's capture writes one as camera.json): {"camera_to_world": 16 numbers, column-major,
// "perspective", "yfov" (radians), "ortho_half_height", "znear", "zfar"} plus optional "name", "width", "height".
nlohmann::json cameraToJson(const Camera& cam);
// Throws std::runtime_error naming `source` and the field for a missing or bad field (non-finite numbers, a matrix
// that is not a rotation and translation, fov outside (0, 180) degrees, znear <= 0 or zfar <= znear).
Camera cameraFromJson(const nlohmann::json& j, const std::string& source);
Camera loadCameraFile(const std::string& path);  // also throws naming the file when it cannot be read or parsed
// --camera-file wins over --camera: the one place every command picks its camera.
Camera selectCamera(const Scene& scene, const std::string& name, const std::string& cameraFile);
// Near/far planes that enclose the scene bounds as seen from this camera (keeps depth precision).
void fitClipPlanes(Camera& cam, const Aabb& bounds);

}  // namespace deepgi
