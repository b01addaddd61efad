// The Item tab: the outliner and the N panel (see scene_panel.h).
#include "ui/scene_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace deepgi::ui {

namespace {

const char* lightTypeName(LightType t) {
    return t == LightType::Directional ? "sun" : t == LightType::Point ? "point light" : "spot light";
}

void rememberRect(ScenePanelState& st, const std::string& key) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    st.rects[key] = glm::vec4(a.x, a.y, b.x, b.y);
}

bool isSelected(const ScenePanelModel& m, int item) {
    return m.selected && std::find(m.selected->begin(), m.selected->end(), item) != m.selected->end();
}

void outlinerRow(const ScenePanelModel& m, ScenePanelState& st, ScenePanelActions& act, int n, int depth) {
    const Scene& s = *m.scene;
    if (depth > 64) return;  // a cycle in a scene built in code: the loader rejects them in files
    const SceneNode& node = s.nodes[size_t(n)];
    ImGui::PushID(n);
    // The eye: visible or hidden (a hidden parent hides its children: theirs are drawn dimmed).
    const bool shown = s.nodeVisible(n);
    if (ImGui::SmallButton(node.visible ? "o" : "-")) act.toggleVisible = n;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip(node.visible ? "Visible: click to hide (H hides the selection)" : "Hidden: click to show");
    rememberRect(st, "eye " + std::to_string(n));
    ImGui::SameLine();
    std::string label = node.name;
    if (!node.parts.empty()) label += "  [mesh" + (node.parts.size() > 1 ? " x" + std::to_string(node.parts.size()) : std::string()) + "]";
    if (node.light >= 0 && node.light < int(s.lights.size())) label += std::string("  [") + lightTypeName(s.lights[size_t(node.light)].type) + "]";
    if (node.camera >= 0) label += "  [camera]";
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth | ImGuiTreeNodeFlags_DefaultOpen;
    if (node.children.empty()) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
    if (isSelected(m, n)) flags |= ImGuiTreeNodeFlags_Selected;
    if (!shown) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    const bool open = ImGui::TreeNodeEx("##node", flags, "%s%s", m.active == n ? "> " : "", label.c_str());
    if (!shown) ImGui::PopStyleColor();
    rememberRect(st, "row " + std::to_string(n));
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) {
        act.clicked = true;
        act.click = n;
        act.extend = ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl;
    }
    if (open && !node.children.empty()) {
        for (int c : node.children)
            if (c >= 0 && c < int(s.nodes.size())) outlinerRow(m, st, act, c, depth + 1);
        ImGui::TreePop();
    }
    ImGui::PopID();
}

}  // namespace

bool drawSunSphere(const char* id, glm::vec3& direction, float size) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(id, ImVec2(size, size));
    const float r = size * 0.5f - 2.0f;
    const ImVec2 c(p0.x + size * 0.5f, p0.y + size * 0.5f);
    // The sky from above, shaded like a ball: the horizon at the rim, the zenith in the middle.
    for (int i = 8; i >= 1; --i) {
        const int g = 40 + 12 * (8 - i);
        dl->AddCircleFilled(c, r * float(i) / 8.0f, IM_COL32(g / 2, g, std::min(255, g * 2), 255), 48);
    }
    dl->AddCircle(c, r, IM_COL32(200, 200, 200, 255), 48);
    dl->AddText(ImVec2(c.x + r - 10.0f, c.y - 7.0f), IM_COL32(255, 120, 120, 255), "X");
    dl->AddText(ImVec2(c.x - 4.0f, c.y + r - 16.0f), IM_COL32(120, 160, 255, 255), "Z");
    bool changed = false;
    if (ImGui::IsItemActive()) {
        const ImVec2 mp = ImGui::GetIO().MousePos;
        glm::vec2 d((mp.x - c.x) / r, (mp.y - c.y) / r);
        const float l = glm::length(d);
        if (l > 0.999f) d *= 0.999f / l;  // on the sphere: the horizon at most
        const glm::vec3 toLight(d.x, std::sqrt(std::max(0.0f, 1.0f - glm::dot(d, d))), d.y);
        const glm::vec3 nd = -glm::normalize(toLight);
        if (nd != direction) direction = nd, changed = true;
    }
    const glm::vec3 toLight = -glm::normalize(direction);
    glm::vec2 d(toLight.x, toLight.z);
    const float l = glm::length(d);
    const bool below = toLight.y < 0.0f;
    if (below && l > 0.0f) d /= l;  // below the horizon: on the rim, hollow
    const ImVec2 dot(c.x + d.x * r, c.y + d.y * r);
    if (below) dl->AddCircle(dot, 5.0f, IM_COL32(255, 220, 90, 255), 16, 2.0f);
    else dl->AddCircleFilled(dot, 5.0f, IM_COL32(255, 220, 90, 255), 16);
    dl->AddLine(c, dot, IM_COL32(255, 220, 90, 160), 1.0f);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Where the light comes from, the sky seen from above: drag the dot");
    return changed;
}

