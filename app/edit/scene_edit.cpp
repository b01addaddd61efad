#include "app/edit/scene_edit.h"

#include "renderer/renderer.h"
#include "renderer/scene/lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi::edit {

bool Selection::contains(int item) const { return std::find(items.begin(), items.end(), item) != items.end(); }

void Selection::click(int item, bool extend) {
    if (!extend) {
        items.clear();
        active = -1;
        if (item != -1) items.push_back(item), active = item;
        return;
    }
    if (item == -1) return;  // Shift-click on nothing keeps the selection
    if (!contains(item)) {
        items.push_back(item);
        active = item;
    } else if (active != item) {
        active = item;
    } else {
        items.erase(std::find(items.begin(), items.end(), item));
        active = -1;
    }
}

Trs toTrs(const Transform& t) { return {t.translation, t.rotation, t.scale}; }
Transform toTransform(const Trs& t) {
    Transform r;
    r.translation = t.translation;
    r.rotation = t.rotation;
    r.scale = t.scale;
    return r;
}

EditState captureState(const Scene& scene, const Settings& settings, const Selection& selection) {
    EditState s;
    for (const auto& n : scene.nodes) {
        s.locals.push_back(toTrs(n.local));
        s.visible.push_back(n.visible ? 1 : 0);
    }
    for (const auto& l : scene.lights) s.lights.push_back({l.color, l.intensity});
    s.sunAzimuth = settings.sunAzimuth;
    s.sunElevation = settings.sunElevation;
    s.sunIntensity = settings.sunIntensity;
    s.selection = selection;
    return s;
}

namespace {
// Does `node` lie in the subtree of any of `roots` (itself included)?
bool below(const Scene& scene, int node, const std::vector<int>& roots) {
    for (int n = node, guard = 0; n >= 0 && n < int(scene.nodes.size()) && guard <= int(scene.nodes.size()); n = scene.nodes[size_t(n)].parent, ++guard)
        if (std::find(roots.begin(), roots.end(), n) != roots.end()) return true;
    return false;
}
bool placesLight(const Scene& scene, const std::vector<int>& roots) {
    for (const auto& l : scene.lights)
        if (l.node >= 0 && below(scene, l.node, roots)) return true;
    return false;
}
}  // namespace

unsigned applyState(Scene& scene, Settings& settings, Selection& selection, const EditState& s) {
    unsigned changes = 0;
    std::vector<int> moved, shown;
    for (size_t i = 0; i < scene.nodes.size() && i < s.locals.size(); ++i) {
        SceneNode& n = scene.nodes[i];
        if (toTrs(n.local) != s.locals[i]) n.local = toTransform(s.locals[i]), moved.push_back(int(i));
        if (i < s.visible.size() && n.visible != (s.visible[i] != 0)) n.visible = s.visible[i] != 0, shown.push_back(int(i));
    }
    if (!moved.empty()) {
        scene.updateWorldTransforms();
        changes |= unsigned(SceneChange::Transforms);
        if (placesLight(scene, moved)) changes |= unsigned(SceneChange::Lights);
    }
    if (!shown.empty()) {
        changes |= unsigned(SceneChange::Visibility);
        if (placesLight(scene, shown)) changes |= unsigned(SceneChange::Lights);
    }
    for (size_t i = 0; i < scene.lights.size() && i < s.lights.size(); ++i) {
        Light& l = scene.lights[i];
        if (l.color != s.lights[i].color || l.intensity != s.lights[i].intensity) {
            l.color = s.lights[i].color;
            l.intensity = s.lights[i].intensity;
            changes |= unsigned(SceneChange::Lights);
        }
    }
    if (settings.sunAzimuth != s.sunAzimuth || settings.sunElevation != s.sunElevation || settings.sunIntensity != s.sunIntensity) {
        settings.sunAzimuth = s.sunAzimuth;
        settings.sunElevation = s.sunElevation;
        settings.sunIntensity = s.sunIntensity;
        if (scene.lights.empty()) changes |= unsigned(SceneChange::Lights);
    }
    selection = s.selection;
    return changes;
}

std::vector<int> transformRoots(const Scene& scene, const Selection& selection) {
    std::vector<int> nodes;
    for (int i : selection.items)
        if (i >= 0 && i < int(scene.nodes.size())) nodes.push_back(i);
    std::vector<int> roots;
    for (int n : nodes) {
        const int parent = scene.nodes[size_t(n)].parent;
        if (parent < 0 || !below(scene, parent, nodes)) roots.push_back(n);
    }
    return roots;
}

std::vector<TransformTarget> targetsOf(const Scene& scene, const std::vector<int>& nodes) {
    std::vector<TransformTarget> t;
    for (int n : nodes) {
        const SceneNode& node = scene.nodes[size_t(n)];
        TransformTarget target;
        target.local = toTrs(node.local);
        target.parentWorld = node.parent >= 0 ? scene.nodes[size_t(node.parent)].world : glm::mat4(1.0f);
        t.push_back(target);
    }
    return t;
}

glm::vec3 medianPoint(const Scene& scene, const std::vector<int>& nodes) {
    glm::vec3 sum(0.0f);
    for (int n : nodes) sum += glm::vec3(scene.nodes[size_t(n)].world[3]);
    return nodes.empty() ? sum : sum / float(nodes.size());
}

