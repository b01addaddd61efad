// The viewport's drawing: the shown buffer fitted into it (a smaller frame magnified bilinearly) and its overlay
// lines (view, buffer, render size and dynamic resolution, frame time, the path tracer's figures, the status).
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace deepgi {

void Viewer::drawViewport() {
    ImGuiIO& io = ImGui::GetIO();
    // The viewport: the chosen buffer (or the path tracer, alone or split against the frame), fitted, aspect kept.
    std::string srcName = view_.buffer;
    BufferSource src = source(srcName, 0), split;
    if (!src.valid()) src = source(srcName = "Final Display", 0);
    const ui::PathTraceMode ptMode = pathTraceMode();
    if (ptMode == ui::PathTraceMode::Full) src = source(srcName = ui::kPathTraceName, 0);
    if (ptMode == ui::PathTraceMode::Split) {
        src = source(srcName = "Final Radiance", 0);  // the same display mapping as the path tracer's radiance
        split = source(ui::kPathTraceName, 0);
    }
    const float vw = vpX1_ - vpX0_, vh = vpY1_ - vpY0_;
    const int ow = std::max(1, int(vw * io.DisplayFramebufferScale.x)), oh = std::max(1, int(vh * io.DisplayFramebufferScale.y));
    if (src.valid()) {
        BufferViewParams p = view_.params;
        // The viewport shows the image: a screen-sized buffer's guard band (gbuffer.guard_band) is cut off here (the
        // inspector shows it).
        int guard = 0;
        {
            const TextureRegistry::Entry* e = nullptr;
            int layer = 0;
            if (renderer_->textures().findLayer(srcName, &e, &layer) && e->texture.id() == src.texture)
                guard = renderer_->guardTexels(*e, src.level);
        }
        p.cropA = glm::vec2(float(guard));
        const float sw = float(src.levelWidth() - 2 * guard), sh = float(src.levelHeight() - 2 * guard);
        const float tpp = std::max(sw / float(ow), sh / float(oh));  // texels per output pixel (fit)
        p.texelsPerPixel = tpp;
        p.origin = glm::vec2(sw, sh) * 0.5f - glm::vec2(float(ow), float(oh)) * 0.5f * tpp + p.cropA;
        p.grid = false;
        const Camera& c = renderer_->camera();
        p.znear = c.znear;
        p.zfar = c.zfar;
        p.perspective = c.perspective;
        p.background = glm::vec4(0.16f, 0.16f, 0.17f, 1.0f);
        if (ptMode != ui::PathTraceMode::Off) {
            p.mode = ViewMode::Radiance;
            p.exposureEV += settings_.exposure;  // the frame's exposure, so both halves read as the final image
            p.splitX = view_.pathTraceSplit;
        }
        // A frame smaller than the viewport (dynamic resolution, the resolution slider): the view is drawn at the
        // frame's size and magnified bilinearly into the viewport, not in blocks of whole texels.
        const bool magnify = ptMode == ui::PathTraceMode::Off && tpp < 1.0f && int(sw) == renderer_->width() &&
                             int(sh) == renderer_->height();
        if (magnify) {
            p.texelsPerPixel = 1.0f;
            p.origin = p.cropA;
        }
        // The image as it is (Final Display, 1:1 or magnified, nothing mapped): the UI draws the renderer's texture
        // itself; the view would only copy it (4 ms a frame at 896x688 on llvmpipe).
        const bool plain = srcName == "Final Display" && ptMode == ui::PathTraceMode::Off && src.target == GL_TEXTURE_2D &&
                           src.level == 0 && (p.mode == ViewMode::Auto || p.mode == ViewMode::Raw) &&
                           p.channel == ViewChannel::RGB && !p.useRange &&
                           (magnify || (tpp == 1.0f && int(sw) == ow && int(sh) == oh));
        // The same inputs as the last drawing (a UI frame: nothing rendered since): its texture again, not redrawn.
        ViewportKey key;
        key.params = p;
        key.source = src.texture;
        key.split = split.valid() ? split.texture : 0;
        key.level = src.level;
        key.layer = src.layer;
        key.splitLayer = split.layer;
        key.vis = int(src.vis);
        key.sourceW = src.levelWidth();
        key.sourceH = src.levelHeight();
        key.width = magnify ? int(sw) : ow;
        key.height = magnify ? int(sh) : oh;
        key.frame = renderer_->frameIndex();
        key.pathTraceSamples = ptMode == ui::PathTraceMode::Off ? -1 : ptSnap_.samples;
        key.pathTraceGeneration = ptMode == ui::PathTraceMode::Off ? 0 : ptSnap_.generation;
        key.reference = referenceLoads_;
        const bool same = viewportTex_ && std::memcmp(&key.params, &viewportKey_.params, sizeof(key.params)) == 0 &&
                          key.source == viewportKey_.source && key.split == viewportKey_.split && key.level == viewportKey_.level &&
                          key.layer == viewportKey_.layer && key.splitLayer == viewportKey_.splitLayer && key.vis == viewportKey_.vis &&
                          key.sourceW == viewportKey_.sourceW && key.sourceH == viewportKey_.sourceH &&
                          key.width == viewportKey_.width && key.height == viewportKey_.height && key.frame == viewportKey_.frame &&
                          key.pathTraceSamples == viewportKey_.pathTraceSamples &&
                          key.pathTraceGeneration == viewportKey_.pathTraceGeneration && key.reference == viewportKey_.reference;
        const GLuint tex = plain ? src.texture
                           : same ? viewportTex_ : drawView(0, src, split.valid() ? &split : nullptr, p, key.width, key.height);
        viewportKey_ = key;
        viewportTex_ = renderError_.empty() ? tex : 0;
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, magnify ? GL_LINEAR : GL_NEAREST);
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, magnify ? GL_LINEAR : GL_NEAREST);
        ImVec2 q0(vpX0_, vpY0_), q1(vpX1_, vpY1_);
        if (magnify) {  // the frame's own aspect, centred (it differs from the viewport's by a rounding at most)
            const float k = std::min(vw / sw, vh / sh);
            const float cx = (vpX0_ + vpX1_) * 0.5f, cy = (vpY0_ + vpY1_) * 0.5f;
            q0 = ImVec2(cx - sw * k * 0.5f, cy - sh * k * 0.5f);
            q1 = ImVec2(cx + sw * k * 0.5f, cy + sh * k * 0.5f);
        }
        // Rows bottom-up; the plain texture keeps its guard band, cut off here.
        const float gu = plain ? float(guard) / float(src.levelWidth()) : 0.0f, gv = plain ? float(guard) / float(src.levelHeight()) : 0.0f;
        // Opaque: drawn without blending (llvmpipe would blend each pixel it covers, 0.7 ms at 896x688).
        ImDrawList* bg = ImGui::GetBackgroundDrawList();
        bg->AddCallback([](const ImDrawList*, const ImDrawCmd*) { glDisable(GL_BLEND); }, nullptr);
        bg->AddImage((ImTextureID)(intptr_t)tex, q0, q1, ImVec2(gu, 1.0f - gv), ImVec2(1.0f - gu, gv));
        bg->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
    }

    // Overlay text: view name, sizes, timing, status; the path tracer's figures.
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    auto shadowed = [&](float x, float y, ImU32 col, const std::string& text) {
        dl->AddText(ImVec2(x + 1, y + 1), IM_COL32(0, 0, 0, 200), text.c_str());
        dl->AddText(ImVec2(x, y), col, text.c_str());
    };
    const double fm = recentFrames_.empty() ? 0.0 : recentFrames_.back().frameMs;
    const double rm = profiler_.cpuFrameMs.empty() ? 0.0 : double(profiler_.cpuFrameMs.back());
    char size[128];
    if (!dynres_.enabled()) std::snprintf(size, sizeof(size), "%dx%d", renderer_->width(), renderer_->height());
    else if (dynres_.step() < DynamicResolution::kSteps)
        std::snprintf(size, sizeof(size), "%dx%d dynamic %d/8 of %dx%d (target %.0f ms)", renderer_->width(), renderer_->height(),
                      dynres_.step(), fullW_, fullH_, dynres_.target());
    else std::snprintf(size, sizeof(size), "%dx%d full (target %.0f ms)", renderer_->width(), renderer_->height(), dynres_.target());
    if (converged_) std::snprintf(size + std::strlen(size), sizeof(size) - std::strlen(size), ", converged: idle");
    char line[384];
    std::snprintf(line, sizeof(line), "%s | %s | %s | %.0f ms (render %.0f)", view_.viewName.c_str(),
                  ptMode == ui::PathTraceMode::Off ? view_.buffer.c_str() : "Path trace this view", size, fm, rm);
    shadowed(vpX0_ + 8, vpY0_ + 6, IM_COL32(235, 235, 235, 255), line);
    if (view_.pathTrace != ui::PathTraceMode::Off) {  // the status shows before the first samples arrive
        // One overlay line per part ("path traced N spp", "whole: ...", "indirect: ...") so that narrow views keep them.
        const std::string fig = pathTraceFiguresLine();
        float y = vpY0_ + 6 + ImGui::GetTextLineHeightWithSpacing();
        for (size_t from = 0; from < fig.size();) {
            const size_t bar = fig.find(" | ", from);
            shadowed(vpX0_ + 8, y, IM_COL32(170, 230, 255, 255), fig.substr(from, bar == std::string::npos ? std::string::npos : bar - from));
            y += ImGui::GetTextLineHeightWithSpacing();
            from = bar == std::string::npos ? fig.size() : bar + 3;
        }
        if (ptMode == ui::PathTraceMode::Split) {
            const float sx = vpX0_ + vw * view_.pathTraceSplit;
            shadowed(sx - ImGui::CalcTextSize("real time").x - 8, vpY1_ - 40, IM_COL32(235, 235, 235, 255), "real time");
            shadowed(sx + 8, vpY1_ - 40, IM_COL32(235, 235, 235, 255), "path traced");
        }
    }
    if (!view_.status.empty() && nowSeconds() - statusTime_ < 8.0)
        shadowed(vpX0_ + 8, vpY1_ - 22, IM_COL32(255, 230, 140, 255), view_.status);
    drawEditOverlay();  // the selection's outline, the light icons, the transform's header
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
