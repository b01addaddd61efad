// Per-pass timings (table + history plots with their scale), CSV export, and texture memory.
#include "ui/viewer_ui.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

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

// The smallest 1, 2 or 5 x 10^k at or above v (a readable axis maximum).
float niceCeil(float v) {
    if (!(v > 0.0f)) return 1.0f;
    const float p = std::pow(10.0f, std::floor(std::log10(v)));
    for (float m : {1.0f, 2.0f, 5.0f, 10.0f})
        if (v <= m * p * 1.0001f) return m * p;
    return 10.0f * p;
}

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
        if (!passMs.count(t.name)) {
            passOrder.push_back(t.name);
            passMs[t.name] = std::deque<float>(frameMs.size(), 0.0f);  // aligned with the frames before it appeared
        }
        push(passMs[t.name], float(t.ms));
        total += float(t.ms);
    }
    // Passes disabled this frame record 0 so the plots stay aligned.
    for (auto& [name, d] : passMs)
        if (std::none_of(timings.begin(), timings.end(), [&](const PassTiming& t) { return t.name == name; })) push(d, 0.0f);
    push(frameMs, total);
    push(cpuFrameMs, float(cpuMs));
}

std::string ProfilerState::csv() const {
    std::ostringstream o;
    o << "frame,cpu_frame_ms,renderer_ms";
    for (const auto& n : passOrder) o << ",\"" << n << " ms\"";
    o << "\n";
    for (size_t i = 0; i < frameMs.size(); ++i) {
        o << i << "," << cpuFrameMs[i] << "," << frameMs[i];
        for (const auto& n : passOrder) {
            const auto& d = passMs.at(n);
            o << "," << (i < d.size() ? d[i] : 0.0f);
        }
        o << "\n";
    }
    return o.str();
}

void drawHistoryPlot(const char* id, const std::deque<float>& values, float height, const char* unit) {
    ImGui::PushID(id);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const float width = std::max(ImGui::GetContentRegionAvail().x, 40.0f);
    ImGui::InvisibleButton("##plot", ImVec2(width, height));
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p1(p0.x + width, p0.y + height);
    dl->AddRectFilled(p0, p1, IM_COL32(30, 30, 34, 255));
    dl->AddRect(p0, p1, IM_COL32(80, 80, 90, 255));
    float vmax = 0.0f;
    std::vector<float> sorted;
    for (float v : values)
        if (std::isfinite(v)) { vmax = std::max(vmax, v); sorted.push_back(v); }
    // The scale follows the 95th percentile, so one slow frame (a shader compile) does not flatten the rest; values
    // above it are drawn at the top.
    float p95 = 0.0f;
    if (!sorted.empty()) {
        const size_t k = std::min(sorted.size() - 1, size_t(0.95 * double(sorted.size())));
        std::nth_element(sorted.begin(), sorted.begin() + long(k), sorted.end());
        p95 = sorted[k];
    }
    const float top = niceCeil(p95 > 0.0f ? p95 : vmax);
    // Axis labels drawn inside on the left; the curve spans the full history width.
    char label[48];
    std::snprintf(label, sizeof(label), "%g %s", double(top), unit);
    const float midY = p0.y + height * 0.5f;
    dl->AddLine(ImVec2(p0.x, midY), ImVec2(p1.x, midY), IM_COL32(60, 60, 70, 255));
    const int n = int(values.size());
    if (n >= 2) {
        std::vector<ImVec2> pts;
        pts.reserve(size_t(n));
        const float dx = (width - 2.0f) / float(n - 1);  // the recorded frames across the plot, newest at the right
        const float x0 = p0.x + 1.0f;
        for (int i = 0; i < n; ++i) {
            const float v = std::isfinite(values[size_t(i)]) ? values[size_t(i)] : 0.0f;
            pts.emplace_back(x0 + dx * float(i), p1.y - 1.0f - (height - 2.0f) * std::clamp(v / top, 0.0f, 1.0f));
        }
        dl->AddPolyline(pts.data(), n, IM_COL32(120, 200, 255, 255), 0, 1.5f);
    }
    dl->AddText(ImVec2(p0.x + 3.0f, p0.y + 1.0f), IM_COL32(190, 190, 200, 255), label);
    dl->AddText(ImVec2(p0.x + 3.0f, p1.y - ImGui::GetTextLineHeight() - 1.0f), IM_COL32(150, 150, 160, 255), "0");
    if (!values.empty()) {
        std::snprintf(label, sizeof(label), "%.2f", double(values.back()));
        const float tw = ImGui::CalcTextSize(label).x;
        dl->AddText(ImVec2(p1.x - tw - 3.0f, p0.y + 1.0f), IM_COL32(235, 235, 235, 255), label);
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("last %d frames; axis 0 .. %.3g %s (95th percentile); max %.3g", n, double(top), unit, double(vmax));
    ImGui::PopID();
}

ProfilerActions drawProfilerPanel(ProfilerState& p, const MemoryReport& mem, int width, int height) {
    ProfilerActions act;
    const float frame = mean(p.frameMs, 10), cpu = mean(p.cpuFrameMs, 10);
    ImGui::Text("%d x %d: passes %.1f ms, frame %.1f ms (%.1f fps)", width, height, frame, cpu,
                cpu > 0.0f ? 1000.0f / cpu : 0.0f);
    ImGui::TextDisabled("%s", p.timingNote.c_str());
    ImGui::TextDisabled("renderer (sum of passes), last %d frames", int(p.frameMs.size()));
    drawHistoryPlot("frame", p.frameMs, 64.0f, "ms");
    // One row per pass: its whole name and mean time, then its own plot across the panel (names are never cut).
    for (const auto& name : p.passOrder) {
        const auto& d = p.passMs.at(name);
        ImGui::TextUnformatted(name.c_str());
        char ms[32];
        std::snprintf(ms, sizeof(ms), "%.2f ms", double(mean(d, 10)));
        ImGui::SameLine(std::max(ImGui::GetContentRegionMax().x - ImGui::CalcTextSize(ms).x, ImGui::GetCursorPosX() + 8.0f));
        ImGui::TextUnformatted(ms);
        drawHistoryPlot(name.c_str(), d, 34.0f, "ms");
    }
    ImGui::SetNextItemWidth(-110.0f);
    ImGui::InputText("##csv", p.csvPath, sizeof(p.csvPath));
    ImGui::SameLine();
    if (ImGui::Button("Export CSV")) act.exportCsv = true;
    if (!p.message.empty()) ImGui::TextWrapped("%s", p.message.c_str());
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
    return act;
}

}  // namespace deepgi::ui
