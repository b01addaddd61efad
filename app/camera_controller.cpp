#include "app/camera_controller.h"

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

namespace {
constexpr float kHalfPi = glm::half_pi<float>();
constexpr float kOrbitRadiansPerPixel = 0.006f;
}  // namespace

glm::vec3 CameraController::forward() const {
    // Direction from the target to the eye is (cos p sin y, sin p, cos p cos y); forward is its opposite.
    return -glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
}
glm::vec3 CameraController::right() const { return glm::vec3(std::cos(yaw), 0.0f, -std::sin(yaw)); }
glm::vec3 CameraController::up() const { return glm::cross(right(), forward()); }
glm::vec3 CameraController::eye() const { return target - forward() * distance; }

void CameraController::setFromCamera(const Camera& cam, float pivotDistance) {
    const glm::vec3 f = cam.forward();
    pitch = std::asin(std::clamp(-f.y, -1.0f, 1.0f));
    yaw = std::atan2(-f.x, -f.z);
    distance = std::max(pivotDistance, 1e-4f);
    target = cam.position() + f * distance;
    perspective = cam.perspective;
    if (cam.perspective) yfov = cam.yfov;
    else distance = std::max(cam.orthoHalfHeight / std::tan(0.5f * yfov), 1e-4f);
}

void CameraController::frame(const Aabb& b) {
    const float r = std::max(b.radius(), 1e-3f);
    target = b.valid() ? b.center() : glm::vec3(0.0f);
    distance = r / std::sin(0.5f * yfov) * 1.05f;
}

void CameraController::setAxisView(AxisView v) {
    switch (v) {
        case AxisView::Front: yaw = 0.0f; pitch = 0.0f; break;
        case AxisView::Back: yaw = glm::pi<float>(); pitch = 0.0f; break;
        case AxisView::Right: yaw = kHalfPi; pitch = 0.0f; break;
        case AxisView::Left: yaw = -kHalfPi; pitch = 0.0f; break;
        case AxisView::Top: yaw = 0.0f; pitch = kHalfPi; break;
        case AxisView::Bottom: yaw = 0.0f; pitch = -kHalfPi; break;
    }
}

void CameraController::orbit(float dx, float dy) {
    yaw -= dx * kOrbitRadiansPerPixel;
    pitch = std::clamp(pitch + dy * kOrbitRadiansPerPixel, -kHalfPi, kHalfPi);
    yaw = std::remainder(yaw, 2.0f * glm::pi<float>());
}

void CameraController::pan(float dx, float dy, float viewportHeight) {
    const float worldPerPixel = 2.0f * distance * std::tan(0.5f * yfov) / std::max(viewportHeight, 1.0f);
    target += (-dx * right() + dy * up()) * worldPerPixel;
}

void CameraController::zoomSteps(float steps) { distance = std::max(distance * std::pow(1.2f, -steps), 1e-4f); }
void CameraController::zoomDrag(float dy) { distance = std::max(distance * std::exp(dy * 0.01f), 1e-4f); }

void CameraController::look(float dx, float dy) {
    const glm::vec3 e = eye();
    yaw -= dx * kOrbitRadiansPerPixel * 0.5f;
    pitch = std::clamp(pitch + dy * kOrbitRadiansPerPixel * 0.5f, -kHalfPi + 1e-3f, kHalfPi - 1e-3f);
    target = e + forward() * distance;
}

void CameraController::moveEye(const glm::vec3& d) { target += right() * d.x + up() * d.y + forward() * d.z; }

Camera CameraController::camera(const Aabb& bounds) const {
    Camera c;
    c.name = "viewport";
    c.perspective = perspective;
    c.yfov = yfov;
    c.orthoHalfHeight = distance * std::tan(0.5f * yfov);
    glm::vec3 e = eye();
    // Orthographic: the eye backs off so that the whole scene is in front of it (the view size does not change).
    if (!perspective) e = target - forward() * (distance + 2.0f * std::max(bounds.radius(), 1e-3f));
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(right(), 0.0f);
    m[1] = glm::vec4(up(), 0.0f);
    m[2] = glm::vec4(-forward(), 0.0f);
    m[3] = glm::vec4(e, 1.0f);
    c.cameraToWorld = m;
    fitClipPlanes(c, bounds);
    return c;
}

nlohmann::json CameraController::toJson() const {
    return {{"target", {target.x, target.y, target.z}}, {"distance", distance}, {"yaw", yaw}, {"pitch", pitch},
            {"perspective", perspective}, {"yfov", yfov}};
}

void CameraController::fromJson(const nlohmann::json& j) {
    if (j.contains("target") && j["target"].is_array() && j["target"].size() == 3)
        target = glm::vec3(j["target"][0].get<float>(), j["target"][1].get<float>(), j["target"][2].get<float>());
    distance = std::max(j.value("distance", distance), 1e-4f);
    yaw = j.value("yaw", yaw);
    pitch = std::clamp(j.value("pitch", pitch), -kHalfPi, kHalfPi);
    perspective = j.value("perspective", perspective);
    yfov = std::clamp(j.value("yfov", yfov), 0.01f, 3.0f);
}

}  // namespace deepgi
