#pragma once
// The editable part of a scene as plain data, for the viewer's undo and panels: node transforms and visibility,
// light colours and intensities, the default sun's settings, the selection. No GL: the unit tests use it directly.
//
// Undo covers every edit a user makes to the scene: transforms (G / R / S, the N panel), visibility, light edits
// (the default sun's direction and intensity included, although they live in the settings: a user drags the sun
// like any light) and the selection (as Blender does: Ctrl+Z after a click gives the old selection back). Other
// settings changes stay out: they are the renderer's knobs, not the scene.
#include "app/edit/transform_tool.h"
#include "renderer/core/settings.h"
#include "renderer/scene/scene.h"

#include <string>
#include <vector>

namespace deepgi::edit {

// The selection's item for the default sun (the renderer's light from light.sun_* when the scene has none).
constexpr int kDefaultSun = -2;

struct Selection {
    std::vector<int> items;  // node indices (or kDefaultSun), in the order they were selected
    int active = -1;         // the one the N panel shows: the last selected; -1 = none
    bool contains(int item) const;
    // A click: only `item` (-1: nothing). Shift (extend): an unselected item is added and made active, the active
    // one is deselected, another selected one becomes active (Blender's Shift-click).
    void click(int item, bool extend);
    void clear() { items.clear(), active = -1; }
    bool operator==(const Selection& o) const { return items == o.items && active == o.active; }
};

struct LightValues {
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    bool operator==(const LightValues& o) const { return color == o.color && intensity == o.intensity; }
};

struct EditState {
    std::vector<Trs> locals;       // per node
    std::vector<uint8_t> visible;  // per node
    std::vector<LightValues> lights;
    float sunAzimuth = 0.0f, sunElevation = 0.0f, sunIntensity = 0.0f;
    Selection selection;
    bool operator==(const EditState& o) const {
        return locals == o.locals && visible == o.visible && lights == o.lights && sunAzimuth == o.sunAzimuth &&
               sunElevation == o.sunElevation && sunIntensity == o.sunIntensity && selection == o.selection;
    }
};

Trs toTrs(const Transform& t);
Transform toTransform(const Trs& t);

EditState captureState(const Scene& scene, const Settings& settings, const Selection& selection);
// Puts a captured state back (world transforms recomputed). Returns the SceneChange bits the renderer needs
// (0: nothing the render reads changed, e.g. only the selection).
unsigned applyState(Scene& scene, Settings& settings, Selection& selection, const EditState& state);

// The selected nodes without a selected ancestor: a child moves with its parent, once.
std::vector<int> transformRoots(const Scene& scene, const Selection& selection);
std::vector<TransformTarget> targetsOf(const Scene& scene, const std::vector<int>& nodes);
// Blender's Median Point: the mean of the nodes' world origins.
glm::vec3 medianPoint(const Scene& scene, const std::vector<int>& nodes);
// New local transforms for `nodes` (world transforms recomputed). Returns the SceneChange bits: Transforms, and
// Lights when one of them places a light (or has one below it).
unsigned setLocals(Scene& scene, const std::vector<int>& nodes, const std::vector<Trs>& locals);
// Hides or shows a node. Returns the SceneChange bits (Visibility, and Lights when a light is below it).
unsigned setVisible(Scene& scene, int node, bool visible);
// Every node (and the default sun when the scene has no lights).
std::vector<int> everything(const Scene& scene);

// The shortest rotation taking direction a to direction b (half a turn about a perpendicular when opposite).
glm::quat rotationBetween(const glm::vec3& a, const glm::vec3& b);

// Euler angles in degrees, Blender's default XYZ order (R = Rz * Ry * Rx), and back.
glm::vec3 eulerDegrees(const glm::quat& q);
glm::quat fromEulerDegrees(const glm::vec3& degrees);

// The default sun's direction (the way light travels) <-> light.sun_azimuth / light.sun_elevation in degrees
// (renderer/scene/lighting.h's convention). An elevation outside the setting's range (1..90) is limited to it.
glm::vec2 sunAngles(const glm::vec3& direction);

// Where the viewport draws each light's icon and where a click selects it.
struct LightIcon {
    int item = -1;             // the light's node, or kDefaultSun
    int light = -1;            // index into Scene::lights (-1: the default sun)
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};  // world: the node's origin; the default sun: beyond the scene's bounds towards it
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec2 screen{0.0f};    // in the view's pointer units
    bool onScreen = false;
};
std::vector<LightIcon> lightIcons(const Scene& scene, const Settings& settings, const ToolView& view);
// The item of the icon nearest to the pointer within `radius` (pointer units); -1 = none.
int pickLight(const std::vector<LightIcon>& icons, const glm::vec2& pointer, float radius);
// World -> the view's pointer units; false behind the eye or outside the view.
bool projectToView(const ToolView& view, const glm::vec3& p, glm::vec2& out);

}  // namespace deepgi::edit
