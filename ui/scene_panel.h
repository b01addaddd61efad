#pragma once
// The sidebar's Item tab: the outliner (the scene's node tree with glTF names, meshes, lights, cameras, visibility
// toggles) and Blender's N panel for the active item (location, rotation in degrees, scale; a light's colour and
// intensity; a directional light's direction on a sphere widget). It only draws and reports what was edited.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>
#include <imgui.h>

#include <map>
#include <string>
#include <vector>

namespace deepgi::ui {

constexpr int kSunItem = -2;  // the default sun's row (the scene has no lights: the light.sun_* settings)

struct ScenePanelModel {
    const Scene* scene = nullptr;
    const std::vector<int>* selected = nullptr;  // node indices or kSunItem
    int active = -1;
    // The active item's values (the app fills them; the panel edits copies).
    bool hasTransform = false;
    glm::vec3 location{0.0f}, rotationDegrees{0.0f}, scale{1.0f};
    int light = -1;                 // index into scene->lights, or -1; the default sun: sun below
    bool sun = false;               // the active item is the default sun
    glm::vec3 color{1.0f};
    float intensity = 0.0f;
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional lights: the way light travels
    size_t undoSteps = 0, redoSteps = 0;
    std::string lastUndo;
};

struct ScenePanelState {
    std::map<std::string, glm::vec4> rects;  // "row NAME", "eye NAME" -> x0 y0 x1 y1 (window units, for scripts)
};

struct ScenePanelActions {
    bool clicked = false;    // an outliner row: `click` (node or kSunItem), Shift/Ctrl held: extend
    int click = -1;
    bool extend = false;
    int toggleVisible = -1;  // a node's eye
    bool transformEdited = false;
    glm::vec3 location{0.0f}, rotationDegrees{0.0f}, scale{1.0f};
    bool lightEdited = false;
    glm::vec3 color{1.0f};
    float intensity = 0.0f;
    bool directionEdited = false;
    glm::vec3 direction{0.0f};
    bool undo = false, redo = false;
};

ScenePanelActions drawScenePanel(const ScenePanelModel& m, ScenePanelState& st);
// The sky seen from above (+X right, +Z down): a dot where the light comes from; a drag moves it. Returns true
// when `direction` (the way light travels, unit) changed. Directions from below the horizon show on the rim.
bool drawSunSphere(const char* id, glm::vec3& direction, float size);

}  // namespace deepgi::ui
