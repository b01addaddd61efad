// Buffer inspector: zoom/pan with a texel grid, channels, exposure and range, the raw value under the cursor
// (a 3x3 readback around it), min/mean/max on demand, NaN/Inf/negative highlights, A/B split.
#include "ui/viewer_ui.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi::ui {

namespace {

const char* kChannels[] = {"RGB", "R", "G", "B", "A", "Luminance"};
const char* kModes[] = {"Auto", "Raw", "Radiance", "Linear depth", "Normal"};

bool bufferCombo(const char* label, std::string& value, const std::vector<std::string>& names, bool allowNone) {
    bool changed = false;
    const std::string preview = value.empty() ? std::string("(none)") : value;
    if (ImGui::BeginCombo(label, preview.c_str(), ImGuiComboFlags_HeightLarge)) {
        if (allowNone && ImGui::Selectable("(none)", value.empty())) { value.clear(); changed = true; }
        for (const auto& n : names)
            if (ImGui::Selectable(n.c_str(), n == value)) { value = n; changed = true; }
        ImGui::EndCombo();
    }
    return changed;
}

void fit(InspectorState& s, const BufferSource& a, ImVec2 area) {
    const float w = float(a.levelWidth()), h = float(a.levelHeight());
    s.zoom = std::max(std::min(area.x / w, area.y / h), 1e-4f);
    s.center = glm::vec2(w, h) * 0.5f;
}

}  // namespace

BufferStats computeStats(const FloatImage& img) {
    BufferStats st;
    st.channels = std::min(img.channels, 4);
    for (int c = 0; c < st.channels; ++c) {
        st.min[c] = std::numeric_limits<double>::max();
        st.max[c] = -std::numeric_limits<double>::max();
    }
    double sum[4] = {0, 0, 0, 0};
    size_t count[4] = {0, 0, 0, 0};
    const size_t n = size_t(img.width) * img.height;
    for (size_t i = 0; i < n; ++i) {
        bool nan = false, inf = false, neg = false;
        for (int c = 0; c < st.channels; ++c) {
            const float v = img.pixels[i * img.channels + c];
            if (std::isnan(v)) { nan = true; continue; }
            if (std::isinf(v)) { inf = true; continue; }
            if (v < 0.0f) neg = true;
            st.min[c] = std::min(st.min[c], double(v));
            st.max[c] = std::max(st.max[c], double(v));
            sum[c] += v;
            ++count[c];
        }
        st.nan += nan;
        st.inf += inf;
        st.negative += neg;
    }
    for (int c = 0; c < st.channels; ++c) {
        st.mean[c] = count[c] ? sum[c] / double(count[c]) : 0.0;
        if (!count[c]) st.min[c] = st.max[c] = 0.0;
    }
    st.texels = n;
    st.valid = true;
    return st;
}

