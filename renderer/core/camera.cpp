#include "renderer/core/camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace deepgi {

glm::mat4 Camera::view() const { return glm::inverse(cameraToWorld); }

glm::mat4 Camera::projection(float aspect) const {
    aspect = std::max(aspect, 1e-6f);
    if (perspective) return glm::perspective(yfov, aspect, znear, zfar);
    const float h = orthoHalfHeight, w = h * aspect;
    return glm::ortho(-w, w, -h, h, znear, zfar);
}

void Camera::primaryRay(float x, float y, int width, int height, glm::vec3& origin, glm::vec3& dir) const {
    const float aspect = float(width) / float(std::max(height, 1));
    const float ndcX = 2.0f * x / float(width) - 1.0f;
    const float ndcY = 1.0f - 2.0f * y / float(height);
    glm::vec3 o, d;
    if (perspective) {
        const float t = std::tan(0.5f * yfov);
        o = glm::vec3(0.0f);
        d = glm::normalize(glm::vec3(ndcX * t * aspect, ndcY * t, -1.0f));
    } else {
        o = glm::vec3(ndcX * orthoHalfHeight * aspect, ndcY * orthoHalfHeight, 0.0f);
        d = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    origin = glm::vec3(cameraToWorld * glm::vec4(o, 1.0f));
    dir = glm::normalize(glm::vec3(cameraToWorld * glm::vec4(d, 0.0f)));
}

void fitClipPlanes(Camera& cam, const Aabb& b) {
    if (!b.valid()) { cam.znear = 0.05f; cam.zfar = 100.0f; return; }
    const glm::mat4 v = cam.view();
    float zmin = 1e30f, zmax = -1e30f;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 c((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
        float d = -(v * glm::vec4(c, 1.0f)).z;  // distance along the view axis
        zmin = std::min(zmin, d);
        zmax = std::max(zmax, d);
    }
    const float span = std::max(zmax - std::max(zmin, 0.0f), 1e-6f);
    // A margin relative to the distance as well: for a flat scene facing the camera (span 0) an absolute 1e-6 left
    // the surface at depth 1.0 in float, where it reads as sky (tests/test_hard_cases.cpp, back faces / full screen).
    cam.zfar = zmax + 0.05f * span + 1e-3f * std::abs(zmax) + 1e-6f;
    // Near: never behind the camera; at least 1/10000 of far for precision.
    cam.znear = std::max({zmin * 0.9f, cam.zfar * 1e-4f, 1e-7f});
    if (cam.znear >= cam.zfar) cam.znear = cam.zfar * 1e-4f;
}

Camera framingCamera(const Aabb& b) {
    Camera cam;
    cam.name = "";
    glm::vec3 c = b.valid() ? b.center() : glm::vec3(0.0f);
    float r = std::max(b.radius(), 1e-3f);
    cam.yfov = glm::radians(50.0f);
    const float dist = r / std::sin(0.5f * cam.yfov) * 1.05f;
    glm::vec3 dir = glm::normalize(glm::vec3(0.55f, 0.45f, 1.0f));
    glm::vec3 eye = c + dir * dist;
    cam.cameraToWorld = glm::inverse(glm::lookAt(eye, c, glm::vec3(0.0f, 1.0f, 0.0f)));
    fitClipPlanes(cam, b);
    return cam;
}

Camera cameraFromDesc(const CameraDesc& d, const Aabb& bounds) {
    Camera cam;
    cam.name = d.name;
    cam.cameraToWorld = d.cameraToWorld;
    cam.perspective = d.perspective;
    cam.yfov = d.yfov;
    cam.orthoHalfHeight = d.ymag;
    cam.znear = d.znear > 0.0f ? d.znear : 0.05f;
    if (d.zfar > cam.znear) cam.zfar = d.zfar;
    else {
        Camera fitted = cam;
        fitClipPlanes(fitted, bounds);
        cam.zfar = std::max(fitted.zfar, cam.znear * 2.0f);
    }
    return cam;
}

Camera selectCamera(const Scene& scene, const std::string& name) {
    if (name.empty()) return scene.cameras.empty() ? framingCamera(scene.bounds) : cameraFromDesc(scene.cameras[0], scene.bounds);
    for (const auto& c : scene.cameras)
        if (c.name == name) return cameraFromDesc(c, scene.bounds);
    std::string names;
    for (const auto& c : scene.cameras) names += (names.empty() ? "" : ", ") + c.name;
    throw std::runtime_error("no camera named '" + name + "' in " +
                             (scene.sourcePath.empty() ? std::string("the scene") : scene.sourcePath) +
                             " (available: " + (names.empty() ? "none" : names) + ")");
}

nlohmann::json cameraToJson(const Camera& cam) {
    nlohmann::json m = nlohmann::json::array();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m.push_back(cam.cameraToWorld[c][r]);
    return {{"name", cam.name}, {"camera_to_world", m}, {"perspective", cam.perspective}, {"yfov", cam.yfov},
            {"ortho_half_height", cam.orthoHalfHeight}, {"znear", cam.znear}, {"zfar", cam.zfar}};
}

Camera cameraFromJson(const nlohmann::json& j, const std::string& source) {
    auto fail = [&](const std::string& why) { throw std::runtime_error(source + ": " + why); };
    if (!j.is_object()) fail("not a JSON object");
    auto number = [&](const char* key) {
        if (!j.contains(key)) fail(std::string("missing \"") + key + "\"");
        if (!j[key].is_number()) fail(std::string("\"") + key + "\" is not a number");
        const double v = j[key].get<double>();
        if (!std::isfinite(v)) fail(std::string("\"") + key + "\" is not finite");
        return float(v);
    };
    Camera c;
    c.name = j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>() : std::string("camera file");
    if (!j.contains("camera_to_world") || !j["camera_to_world"].is_array() || j["camera_to_world"].size() != 16)
        fail("\"camera_to_world\" must be an array of 16 numbers (column-major 4x4)");
    for (int i = 0; i < 16; ++i) {
        const auto& v = j["camera_to_world"][size_t(i)];
        if (!v.is_number() || !std::isfinite(v.get<double>())) fail("\"camera_to_world\"[" + std::to_string(i) + "] is not a finite number");
        c.cameraToWorld[i / 4][i % 4] = v.get<float>();
    }
    const glm::mat3 r(c.cameraToWorld);
    for (int a = 0; a < 3; ++a) {
        if (std::abs(glm::length(r[a]) - 1.0f) > 1e-3f) fail("\"camera_to_world\" axis " + std::to_string(a) + " is not of unit length");
        for (int b = a + 1; b < 3; ++b)
            if (std::abs(glm::dot(r[a], r[b])) > 1e-3f) fail("\"camera_to_world\" axes are not orthogonal");
    }
    const glm::vec4 last(c.cameraToWorld[0][3], c.cameraToWorld[1][3], c.cameraToWorld[2][3], c.cameraToWorld[3][3]);
    if (glm::length(last - glm::vec4(0, 0, 0, 1)) > 1e-5f) fail("\"camera_to_world\" last row must be 0 0 0 1");
    if (!j.contains("perspective") || !j["perspective"].is_boolean()) fail("\"perspective\" must be true or false");
    c.perspective = j["perspective"].get<bool>();
    c.yfov = number("yfov");
    c.orthoHalfHeight = number("ortho_half_height");
    c.znear = number("znear");
    c.zfar = number("zfar");
    if (c.perspective && !(c.yfov > 0.0f && c.yfov < 3.14159f)) fail("\"yfov\" must be in (0, pi) radians");
    if (!c.perspective && !(c.orthoHalfHeight > 0.0f)) fail("\"ortho_half_height\" must be positive");
    if (!(c.znear > 0.0f)) fail("\"znear\" must be positive");
    if (!(c.zfar > c.znear)) fail("\"zfar\" must be greater than \"znear\"");
    return c;
}

Camera loadCameraFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read camera file " + path);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw std::runtime_error("camera file " + path + " is not valid JSON (" + e.what() + ")");
    }
    return cameraFromJson(j, "camera file " + path);
}

Camera selectCamera(const Scene& scene, const std::string& name, const std::string& cameraFile) {
    return cameraFile.empty() ? selectCamera(scene, name) : loadCameraFile(cameraFile);
}

}  // namespace deepgi
