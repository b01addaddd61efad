#pragma once
// Blender-style viewport navigation (turntable about world +Y, the glTF up axis): orbit, pan, zoom, axis views,
// perspective/orthographic, fly mode. Pure maths on a small state; the viewer maps input events onto it.
#include "renderer/core/camera.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

namespace deepgi {

class CameraController {
public:
    // Orbit state: the view looks at `target` from `distance` along the direction given by yaw/pitch.
    glm::vec3 target{0.0f};
    float distance = 5.0f;
    float yaw = 0.0f;    // radians; 0 = camera on +Z looking towards -Z (Blender "front")
    float pitch = 0.0f;  // radians, [-pi/2, pi/2]; +pi/2 = looking straight down (Blender "top")
    bool perspective = true;
    float yfov = 0.8727f;  // 50 degrees

    enum class AxisView { Front, Back, Right, Left, Top, Bottom };

    // Adopts a camera (glTF or framing): its position and direction; the pivot is placed `pivotDistance` ahead.
    void setFromCamera(const Camera& cam, float pivotDistance);
    // Frames the bounds (Home): keeps the direction, centres the pivot, fits the bounding sphere.
    void frame(const Aabb& bounds);
    void setAxisView(AxisView v);
    void togglePerspective() { perspective = !perspective; }

    // Mouse deltas in window pixels; viewportHeight in the same units.
    void orbit(float dx, float dy);
    void pan(float dx, float dy, float viewportHeight);
    void zoomSteps(float steps);            // wheel notches: > 0 moves closer
    void zoomDrag(float dy);                // Ctrl+MMB drag
    // Fly: turns the view about the eye (mouse look), and moves the eye in view space (right, up, forward).
    void look(float dx, float dy);
    void moveEye(const glm::vec3& viewSpaceDelta);

    glm::vec3 eye() const;
    glm::vec3 forward() const;
    glm::vec3 right() const;
    glm::vec3 up() const;
    // The renderer's camera: clip planes fitted to the scene bounds (with room behind an orthographic eye).
    Camera camera(const Aabb& bounds) const;

    nlohmann::json toJson() const;
    void fromJson(const nlohmann::json& j);  // ignores missing fields
};

}  // namespace deepgi
