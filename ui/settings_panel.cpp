// Settings panel generated from the declaration table (settings.def): no per-setting code here.
#include "ui/viewer_ui.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <exception>

namespace deepgi::ui {

namespace {

void tooltip(const SettingInfo& info) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(info.effect);
    ImGui::TextDisabled("%s  (default %s%s%s)", info.key, formatSettingValue(info, info.def).c_str(),
                        info.unit[0] ? " " : "", info.unit);
    ImGui::TextDisabled("Right-click resets to the default; Ctrl+click types a value.");
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

// One widget for one setting; returns true if the value changed.
bool settingWidget(Settings& s, const SettingInfo& info) {
    double v = info.get(s);
    bool changed = false;
    std::string label = info.key;
    const size_t dot = label.find('.');
    if (dot != std::string::npos) label = label.substr(dot + 1);
    std::replace(label.begin(), label.end(), '_', ' ');
    const std::string id = label + "##" + info.key;
    const char* unit = info.unit;
    // Huge ranges (0..1e5 "scene units") are drags, the rest sliders.
    const bool wide = info.max - info.min > 1000.0 && info.max > 1000.0 * std::max(1.0, std::abs(info.min));
    switch (info.type) {
        case SettingType::Bool: {
            bool b = v != 0.0;
            if (ImGui::Checkbox(id.c_str(), &b)) { v = b ? 1.0 : 0.0; changed = true; }
            break;
        }
        case SettingType::Enum: {
            int i = int(v);
            const std::string preview = i >= 0 && i < int(info.choices.size()) ? info.choices[i] : "?";
            if (ImGui::BeginCombo(id.c_str(), preview.c_str())) {
                for (int c = 0; c < int(info.choices.size()); ++c)
                    if (ImGui::Selectable(info.choices[c].c_str(), c == i)) { v = c; changed = true; }
                ImGui::EndCombo();
            }
            break;
        }
        case SettingType::Int: {
            int i = int(v);
            const std::string fmt = std::string("%d") + (unit[0] ? " " : "") + unit;
            if (wide) changed = ImGui::DragInt(id.c_str(), &i, std::max(1.0f, float(std::abs(i)) * 0.01f), int(info.min),
                                               int(info.max), fmt.c_str(), ImGuiSliderFlags_AlwaysClamp);
            else changed = ImGui::SliderInt(id.c_str(), &i, int(info.min), int(info.max), fmt.c_str(), ImGuiSliderFlags_AlwaysClamp);
            if (changed) v = i;
            break;
        }
        case SettingType::Float: {
            float f = float(v);
            const std::string fmt = std::string(wide ? "%.4g" : "%.3f") + (unit[0] ? " " : "") + unit;
            if (wide) changed = ImGui::DragFloat(id.c_str(), &f, std::max(0.001f, std::abs(f) * 0.005f), float(info.min),
                                                 float(info.max), fmt.c_str(), ImGuiSliderFlags_AlwaysClamp);
            else changed = ImGui::SliderFloat(id.c_str(), &f, float(info.min), float(info.max), fmt.c_str(), ImGuiSliderFlags_AlwaysClamp);
            if (changed) v = f;
            break;
        }
    }
    tooltip(info);
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && v != info.def) { v = info.def; changed = true; }
    if (changed) info.set(s, v);
    return changed;
}

}  // namespace

bool drawSettingWidget(Settings& s, const SettingInfo& info) { return settingWidget(s, info); }

SettingsActions drawSettingsPanel(Settings& s, SettingsPanelState& state) {
    SettingsActions a;
    ImGui::TextDisabled("Preset");
    ImGui::SameLine();
    for (const auto& name : presetNames()) {
        std::string label = name;
        if (!label.empty()) label[0] = char(std::toupper((unsigned char)label[0]));
        if (ImGui::Button(label.c_str())) {
            try {
                Settings next = s;
                applyPreset(next, name);
                s = next;
                a.changed = a.resetHistory = true;
                state.message = "applied preset " + name;
            } catch (const std::exception& e) {
                state.message = e.what();
            }
        }
        ImGui::SameLine();
    }
    if (ImGui::Button("Defaults")) {
        s = Settings{};
        a.changed = a.resetHistory = true;
    }
    if (ImGui::Button("Reset history")) a.resetHistory = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Forget the temporal history (next frame starts from scratch)");
    ImGui::SameLine();
    if (ImGui::Button("Converge")) a.convergeFrames = state.convergeFrames;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Render this many frames now, so the temporal filter settles");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90.0f);
    ImGui::SliderInt("frames##converge", &state.convergeFrames, 1, 128);

    ImGui::SetNextItemWidth(-110.0f);
    ImGui::InputText("##settingspath", state.path, sizeof(state.path));
    ImGui::SameLine();
    if (ImGui::Button("Save")) {
        try {
            saveSettingsFile(s, state.path);
            state.message = std::string("saved ") + state.path;
        } catch (const std::exception& e) {
            state.message = e.what();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Load")) {
        try {
            Settings next = s;
            loadSettingsFile(next, state.path);
            s = next;
            a.changed = a.resetHistory = true;
            state.message = std::string("loaded ") + state.path;
        } catch (const std::exception& e) {
            state.message = e.what();
        }
    }
    if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
    ImGui::Separator();

    ImGui::PushItemWidth(-ImGui::GetContentRegionAvail().x * 0.45f);
    for (const auto& group : settingGroups()) {
        if (!ImGui::CollapsingHeader(group.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
        for (const auto& info : settingTable())
            if (group == info.group && settingWidget(s, info)) a.changed = true;
    }
    ImGui::PopItemWidth();
    return a;
}

}  // namespace deepgi::ui
