// Buffer inspector, a fixed pane beside the viewport: zoom/pan with a texel grid, channels, exposure and range, the
// raw value under the cursor (a 3x3 readback around it), statistics on demand (empty texels left out, normals as
// vectors), NaN/Inf/negative highlights, empty texels hatched, and error views of A against B: A, B, wipe,
// |A - B|, relative error in false colour with its legend, and the error figures in a line under the image.
#include "renderer/core/gbuffer_codec.h"
#include "ui/viewer_ui.h"

#include "renderer/core/image_compare.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi::ui {

namespace {

const char* kChannels[] = {"RGB", "R", "G", "B", "A", "Luminance"};
const char* kModes[] = {"Auto", "Raw", "Radiance", "Linear depth", "Normal"};
const char* kCompare[] = {"A", "B", "Wipe", "|A - B|", "Relative"};

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

// Depth-like: a depth format that is not the camera's depth (shadow maps, probe depths): shown as grey depth.
bool depthLike(const BufferSource& s) { return s.vis == Visualize::ShadowDepth || (gl::isDepthFormat(s.format) && s.vis != Visualize::Depth); }

}  // namespace

BufferStats computeStats(const FloatImage& img, const std::vector<uint8_t>& mask, bool vectors) {
    BufferStats st;
    st.channels = std::min(img.channels, 4);
    st.vectors = vectors;
    for (int c = 0; c < st.channels; ++c) {
        st.min[c] = std::numeric_limits<double>::max();
        st.max[c] = -std::numeric_limits<double>::max();
    }
    double sum[4] = {0, 0, 0, 0}, lengthSum = 0.0;
    size_t count[4] = {0, 0, 0, 0}, lengthCount = 0;
    const size_t n = size_t(img.width) * img.height;
    const bool useMask = mask.size() == n;
    for (size_t i = 0; i < n; ++i) {
        if (useMask && !mask[i]) { ++st.empty; continue; }
        bool nan = false, inf = false, neg = false;
        double len2 = 0.0;
        for (int c = 0; c < st.channels; ++c) {
            const float v = img.pixels[i * img.channels + c];
            if (std::isnan(v)) { nan = true; continue; }
            if (std::isinf(v)) { inf = true; continue; }
            if (v < 0.0f) neg = true;
            len2 += double(v) * v;
            st.min[c] = std::min(st.min[c], double(v));
            st.max[c] = std::max(st.max[c], double(v));
            sum[c] += v;
            ++count[c];
        }
        if (vectors && !nan && !inf) { lengthSum += std::sqrt(len2); ++lengthCount; }
        st.nan += nan;
        st.inf += inf;
        st.negative += neg && !vectors;
    }
    for (int c = 0; c < st.channels; ++c) {
        st.mean[c] = count[c] ? sum[c] / double(count[c]) : 0.0;
        if (!count[c]) st.min[c] = st.max[c] = 0.0;
    }
    st.meanLength = lengthCount ? lengthSum / double(lengthCount) : 0.0;
    st.texels = n;
    st.valid = true;
    return st;
}

void drawHeatLegend(float scale, float width) {
    static const std::vector<std::array<float, 3>> pal = heatPalette(64);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const float h = 10.0f, w = std::max(width, 60.0f);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const int n = int(pal.size());
    for (int i = 0; i < n; ++i) {
        const auto& c = pal[size_t(i)];
        const ImU32 col = IM_COL32(int(c[0] * 255.0f), int(c[1] * 255.0f), int(c[2] * 255.0f), 255);
        dl->AddRectFilled(ImVec2(p0.x + w * i / n, p0.y), ImVec2(p0.x + w * (i + 1) / n + 0.5f, p0.y + h), col);
    }
    for (int k = 0; k <= 4; ++k) {
        const float x = p0.x + (w - 1.0f) * k / 4.0f;
        dl->AddLine(ImVec2(x, p0.y + h), ImVec2(x, p0.y + h + 3.0f), IM_COL32(220, 220, 220, 255));
        char label[32];
        std::snprintf(label, sizeof(label), "%s%g%%", k == 4 ? ">=" : "", double(scale) * 25.0 * k);
        const float tw = ImGui::CalcTextSize(label).x;
        const float tx = k == 0 ? x : k == 4 ? x - tw : x - tw * 0.5f;
        dl->AddText(ImVec2(tx, p0.y + h + 3.0f), IM_COL32(220, 220, 220, 255), label);
    }
    ImGui::Dummy(ImVec2(w, h + 3.0f + ImGui::GetTextLineHeight()));
}

