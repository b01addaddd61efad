// The Pipeline panel: the passes in order with what each reads and writes. Click a texture to show it, a pass to
// see its settings and time.
#include "ui/viewer_ui.h"

#include <imgui.h>

namespace deepgi::ui {

PipelineActions drawPipelinePanel(const PipelineGraph& g, PipelinePanelState& st, Settings& settings) {
    PipelineActions act;
    st.itemRects.clear();
    ImGui::TextDisabled("%zu passes, in execution order; click a texture to show it", g.passes.size());
    for (size_t i = 0; i < g.passes.size(); ++i) {
        const PipelineNode& n = g.passes[i];
        ImGui::PushID(int(i));
        char label[160];
        // "###pass": the ID must not change with the time in the label, or a click spanning two frames is lost.
        if (n.ms >= 0.0) std::snprintf(label, sizeof(label), "%zu. %s  (%.2f ms)%s###pass", i + 1, n.name.c_str(), n.ms, n.enabled ? "" : "  off");
        else std::snprintf(label, sizeof(label), "%zu. %s%s###pass", i + 1, n.name.c_str(), n.enabled ? "" : "  off");
        if (!n.enabled) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        if (ImGui::Selectable(label, st.selectedPass == n.name)) st.selectedPass = st.selectedPass == n.name ? "" : n.name;
        if (!n.enabled) ImGui::PopStyleColor();
        auto remember = [&](const std::string& key) {
            if (!st.itemRects.count(key))
                st.itemRects[key] = glm::vec4(ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y, ImGui::GetItemRectMax().x,
                                              ImGui::GetItemRectMax().y);
        };
        remember("pass " + n.name);
        auto textures = [&](const char* what, const std::vector<std::string>& names) {
            ImGui::Indent();
            ImGui::PushID(what);  // a texture both read and written by one pass gets two distinct buttons
            ImGui::TextDisabled("%s", what);
            const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
            for (const auto& t : names) {
                // Wrap onto the next line rather than run off the panel.
                const float w = ImGui::CalcTextSize(t.c_str()).x + ImGui::GetStyle().FramePadding.x * 2.0f;
                if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + w <= right) ImGui::SameLine();
                else ImGui::Dummy(ImVec2(ImGui::CalcTextSize("writes").x, 0.0f)), ImGui::SameLine();
                if (ImGui::SmallButton(t.c_str())) act.showTexture = t;
                remember("texture " + t);
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("show '%s' in the viewport and the inspector", t.c_str());
            }
            if (names.empty()) { ImGui::SameLine(); ImGui::TextDisabled("-"); }
            ImGui::PopID();
            ImGui::Unindent();
        };
        textures("reads ", n.reads);
        textures("writes", n.writes);
        if (st.selectedPass == n.name) {
            ImGui::Indent();
            ImGui::TextDisabled(n.ms >= 0.0 ? "last frame %.3f ms" : "no time recorded (not run this frame)", n.ms);
            for (const auto& key : n.settingKeys)
                if (const SettingInfo* info = findSetting(key)) act.settingsChanged |= drawSettingWidget(settings, *info);
            if (n.settingKeys.empty()) ImGui::TextDisabled("no settings of its own");
            ImGui::Unindent();
        }
        ImGui::Separator();
        ImGui::PopID();
    }
    return act;
}

}  // namespace deepgi::ui