void drawInspector(InspectorState& s, ViewerServices& services, double now) {
    if (!s.open) return;
    ImGui::SetNextWindowSize(ImVec2(560.0f, 520.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowPos(ImVec2(40.0f, 60.0f), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Inspector", &s.open)) {
        ImGui::End();
        return;
    }
    const std::vector<std::string> names = services.bufferNames();
    if (std::find(names.begin(), names.end(), s.a) == names.end() && !names.empty()) s.a = names.front();

    // Row 1: buffers.
    ImGui::SetNextItemWidth(160.0f);
    if (bufferCombo("A##inspA", s.a, names, false)) { s.zoom = 0.0f; s.stats = {}; }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(160.0f);
    bufferCombo("B (split)##inspB", s.b, names, true);
    BufferSource a = services.source(s.a, s.level);
    if (a.levels > 1) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(70.0f);
        if (ImGui::SliderInt("mip", &s.level, 0, a.levels - 1)) { s.zoom = 0.0f; a = services.source(s.a, s.level); }
    }

    // Row 2: display.
    ImGui::SetNextItemWidth(80.0f);
    int ch = int(s.params.channel);
    if (ImGui::Combo("##ich", &ch, kChannels, IM_ARRAYSIZE(kChannels))) s.params.channel = ViewChannel(ch);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(100.0f);
    int mode = int(s.params.mode);
    if (ImGui::Combo("##imode", &mode, kModes, IM_ARRAYSIZE(kModes))) s.params.mode = ViewMode(mode);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90.0f);
    ImGui::SliderFloat("##iev", &s.params.exposureEV, -10.0f, 10.0f, "%+.1f EV");
    ImGui::SameLine();
    ImGui::Checkbox("range", &s.params.useRange);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Map [min, max] to black..white (depth: linear distance)");
    if (s.params.useRange) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(120.0f);
        ImGui::DragFloatRange2("##irange", &s.params.rangeMin, &s.params.rangeMax, 0.01f, 0.0f, 0.0f, "%.3g", "%.3g");
    }
    ImGui::Checkbox("NaN/Inf/neg", &s.params.highlight);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("NaN magenta, +Inf yellow, -Inf cyan, negative tinted blue (any channel)");
    ImGui::SameLine();
    ImGui::Checkbox("grid", &s.params.grid);
    ImGui::SameLine();
    const bool doFit = ImGui::Button("Fit");
    ImGui::SameLine();
    const bool oneToOne = ImGui::Button("1:1");
    ImGui::SameLine();
    ImGui::TextDisabled("%.0f%%", double(s.zoom) * 100.0);
    if (!s.b.empty()) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(80.0f);
        ImGui::SliderFloat("split", &s.params.splitX, 0.0f, 1.0f, "%.2f");
    }

    // Image area: leave room for the info lines.
    const float infoHeight = ImGui::GetTextLineHeightWithSpacing() * 5.5f;
    ImVec2 area = ImGui::GetContentRegionAvail();
    area.y -= infoHeight;
    area.x = std::max(area.x, 32.0f);
    area.y = std::max(area.y, 32.0f);
    if (!a.valid()) {
        ImGui::TextDisabled("'%s' is not allocated in the current pipeline", s.a.c_str());
        ImGui::End();
        return;
    }
    if (s.zoom <= 0.0f || doFit) fit(s, a, area);
    if (oneToOne) s.zoom = 1.0f;

    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("##image", area, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle);
    const bool hovered = ImGui::IsItemHovered();
    ImGuiIO& io = ImGui::GetIO();
    const glm::vec2 areaSize(area.x, area.y);
    auto texelAt = [&](ImVec2 m) {
        const glm::vec2 fromBottomLeft(m.x - p0.x, p0.y + area.y - m.y);
        return s.center + (fromBottomLeft - areaSize * 0.5f) / s.zoom;
    };
    if (hovered && io.MouseWheel != 0.0f) {
        const glm::vec2 t = texelAt(io.MousePos);
        s.zoom = std::clamp(s.zoom * std::pow(1.25f, io.MouseWheel), 1e-3f, 512.0f);
        const glm::vec2 fromBottomLeft(io.MousePos.x - p0.x, p0.y + area.y - io.MousePos.y);
        s.center = t - (fromBottomLeft - areaSize * 0.5f) / s.zoom;  // the texel under the cursor stays put
    }
    if (ImGui::IsItemActive() && (ImGui::IsMouseDragging(ImGuiMouseButton_Left) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle))) {
        s.center.x -= io.MouseDelta.x / s.zoom;
        s.center.y += io.MouseDelta.y / s.zoom;
    }

    BufferViewParams p = s.params;
    p.texelsPerPixel = 1.0f / s.zoom;
    p.origin = s.center - areaSize * 0.5f / s.zoom;
    const Camera& cam = services.camera();
    p.znear = cam.znear;
    p.zfar = cam.zfar;
    p.perspective = cam.perspective;
    BufferSource b;
    if (!s.b.empty()) b = services.source(s.b, s.level);
    const GLuint tex = services.drawView(1, a, b.valid() ? &b : nullptr, p, int(area.x), int(area.y));
    ImGui::GetWindowDrawList()->AddImage((ImTextureID)(intptr_t)tex, p0, ImVec2(p0.x + area.x, p0.y + area.y), ImVec2(0, 1),
                                         ImVec2(1, 0));

    // Readout under the cursor: a 3x3 block read back around it (never the whole texture).
    if (hovered) {
        const glm::vec2 t = texelAt(io.MousePos);
        const bool onB = b.valid() && (io.MousePos.x - p0.x) >= p.splitX * area.x;
        const BufferSource& src = onB ? b : a;
        glm::vec2 ts = t;
        if (onB) ts *= glm::vec2(float(b.levelWidth()) / float(a.levelWidth()), float(b.levelHeight()) / float(a.levelHeight()));
        const int tx = int(std::floor(ts.x)), ty = int(std::floor(ts.y));
        if (tx >= 0 && ty >= 0 && tx < src.levelWidth() && ty < src.levelHeight()) {
            const TexelBlock blk = services.readTexels(src, tx - 1, ty - 1, 3, 3);
            if (blk.contains(tx, ty)) {
                std::string text;
                char buf[64];
                for (int c = 0; c < blk.channels; ++c) {
                    std::snprintf(buf, sizeof(buf), "%s%.6g", c ? ", " : "", double(blk.at(tx, ty, c)));
                    text += buf;
                }
                ImGui::BeginTooltip();
                ImGui::Text("%s  texel (%d, %d)  uv (%.4f, %.4f)", onB ? s.b.c_str() : s.a.c_str(), tx,
                            src.levelHeight() - 1 - ty, (tx + 0.5) / src.levelWidth(), 1.0 - (ty + 0.5) / src.levelHeight());
                ImGui::Text("raw: %s", text.c_str());
                if (src.vis == Visualize::Depth) {
                    const float d = blk.at(tx, ty, 0), n = cam.znear, f = cam.zfar;
                    const float z = cam.perspective ? 2.0f * n * f / std::max(f + n - (d * 2.0f - 1.0f) * (f - n), 1e-30f)
                                                    : n + d * (f - n);
                    ImGui::Text("linear depth: %.5g", double(z));
                } else if (src.vis == Visualize::Normal && blk.channels >= 2) {
                    glm::vec3 v(blk.at(tx, ty, 0), blk.at(tx, ty, 1), 0.0f);
                    v.z = 1.0f - std::abs(v.x) - std::abs(v.y);
                    if (v.z < 0.0f) {
                        const float vx = (1.0f - std::abs(v.y)) * (v.x >= 0.0f ? 1.0f : -1.0f);
                        v.y = (1.0f - std::abs(v.x)) * (v.y >= 0.0f ? 1.0f : -1.0f);
                        v.x = vx;
                    }
                    v = glm::normalize(v);
                    ImGui::Text("normal: (%.4f, %.4f, %.4f)", double(v.x), double(v.y), double(v.z));
                }
                ImGui::EndTooltip();
            }
        }
    }

    // Info and statistics.
    ImGui::Text("%s: %d x %d, mip %d of %d", s.a.c_str(), a.levelWidth(), a.levelHeight(), a.level, a.levels);
    ImGui::SameLine();
    const bool statsNow = ImGui::SmallButton("min/mean/max");
    ImGui::SameLine();
    ImGui::Checkbox("every second", &s.autoStats);
    if (statsNow || s.statsOf != s.a + "#" + std::to_string(s.level) || (s.autoStats && now - s.lastStatsTime > 1.0)) {
        if (statsNow || s.autoStats) {
            s.stats = services.stats(s.a, s.level);
            s.lastStatsTime = now;
        } else {
            s.stats = {};
        }
        s.statsOf = s.a + "#" + std::to_string(s.level);
    }
    if (s.stats.valid) {
        static const char* kC = "RGBA";
        for (int c = 0; c < s.stats.channels; ++c)
            ImGui::Text("%c  min %-11.5g mean %-11.5g max %-11.5g", kC[c], s.stats.min[c], s.stats.mean[c], s.stats.max[c]);
        ImGui::TextColored(s.stats.nan || s.stats.inf ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.6f, 0.6f, 0.6f, 1),
                           "NaN %zu   Inf %zu   negative %zu   of %zu texels", s.stats.nan, s.stats.inf, s.stats.negative,
                           s.stats.texels);
        ImGui::SameLine();
        if (ImGui::SmallButton("use as range")) {
            s.params.useRange = true;
            s.params.rangeMin = float(*std::min_element(s.stats.min, s.stats.min + s.stats.channels));
            s.params.rangeMax = float(*std::max_element(s.stats.max, s.stats.max + s.stats.channels));
        }
    } else {
        ImGui::TextDisabled("statistics read the whole buffer back: on demand");
    }
    ImGui::SetNextItemWidth(-150.0f);
    ImGui::InputTextWithHint("##refpath", "reference EXR path", s.refPath, sizeof(s.refPath));
    ImGui::SameLine();
    if (ImGui::Button("Load reference")) {
        s.refMessage = services.loadReference(s.refPath);
        if (s.refMessage.empty()) {
            s.b = kReferenceName;
            if (s.a == kReferenceName) s.a = "Final Radiance";
            s.refMessage = "loaded; B = reference, A = " + s.a;
        }
    }
    if (!s.refMessage.empty()) ImGui::TextWrapped("%s", s.refMessage.c_str());
    ImGui::End();
}

}  // namespace deepgi::ui
