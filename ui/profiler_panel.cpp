// Per-pass timings (table + history plots) and texture memory.
#include "ui/viewer_ui.h"

#include <imgui.h>

#include <algorithm>
#include <numeric>

namespace deepgi::ui {

namespace {

void push(std::deque<float>& d, float v) {
    d.push_back(v);
    while (int(d.size()) > ProfilerState::kHistory) d.pop_front();
}

float mean(const std::deque<float>& d, int last) {
    if (d.empty()) return 0.0f;
    const int n = std::min<int>(last, int(d.size()));
    return std::accumulate(d.end() - n, d.end(), 0.0f) / float(n);
}

float getter(void* data, int i) { return (*static_cast<const std::deque<float>*>(data))[size_t(i)]; }

std::string bytesText(uint64_t b) {
    char buf[32];
    if (b >= (uint64_t(1) << 20)) std::snprintf(buf, sizeof(buf), "%.2f MiB", double(b) / double(1 << 20));
    else std::snprintf(buf, sizeof(buf), "%.1f KiB", double(b) / 1024.0);
    return buf;
}

}  // namespace

void ProfilerState::record(const std::vector<PassTiming>& timings, double cpuMs) {
    float total = 0.0f;
    for (const auto& t : timings) {
        if (!passMs.count(t.name)) passOrder.push_back(t.name);
        push(passMs[t.name], float(t.ms));
        total += float(t.ms);
    }
    // Passes disabled this frame record 0 so the plots stay aligned.
    for (auto& [name, d] : passMs)
        if (std::none_of(timings.begin(), timings.end(), [&](const PassTiming& t) { return t.name == name; })) push(d, 0.0f);
    push(frameMs, total);
    push(cpuFrameMs, float(cpuMs));
}

void drawProfilerPanel(const ProfilerState& p, const MemoryReport& mem, int width, int height) {
    const float frame = mean(p.frameMs, 10), cpu = mean(p.cpuFrameMs, 10);
    ImGui::Text("%d x %d: passes %.1f ms, frame %.1f ms (%.1f fps)", width, height, frame, cpu,
                cpu > 0.0f ? 1000.0f / cpu : 0.0f);
    ImGui::TextDisabled("wall clock, glFinish around each pass");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("llvmpipe's GL timer queries miss vertex work, so CPU wall-clock time is shown");
    if (!p.frameMs.empty()) {
        char overlay[64];
        std::snprintf(overlay, sizeof(overlay), "renderer %.1f ms", p.frameMs.back());
        ImGui::PlotLines("##frame", getter, const_cast<std::deque<float>*>(&p.frameMs), int(p.frameMs.size()), 0, overlay,
                         0.0f, FLT_MAX, ImVec2(-1.0f, 60.0f));
    }
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch, 2.2f);
        ImGui::TableSetupColumn("ms", ImGuiTableColumnFlags_WidthFixed, 55.0f);
        ImGui::TableSetupColumn("history", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableHeadersRow();
        for (const auto& name : p.passOrder) {
            const auto& d = p.passMs.at(name);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%7.2f", mean(d, 10));
            ImGui::TableNextColumn();
            ImGui::PushID(name.c_str());
            ImGui::PlotLines("##h", getter, const_cast<std::deque<float>*>(&d), int(d.size()), 0, nullptr, 0.0f, FLT_MAX,
                             ImVec2(-1.0f, ImGui::GetTextLineHeight()));
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::Text("Texture memory: %s", bytesText(mem.totalBytes).c_str());
    ImGui::TextDisabled("G-buffer %d bits/px (%s), radiosity %d bits/px (%s), extra %s", mem.gbufferBitsPerPixel,
                        bytesText(mem.gbufferBytes).c_str(), mem.radiosityBitsPerPixel, bytesText(mem.radiosityBytes).c_str(),
                        bytesText(mem.extraBytes).c_str());
    if (ImGui::BeginTable("memory", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("buffer", ImGuiTableColumnFlags_WidthStretch, 1.5f);
        ImGui::TableSetupColumn("format", ImGuiTableColumnFlags_WidthStretch, 1.3f);
        ImGui::TableSetupColumn("bpp", ImGuiTableColumnFlags_WidthFixed, 28.0f);
        ImGui::TableSetupColumn("size", ImGuiTableColumnFlags_WidthFixed, 72.0f);
        ImGui::TableHeadersRow();
        for (const auto& l : mem.lines) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l.name.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l.format.c_str());
            ImGui::TableNextColumn();
            if (l.bitsPerPixel) ImGui::Text("%d", l.bitsPerPixel);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(bytesText(l.bytes).c_str());
        }
        ImGui::EndTable();
    }
}

}  // namespace deepgi::ui
