// The sidebar right of the viewport: Settings, Profiler, View and Pipeline tabs.
#include "ui/viewer_ui.h"

#include <imgui.h>

namespace deepgi::ui {

namespace {

void drawViewTab(const SidebarModel& m, SidebarState& st, SidebarActions& act) {
    ImGui::TextDisabled("Scene");
    ImGui::TextWrapped("%s", m.scenePath.c_str());
    ImGui::Text("%zu triangles, %zu lights, %zu cameras", m.triangles, m.lights, m.cameraNames.size());
    ImGui::Separator();
    ImGui::TextDisabled("Cameras");
    if (ImGui::Selectable("Frame all (Home)")) act.frameAll = true;
    for (int i = 0; i < int(m.cameraNames.size()); ++i)
        if (ImGui::Selectable((m.cameraNames[size_t(i)] + (i == 0 ? "  (Numpad 0)" : "")).c_str())) act.camera = i;
    ImGui::Separator();
    ImGui::Checkbox("Emulate 3-button mouse (Alt+left)", &st.view->emulate3Button);
    ImGui::SliderFloat("resolution", &st.view->resolutionScale, 0.25f, 1.0f, "%.2f x");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Render at a fraction of the viewport (llvmpipe is slow)");
    bool autoTarget = st.view->targetFrameMs < 0.0f;
    if (ImGui::Checkbox("automatic target frame time", &autoTarget)) st.view->targetFrameMs = autoTarget ? -1.0f : m.autoTargetFrameMs;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Dynamic resolution: while the camera moves the render shrinks (down to 1/4 of the viewport)\n"
                          "to hold the target frame time; when it stops, the whole viewport. Automatic: 100 ms on\n"
                          "software GL, 16.7 ms on a GPU");
    if (autoTarget) ImGui::TextDisabled("target frame time %.1f ms", double(m.autoTargetFrameMs));
    else ImGui::SliderFloat("target frame", &st.view->targetFrameMs, 0.0f, 500.0f, st.view->targetFrameMs > 0.0f ? "%.0f ms" : "off");
    if (ImGui::Checkbox("Perspective (Numpad 5)", &st.perspective)) act.projectionChanged = true;
    float fov = glm::degrees(st.yfov);
    if (ImGui::SliderFloat("vertical fov", &fov, 10.0f, 120.0f, "%.0f deg")) {
        st.yfov = glm::radians(fov);
        act.fovChanged = true;
    }
    ImGui::Checkbox("Inspector beside the viewport (I)", &st.inspector->open);
    ImGui::Separator();
    ImGui::TextDisabled("Shaders");
    ImGui::TextWrapped("%s", m.shaderDir.c_str());
    if (ImGui::Button("Reload all (F5)")) act.reloadShaders = true;
    ImGui::SameLine();
    ImGui::TextDisabled(m.shaderErrors == 0 ? "no errors" : "%zu error(s)", m.shaderErrors);
    ImGui::Separator();
    ImGui::TextDisabled("Screenshot (F12)");
    ImGui::TextWrapped("folder: %s", m.screenshotDir.c_str());
    ImGui::Checkbox("also every buffer as EXR (raw values)", st.captureBuffers);
    if (ImGui::Button("Save screenshot")) act.capture = true;
    if (!m.lastCapture.empty()) ImGui::TextWrapped("last: %s", m.lastCapture.c_str());
    ImGui::Separator();
    ImGui::TextDisabled("Keys");
    ImGui::TextWrapped("MMB orbit, Shift+MMB pan, wheel/Ctrl+MMB zoom; Numpad 1/3/7 front/right/top (Ctrl: opposite), "
                       "5 persp/ortho, 0 camera; Home frame all; Shift+` fly; F5 reload shaders; F12 screenshot; "
                       "N sidebar; I inspector. Editing: click selects (Shift adds), A all, Alt+A none, G/R/S move/rotate/"
                       "scale (X/Y/Z axis, Shift+X/Y/Z plane, again: local, typed values, Enter/click confirm, Esc/right-click "
                       "cancel), H hide, Alt+H show all, Ctrl+Z undo, Shift+Ctrl+Z redo.");
}

}  // namespace

SidebarActions drawSidebar(const SidebarModel& m, SidebarState& st, float x0, float height) {
    SidebarActions act;
    ImGui::SetNextWindowPos(ImVec2(x0, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(ImGui::GetIO().DisplaySize.x - x0, height));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoTitleBar;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
    if (ImGui::Begin("Sidebar", nullptr, flags)) {
        auto tabFlags = [&](const char* name) {
            return st.selectTab == name ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None;
        };
        if (ImGui::BeginTabBar("tabs")) {
            if (st.itemTab && ImGui::BeginTabItem("Item", nullptr, tabFlags("item"))) {
                st.itemTab();
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Settings", nullptr, tabFlags("settings"))) {
                act.settings = drawSettingsPanel(*st.settings, *st.settingsPanel);
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Profiler", nullptr, tabFlags("profiler"))) {
                act.profiler = drawProfilerPanel(*st.profiler, m.memory, m.width, m.height);
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("View", nullptr, tabFlags("view"))) {
                drawViewTab(m, st, act);
                ImGui::EndTabItem();
            }
            if (m.pipeline && ImGui::BeginTabItem("Pipeline", nullptr, tabFlags("pipeline"))) {
                act.pipeline = drawPipelinePanel(*m.pipeline, *st.pipeline, *st.settings);
                ImGui::EndTabItem();
            }
            ImGui::EndTabBar();
            st.selectTab.clear();
        }
    }
    ImGui::End();
    ImGui::PopStyleVar();
    return act;
}

}  // namespace deepgi::ui