unsigned setLocals(Scene& scene, const std::vector<int>& nodes, const std::vector<Trs>& locals) {
    for (size_t i = 0; i < nodes.size() && i < locals.size(); ++i) scene.nodes[size_t(nodes[i])].local = toTransform(locals[i]);
    scene.updateWorldTransforms();
    return unsigned(SceneChange::Transforms) | (placesLight(scene, nodes) ? unsigned(SceneChange::Lights) : 0u);
}

unsigned setVisible(Scene& scene, int node, bool visible) {
    if (node < 0 || node >= int(scene.nodes.size()) || scene.nodes[size_t(node)].visible == visible) return 0;
    scene.nodes[size_t(node)].visible = visible;
    return unsigned(SceneChange::Visibility) | (placesLight(scene, {node}) ? unsigned(SceneChange::Lights) : 0u);
}

std::vector<int> everything(const Scene& scene) {
    std::vector<int> all;
    for (int i = 0; i < int(scene.nodes.size()); ++i) all.push_back(i);
    if (scene.lights.empty()) all.push_back(kDefaultSun);
    return all;
}

glm::quat rotationBetween(const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 u = glm::normalize(a), v = glm::normalize(b);
    const float c = glm::dot(u, v);
    if (c < -0.999999f) {  // opposite: any perpendicular axis
        glm::vec3 axis = glm::cross(glm::vec3(1.0f, 0.0f, 0.0f), u);
        if (glm::length(axis) < 1e-3f) axis = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), u);
        return glm::angleAxis(3.14159265f, glm::normalize(axis));
    }
    const glm::vec3 axis = glm::cross(u, v);
    return glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
}

glm::vec3 eulerDegrees(const glm::quat& q) {
    const glm::mat3 m = glm::mat3_cast(glm::normalize(q));  // m[column][row]
    const float r20 = std::clamp(m[0][2], -1.0f, 1.0f);
    float x, y, z;
    if (std::abs(r20) < 1.0f - 1e-6f) {
        y = std::asin(-r20);
        x = std::atan2(m[1][2], m[2][2]);
        z = std::atan2(m[0][1], m[0][0]);
    } else {  // gimbal lock: X and Z turn about the same axis; all of it goes to Z
        y = r20 < 0.0f ? 1.5707963f : -1.5707963f;
        x = 0.0f;
        z = std::atan2(-m[1][0], m[1][1]);
    }
    return glm::degrees(glm::vec3(x, y, z));
}

glm::quat fromEulerDegrees(const glm::vec3& d) {
    const glm::vec3 r = glm::radians(d);
    return glm::normalize(glm::angleAxis(r.z, glm::vec3(0, 0, 1)) * glm::angleAxis(r.y, glm::vec3(0, 1, 0)) *
                          glm::angleAxis(r.x, glm::vec3(1, 0, 0)));
}

glm::vec2 sunAngles(const glm::vec3& direction) {
    const glm::vec3 toSun = -glm::normalize(direction);
    float el = glm::degrees(std::asin(std::clamp(toSun.y, -1.0f, 1.0f)));
    float az = glm::degrees(std::atan2(toSun.x, toSun.z));
    if (az < 0.0f) az += 360.0f;
    if (az >= 360.0f) az -= 360.0f;
    el = std::clamp(el, 1.0f, 90.0f);
    return {az, el};
}

bool projectToView(const ToolView& view, const glm::vec3& p, glm::vec2& out) {
    const float w = std::max(view.width, 1.0f), h = std::max(view.height, 1.0f);
    const glm::vec4 clip = view.camera.projection(w / h) * view.camera.view() * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-12f) return false;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    out = glm::vec2((ndc.x + 1.0f) * 0.5f * w, (1.0f - ndc.y) * 0.5f * h);
    return std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f && ndc.z >= -1.0f && ndc.z <= 1.0f;
}

std::vector<LightIcon> lightIcons(const Scene& scene, const Settings& settings, const ToolView& view) {
    std::vector<LightIcon> icons;
    for (int i = 0; i < int(scene.lights.size()); ++i) {
        const Light& l = scene.lights[size_t(i)];
        if (l.node < 0 || !scene.nodeVisible(l.node)) continue;  // a fixed light (built in code) is not editable
        LightIcon icon;
        icon.item = l.node;
        icon.light = i;
        icon.type = l.type;
        icon.position = glm::vec3(scene.nodes[size_t(l.node)].world[3]);
        icon.direction = l.direction;
        icon.onScreen = projectToView(view, icon.position, icon.screen);
        icons.push_back(icon);
    }
    if (scene.lights.empty()) {
        LightIcon sun;
        sun.item = kDefaultSun;
        sun.type = LightType::Directional;
        sun.direction = defaultSunDirection(settings);
        const Aabb& b = scene.bounds;
        sun.position = (b.valid() ? b.center() : glm::vec3(0.0f)) - sun.direction * std::max(b.radius(), 0.5f) * 0.9f;
        sun.onScreen = projectToView(view, sun.position, sun.screen);
        icons.push_back(sun);
    }
    return icons;
}

int pickLight(const std::vector<LightIcon>& icons, const glm::vec2& pointer, float radius) {
    int best = -1;
    float bestD = radius;
    for (const auto& i : icons) {
        if (!i.onScreen) continue;
        const float d = glm::length(i.screen - pointer);
        if (d <= bestD) bestD = d, best = i.item;
    }
    return best;
}

}  // namespace deepgi::edit