ScenePanelActions drawScenePanel(const ScenePanelModel& m, ScenePanelState& st) {
    ScenePanelActions act;
    st.rects.clear();
    if (!m.scene) return act;
    const Scene& s = *m.scene;
    ImGui::TextDisabled("Outliner");
    ImGui::BeginChild("outliner", ImVec2(0.0f, std::min(220.0f, 30.0f + 22.0f * float(s.nodes.size() + 1))), true);
    if (s.lights.empty()) {
        ImGui::PushID("sun");
        ImGui::SmallButton("o");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("The default sun is always on: set its intensity to 0 to turn it off");
        ImGui::SameLine();
        ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen | ImGuiTreeNodeFlags_SpanAvailWidth;
        if (isSelected(m, kSunItem)) flags |= ImGuiTreeNodeFlags_Selected;
        ImGui::TreeNodeEx("##sun", flags, "%sSun  [default: light.sun_* settings]", m.active == kSunItem ? "> " : "");
        rememberRect(st, "row sun");
        if (ImGui::IsItemClicked()) {
            act.clicked = true;
            act.click = kSunItem;
            act.extend = ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl;
        }
        ImGui::PopID();
    }
    for (int r : s.roots)
        if (r >= 0 && r < int(s.nodes.size())) outlinerRow(m, st, act, r, 0);
    ImGui::EndChild();
    ImGui::TextDisabled("%zu selected", m.selected ? m.selected->size() : size_t(0));
    ImGui::SameLine();
    ImGui::BeginDisabled(m.undoSteps == 0);
    if (ImGui::SmallButton("Undo")) act.undo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(m.redoSteps == 0);
    if (ImGui::SmallButton("Redo")) act.redo = true;
    ImGui::EndDisabled();
    if (!m.lastUndo.empty()) {
        ImGui::SameLine();
        ImGui::TextDisabled("last: %s", m.lastUndo.c_str());
    }
    ImGui::Separator();

    // ---- N panel ----
    if (m.active == -1) {
        ImGui::TextDisabled("Click an object (viewport or outliner) to edit it. G / R / S move, rotate, scale it;");
        ImGui::TextDisabled("X / Y / Z constrain, type a value, Enter confirms, Esc cancels; Ctrl+Z undoes.");
        return act;
    }
    const bool isNode = m.active >= 0 && m.active < int(s.nodes.size());
    ImGui::Text("%s", isNode ? s.nodes[size_t(m.active)].name.c_str() : "Sun (default)");
    if (m.hasTransform) {
        ImGui::TextDisabled("Transform");
        act.location = m.location;
        act.rotationDegrees = m.rotationDegrees;
        act.scale = m.scale;
        bool e = ImGui::DragFloat3("Location", &act.location.x, 0.01f, 0.0f, 0.0f, "%.3f");
        rememberRect(st, "location");
        e = ImGui::DragFloat3("Rotation", &act.rotationDegrees.x, 0.5f, 0.0f, 0.0f, "%.1f deg") || e;
        rememberRect(st, "rotation");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Euler XYZ in degrees (Blender's default order)");
        e = ImGui::DragFloat3("Scale", &act.scale.x, 0.01f, 0.0f, 0.0f, "%.3f") || e;
        rememberRect(st, "scale");
        act.transformEdited = e;
    }
    if (m.light >= 0 || m.sun) {
        ImGui::TextDisabled("Light");
        act.color = m.color;
        act.intensity = m.intensity;
        bool e = false;
        if (m.sun) {
            ImGui::TextDisabled("white (the default sun has no colour setting)");
        } else {
            e = ImGui::ColorEdit3("Colour", &act.color.x, ImGuiColorEditFlags_Float);
        }
        const bool directional = m.sun || (m.light >= 0 && m.light < int(s.lights.size()) && s.lights[size_t(m.light)].type == LightType::Directional);
        e = ImGui::DragFloat(directional ? "Irradiance (W/m^2)" : "Intensity (W/sr)", &act.intensity, 0.01f * std::max(1.0f, m.intensity),
                             0.0f, 1e6f, "%.3f", ImGuiSliderFlags_AlwaysClamp) || e;
        rememberRect(st, "intensity");
        act.lightEdited = e;
        if (directional) {
            act.direction = m.direction;
            ImGui::TextDisabled("Direction");
            act.directionEdited = drawSunSphere("##sunsphere", act.direction, 120.0f);
            rememberRect(st, "sphere");
            const glm::vec3 t = -act.direction;
            ImGui::TextDisabled("towards the light %.2f %.2f %.2f", double(t.x), double(t.y), double(t.z));
        }
    }
    return act;
}

}  // namespace deepgi::ui
