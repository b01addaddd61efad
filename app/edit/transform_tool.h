#pragma once
// Blender's modal transform (G / R / S) as plain state: the pointer and keys in, each target's local TRS out. No GL
// and no window: the viewer feeds it its events, the unit tests drive it directly.
//
// Semantics (Blender 2.8+ with the Global transform orientation and the Median Point pivot):
//  - begin(G|R|S): the pointer's motion drives it. G moves in the view plane through the pivot (the selection
//    follows the pointer), R turns about the view axis by the pointer's angle around the pivot's projection, S scales
//    by the pointer's distance to it (past the pivot: negative).
//  - X / Y / Z constrain to that axis; Shift+X/Y/Z to the plane without it (R: the axis itself). The same key again
//    goes Global -> Local (the object's own axes) -> off; another axis key starts again at Global.
//  - Typed values replace the pointer: digits, '.', '-' (negates, anywhere), '/' (reciprocal), Backspace (deletes
//    the last character; once empty it leaves typing, back to the pointer), Tab (G: the next component). G without
//    an axis types X first (then Tab Y, Z), S uniform, R degrees. Typed R with an axis is right-handed about the
//    positive axis (R X 90: +90 degrees about +X, what the N panel then shows); without one it is clockwise on the
//    screen, as Blender's manual says.
//  - confirm() keeps the result; cancel() gives back the targets exactly as they were at begin().
#include "renderer/core/camera.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace deepgi::edit {

// A node's local transform (the scene's Transform has the same fields; the app converts).
struct Trs {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    glm::mat4 matrix() const;
    bool operator==(const Trs& o) const { return translation == o.translation && rotation == o.rotation && scale == o.scale; }
    bool operator!=(const Trs& o) const { return !(*this == o); }
};

// One thing the tool moves: its local TRS and its parent's world matrix (world = parentWorld * local).
struct TransformTarget {
    Trs local;
    glm::mat4 parentWorld{1.0f};
    glm::mat4 world() const { return parentWorld * local.matrix(); }
};

enum class ToolMode { None, Translate, Rotate, Scale };
enum class Orientation { Global, Local };

// What the pointer is mapped through: the camera of the viewport and its size in the pointer's units (window
// units, (0, 0) at the viewport's top-left corner).
struct ToolView {
    Camera camera;
    float width = 1.0f, height = 1.0f;
};

class TransformTool {
public:
    bool active() const { return mode_ != ToolMode::None; }
    ToolMode mode() const { return mode_; }
    // Starts a transform of the targets about the pivot (world space) with the pointer at `pointer`. A transform
    // already running is cancelled first. No targets: nothing starts (returns false).
    bool begin(ToolMode mode, const std::vector<TransformTarget>& targets, const glm::vec3& pivot, const ToolView& view,
               const glm::vec2& pointer);
    void setView(const ToolView& view) { view_ = view; }
    void pointer(const glm::vec2& at);
    // Axis 0/1/2 = X/Y/Z; plane = Shift (the plane without that axis).
    void axis(int a, bool plane);
    // A typed character: '0'..'9', '.', '-', '/'. Returns false for anything else (the caller passes it on).
    bool type(char c);
    void backspace();
    void tab();
    // The targets' local transforms now (the same order as begin()'s).
    std::vector<Trs> current() const;
    std::vector<Trs> confirm();  // ends the transform: the result
    std::vector<Trs> cancel();   // ends it: the targets exactly as they were
    const std::vector<TransformTarget>& original() const { return targets_; }

    // The constraint: -1 none, else the axis (plane: the one left out).
    int constraintAxis() const { return axis_; }
    bool constraintPlane() const { return plane_; }
    Orientation orientation() const { return orient_; }
    bool typing() const { return typing_; }
    // Blender's header line: what is applied now and how ("Move  X 2  global | ...").
    std::string header() const;
    // The pointer-driven amount now (translation in world units along the constraint, degrees, factor): for tests.
    glm::vec3 amount() const;

private:
    glm::vec3 worldAxis(int target, int a) const;  // constraint axis a of target i in world space (unit)
    glm::vec3 translationOf(int target) const;     // world-space offset for target i
    void rayAt(const glm::vec2& p, glm::vec3& o, glm::vec3& d) const;
    glm::vec2 project(const glm::vec3& p) const;   // world -> pointer units
    float typedValue(int component, float untyped) const;
    int components() const;

    ToolMode mode_ = ToolMode::None;
    std::vector<TransformTarget> targets_;
    glm::vec3 pivot_{0.0f};
    ToolView view_;
    glm::vec2 start_{0.0f}, at_{0.0f};
    float angle_ = 0.0f;  // the pointer's turn about the pivot so far (radians, counter-clockwise on the screen)
    int axis_ = -1;
    bool plane_ = false;
    Orientation orient_ = Orientation::Global;
    bool typing_ = false;
    std::string text_[3];
    bool negate_[3] = {false, false, false}, reciprocal_[3] = {false, false, false};
    int component_ = 0;
};

// The world rotation of a matrix without its scale (columns normalised, a mirror folded into the X column).
glm::quat rotationOf(const glm::mat4& m);

}  // namespace deepgi::edit
