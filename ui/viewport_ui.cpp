// The viewport's header bar (buffer to show, display controls, cameras) and its overlays.
#include "ui/viewer_ui.h"

#include <imgui.h>

namespace deepgi::ui {

namespace {
const char* kChannels[] = {"RGB", "R", "G", "B", "A", "Luminance"};
const char* kModes[] = {"Auto", "Raw", "Radiance", "Linear depth", "Normal"};
}  // namespace

float drawViewportHeader(ViewportState& v, ViewerServices& services, float x0, float x1) {
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus;
    ImGui::SetNextWindowPos(ImVec2(x0, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(x1 - x0, 0.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6.0f, 4.0f));
    float height = 0.0f;
    if (ImGui::Begin("##viewport header", nullptr, flags)) {
        if (ImGui::Button("File")) ImGui::OpenPopup("file menu");
        if (ImGui::BeginPopup("file menu")) {
            ImGui::TextDisabled("Save As (glTF 2.0: .gltf with a .bin beside it, or .glb)");
            ImGui::SetNextItemWidth(280.0f);
            const bool enter = ImGui::InputText("##savepath", v.savePath, sizeof(v.savePath), ImGuiInputTextFlags_EnterReturnsTrue);
            ImGui::SameLine();
            if (ImGui::Button("Save") || enter) v.saveRequested = true;
            if (!v.saveMessage.empty()) {
                const bool failed = v.saveMessage.rfind("saved ", 0) != 0;
                ImGui::PushStyleColor(ImGuiCol_Text, failed ? IM_COL32(255, 110, 110, 255) : IM_COL32(150, 230, 150, 255));
                ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 360.0f);
                ImGui::TextUnformatted(v.saveMessage.c_str());
                ImGui::PopTextWrapPos();
                ImGui::PopStyleColor();
            }
            ImGui::EndPopup();
        }
        ImGui::SameLine();
        ImGui::SetNextItemWidth(150.0f);
        if (ImGui::BeginCombo("##buffer", v.buffer.c_str(), ImGuiComboFlags_HeightLarge)) {
            for (const auto& name : services.bufferNames())
                if (ImGui::Selectable(name.c_str(), name == v.buffer)) v.buffer = name;
            ImGui::EndCombo();
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Buffer shown in the viewport (like Blender's Render Pass)");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(80.0f);
        int ch = int(v.params.channel);
        if (ImGui::Combo("##channel", &ch, kChannels, IM_ARRAYSIZE(kChannels))) v.params.channel = ViewChannel(ch);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(95.0f);
        int mode = int(v.params.mode);
        if (ImGui::Combo("##mode", &mode, kModes, IM_ARRAYSIZE(kModes))) v.params.mode = ViewMode(mode);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Display: Auto follows the buffer (radiance, depth, normal, colour)");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(90.0f);
        ImGui::SliderFloat("##ev", &v.params.exposureEV, -10.0f, 10.0f, "%+.1f EV");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Display exposure of radiance buffers (not the render's)");
        if (!v.cameraNames.empty()) {
            ImGui::SameLine();
            ImGui::SetNextItemWidth(110.0f);
            if (ImGui::BeginCombo("##camera", "Camera", ImGuiComboFlags_HeightLarge)) {
                for (int i = 0; i < int(v.cameraNames.size()); ++i)
                    if (ImGui::Selectable(v.cameraNames[i].c_str())) v.cameraChoice = i;
                ImGui::EndCombo();
            }
        }
        ImGui::SameLine();
        ImGui::SetNextItemWidth(120.0f);
        static const char* kPathTrace[] = {"Real time", "Path traced", "Split: PT right"};
        int pt = int(v.pathTrace);
        if (ImGui::Combo("##pathtrace", &pt, kPathTrace, IM_ARRAYSIZE(kPathTrace))) v.pathTrace = PathTraceMode(pt);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Path trace this view: the reference path tracer renders this camera progressively (1/4 size,\n"
                              "all cores but one), alone or split against the real-time frame, with live error figures");
        if (v.pathTrace == PathTraceMode::Split) {
            ImGui::SameLine();
            ImGui::SetNextItemWidth(70.0f);
            ImGui::SliderFloat("##ptsplit", &v.pathTraceSplit, 0.0f, 1.0f, "%.2f");
        }
        ImGui::SameLine();
        ImGui::TextDisabled("%s", v.viewName.c_str());
        height = ImGui::GetWindowHeight();
    }
    ImGui::End();
    ImGui::PopStyleVar(2);
    return height;
}

void drawShaderErrors(const std::vector<std::string>& errors, float x0, float y1, float width) {
    if (errors.empty()) return;
    ImGui::SetNextWindowPos(ImVec2(x0 + 8.0f, y1 - 8.0f), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(width - 16.0f, 0.0f));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(150, 20, 20, 235));
    ImGui::PushStyleColor(ImGuiCol_Border, IM_COL32(255, 90, 90, 255));
    ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 255, 255, 255));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("##shader errors", nullptr, flags)) {
        ImGui::Text("Shader error: last good program kept (fix the file; it reloads by itself, F5 forces)");
        ImGui::Separator();
        ImGui::PushTextWrapPos(0.0f);
        int shown = 0;
        for (const auto& e : errors) {
            if (++shown > 8) { ImGui::Text("... %d more", int(errors.size()) - 8); break; }
            ImGui::TextUnformatted(e.c_str());
        }
        ImGui::PopTextWrapPos();
    }
    ImGui::End();
    ImGui::PopStyleColor(3);
}

}  // namespace deepgi::ui