void drawInspector(InspectorState& s, ViewerServices& services, double now, ImVec2 pos, ImVec2 size) {
    if (!s.open) return;
    ImGui::SetNextWindowPos(pos);
    ImGui::SetNextWindowSize(size);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
    const bool visible = ImGui::Begin("Inspector", &s.open, flags);
    ImGui::PopStyleVar();
    if (!visible) {
        ImGui::End();
        return;
    }
    const std::vector<std::string> names = services.bufferNames();
    if (std::find(names.begin(), names.end(), s.a) == names.end() && !names.empty()) s.a = names.front();
    if (!s.b.empty() && std::find(names.begin(), names.end(), s.b) == names.end()) s.b.clear();

    // Row 1: buffers and the comparison.
    ImGui::SetNextItemWidth(150.0f);
    if (bufferCombo("A##inspA", s.a, names, false)) {
        s.zoom = 0.0f;
        s.stats = {};
        s.level = services.dataLevel(s.a);
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(150.0f);
    bufferCombo("B##inspB", s.b, names, true);
    if (!s.b.empty()) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(90.0f);
        int cm = int(s.compare);
        if (ImGui::Combo("##compare", &cm, kCompare, IM_ARRAYSIZE(kCompare))) s.compare = CompareMode(cm);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("A, B, a wipe between them, |A - B|, or |LA - LB| / LB in false colour");
    }
    BufferSource a = services.source(s.a, s.level);
    if (a.levels > 1) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(70.0f);
        if (ImGui::SliderInt("mip", &s.level, 0, a.levels - 1)) { s.zoom = 0.0f; a = services.source(s.a, s.level); }
    }
    const bool hasB = !s.b.empty();
    const CompareMode mode = hasB ? s.compare : CompareMode::A;

    // Row 2: display.
    ImGui::SetNextItemWidth(80.0f);
    int ch = int(s.params.channel);
    if (ImGui::Combo("##ich", &ch, kChannels, IM_ARRAYSIZE(kChannels))) s.params.channel = ViewChannel(ch);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(100.0f);
    int vmode = int(s.params.mode);
    if (ImGui::Combo("##imode", &vmode, kModes, IM_ARRAYSIZE(kModes))) s.params.mode = ViewMode(vmode);
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
    ImGui::Checkbox("hatch empty", &s.hatchEmpty);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Grey stripes where this layer has no surface (sky, no layer-2 surface)");
    ImGui::SameLine();
    ImGui::Checkbox("grid", &s.params.grid);
    ImGui::SameLine();
    const bool doFit = ImGui::Button("Fit");
    ImGui::SameLine();
    const bool oneToOne = ImGui::Button("1:1");
    ImGui::SameLine();
    ImGui::TextDisabled("%.0f%%", double(s.zoom) * 100.0);
    if (mode == CompareMode::Wipe) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(80.0f);
        ImGui::SliderFloat("split", &s.params.splitX, 0.0f, 1.0f, "%.2f");
    }
    if (mode == CompareMode::Relative) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(90.0f);
        ImGui::SliderFloat("scale", &s.relativeScale, 0.01f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Relative error at the top of the colour scale (1 = 100%%)");
    }

    // Image area: leave room for the description, figures, legend and statistics lines.
    const float infoHeight = ImGui::GetTextLineHeightWithSpacing() * 9.5f;
    ImVec2 area = ImGui::GetContentRegionAvail();
    area.y = std::max(area.y - infoHeight, area.y * 0.6f);  // the image keeps most of a short pane; the lines scroll
    area.x = std::max(area.x, 32.0f);
    area.y = std::max(area.y, 32.0f);
    if (!a.valid()) {
        ImGui::TextDisabled("'%s' is not allocated in the current pipeline", s.a.c_str());
        ImGui::End();
        return;
    }
    // Depth-like textures (shadow maps): grey depth over the range of their values, set once per buffer.
    const bool aDepthLike = depthLike(a);
    if (aDepthLike && s.depthLikeRangeOf != s.a) {
        const BufferStats st = services.stats(s.a, s.level);
        if (st.valid && st.max[0] > st.min[0]) {
            s.params.mode = ViewMode::Raw;
            s.params.channel = ViewChannel::R;
            s.params.useRange = true;
            s.params.rangeMin = float(st.min[0]);
            s.params.rangeMax = float(st.max[0]);
        }
        s.depthLikeRangeOf = s.a;
    }
    if (s.zoom <= 0.0f || doFit) fit(s, a, area);
    if (oneToOne) s.zoom = 1.0f;

    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("##image", area, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle);
    const bool hovered = ImGui::IsItemHovered();
    s.imageRect = glm::vec4(p0.x, p0.y, p0.x + area.x, p0.y + area.y);
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
    if (hasB) b = services.source(s.b, s.level);
    ErrorView ev;
    if (b.valid() && (mode == CompareMode::Diff || mode == CompareMode::Relative || mode == CompareMode::Wipe ||
                      mode == CompareMode::A || mode == CompareMode::B))
        ev = services.errorView(s.a, s.b, s.level, mode, s.relativeScale);
    s.figures = ev.figures;
    // What the image shows: A, B, both (wipe) or the error image, all in A's texel window.
    const BufferSource* first = &a;
    const BufferSource* second = nullptr;
    if (mode == CompareMode::B && b.valid()) {
        first = &b;
        p.origin *= glm::vec2(float(b.levelWidth()) / float(a.levelWidth()), float(b.levelHeight()) / float(a.levelHeight()));
        p.texelsPerPixel *= float(b.levelWidth()) / float(a.levelWidth());
    } else if (mode == CompareMode::Wipe && b.valid()) {
        second = &b;
    } else if ((mode == CompareMode::Diff || mode == CompareMode::Relative) && ev.source.valid()) {
        first = &ev.source;
        const float sx = float(ev.source.levelWidth()) / float(a.levelWidth()), sy = float(ev.source.levelHeight()) / float(a.levelHeight());
        p.origin *= glm::vec2(sx, sy);
        p.texelsPerPixel *= sx;
        if (mode == CompareMode::Relative) { p.mode = ViewMode::Raw; p.channel = ViewChannel::RGB; p.useRange = false; }
        else p.mode = ViewMode::Radiance;
    }
    const GLuint tex = services.drawView(1, *first, second, p, int(area.x), int(area.y));
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddImage((ImTextureID)(intptr_t)tex, p0, ImVec2(p0.x + area.x, p0.y + area.y), ImVec2(0, 1), ImVec2(1, 0));

    // Empty texels of A: a hatch over them (A's side of a wipe, or A alone).
    EmptyMask mask;
    if (s.hatchEmpty && (mode == CompareMode::A || mode == CompareMode::Wipe)) mask = services.emptyMask(s.a, s.level);
    if (mask.texture && mask.empty > 0) {
        const float W = float(a.levelWidth()), H = float(a.levelHeight());
        const glm::vec2 lo = p.origin, hi = p.origin + areaSize / s.zoom;
        const float clipX = mode == CompareMode::Wipe && second ? p0.x + area.x * p.splitX : p0.x + area.x;
        dl->PushClipRect(p0, ImVec2(clipX, p0.y + area.y), true);
        dl->AddImage((ImTextureID)(intptr_t)mask.texture, p0, ImVec2(p0.x + area.x, p0.y + area.y), ImVec2(lo.x / W, hi.y / H),
                     ImVec2(hi.x / W, lo.y / H));
        dl->PopClipRect();
    }

    // Readout under the cursor: a 3x3 block read back around it (never the whole texture).
    if (hovered) {
        const glm::vec2 t = texelAt(io.MousePos);
        const bool onB = b.valid() && ((mode == CompareMode::Wipe && (io.MousePos.x - p0.x) >= p.splitX * area.x) || mode == CompareMode::B);
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
                char line[512];
                std::snprintf(line, sizeof(line), "%s  texel (%d, %d)  uv (%.4f, %.4f)\nraw: %s", onB ? s.b.c_str() : s.a.c_str(), tx,
                              src.levelHeight() - 1 - ty, (tx + 0.5) / src.levelWidth(), 1.0 - (ty + 0.5) / src.levelHeight(),
                              text.c_str());
                std::string readout = line;
                if (src.vis == Visualize::Depth) {
                    const float d = blk.at(tx, ty, 0), n = cam.znear, f = cam.zfar;
                    const float z = linearDepth(d, n, f, cam.perspective);
                    std::snprintf(line, sizeof(line), "\nlinear depth: %.5g%s", double(z), d >= 1.0f ? " (empty: far plane)" : "");
                    readout += line;
                } else if (depthLike(src)) {
                    std::snprintf(line, sizeof(line), "\nlight-space depth: %.6g (0 near .. 1 far)", double(blk.at(tx, ty, 0)));
                    readout += line;
                } else if (src.vis == Visualize::Normal && blk.channels >= 2) {
                    const glm::vec3 v = octDecode(blk.at(tx, ty, 0), blk.at(tx, ty, 1));
                    std::snprintf(line, sizeof(line), "\nnormal: (%.4f, %.4f, %.4f)", double(v.x), double(v.y), double(v.z));
                    readout += line;
                }
                s.readout = readout;
                ImGui::BeginTooltip();
                ImGui::TextUnformatted(readout.c_str());
                ImGui::EndTooltip();
            }
        }
    }

    // Under the image: what the buffer is (the registry's description), the figures line and the legend.
    const std::string desc = services.description(mode == CompareMode::B && b.valid() ? s.b : s.a);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s: %s", (mode == CompareMode::B && b.valid() ? s.b : s.a).c_str(), desc.empty() ? "(no description)" : desc.c_str());
    ImGui::PopTextWrapPos();
    if (hasB) {
        if (!ev.figures.empty()) ImGui::Text("A vs B: %s", ev.figures.c_str());
        else if (!ev.message.empty()) ImGui::TextColored(ImVec4(1, 0.6f, 0.4f, 1), "%s", ev.message.c_str());
        if (mode == CompareMode::Relative) drawHeatLegend(s.relativeScale, std::min(area.x, 360.0f));
    }
    if (mask.texture && mask.empty > 0)
        ImGui::TextDisabled("hatched: %zu of %zu texels have no surface at this layer", mask.empty, mask.texels);

    // Statistics.
    ImGui::Text("%s: %d x %d, mip %d of %d", s.a.c_str(), a.levelWidth(), a.levelHeight(), a.level, a.levels);
    ImGui::SameLine();
    const bool statsNow = ImGui::SmallButton("min/mean/max");
    s.statsButtonRect = glm::vec4(ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y, ImGui::GetItemRectMax().x, ImGui::GetItemRectMax().y);
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
        const char* kC = s.stats.vectors ? "XYZ" : "RGBA";
        for (int c = 0; c < s.stats.channels; ++c)
            ImGui::Text("%c  min %-11.5g mean %-11.5g max %-11.5g", kC[c], s.stats.min[c], s.stats.mean[c], s.stats.max[c]);
        const size_t counted = s.stats.texels - s.stats.empty;
        if (s.stats.vectors)
            ImGui::TextColored(s.stats.nan || s.stats.inf ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.6f, 0.6f, 0.6f, 1),
                               "unit vectors: mean length %.4f; NaN %zu  Inf %zu  of %zu texels (%zu empty left out)",
                               s.stats.meanLength, s.stats.nan, s.stats.inf, counted, s.stats.empty);
        else
            ImGui::TextColored(s.stats.nan || s.stats.inf ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.6f, 0.6f, 0.6f, 1),
                               "NaN %zu   Inf %zu   negative %zu   of %zu texels (%zu empty left out)", s.stats.nan,
                               s.stats.inf, s.stats.negative, counted, s.stats.empty);
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

void drawSplitDivider(float x, float y0, float y1, float x0, float x1, float& split) {
    ImGui::SetNextWindowPos(ImVec2(x, y0));
    ImGui::SetNextWindowSize(ImVec2(kDividerWidth, y1 - y0));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoScrollWithMouse;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    if (ImGui::Begin("##divider", nullptr, flags)) {
        ImGui::InvisibleButton("##drag", ImVec2(kDividerWidth, y1 - y0));
        const bool active = ImGui::IsItemActive(), hovered = ImGui::IsItemHovered();
        if (active && ImGui::GetIO().MouseDelta.x != 0.0f && x1 > x0)
            split = std::clamp(split + ImGui::GetIO().MouseDelta.x / (x1 - x0), kMinSplit, kMaxSplit);
        if (active || hovered) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
        ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(x, y0), ImVec2(x + kDividerWidth, y1),
                                                  active ? IM_COL32(110, 140, 200, 255) : hovered ? IM_COL32(90, 100, 120, 255)
                                                                                                   : IM_COL32(55, 55, 62, 255));
    }
    ImGui::End();
    ImGui::PopStyleVar(2);
}

}  // namespace deepgi::ui
