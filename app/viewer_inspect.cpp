// What the inspector and the viewport's path-trace mode ask of the app: buffers read back, error images, the
// empty-texel hatch, statistics, and the path tracer's live figures.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include "renderer/core/image_compare.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace deepgi {

namespace {

// Uploads a top-down float image into `tex` as a bottom-up RGBA32F texture (GL rows), replacing its storage.
BufferSource upload(gl::TextureHandle& tex, const FloatImage& img, Visualize vis, const char* label) {
    std::vector<float> rgba(size_t(img.width) * img.height * 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const float v = c < img.channels ? img.at(x, y, c) : (c == 3 ? 1.0f : img.channels == 1 ? img.at(x, y, 0) : 0.0f);
                rgba[(size_t(img.height - 1 - y) * img.width + x) * 4 + c] = v;
            }
    tex = gl::createTexture(GL_TEXTURE_2D, label);
    glTextureStorage2D(tex.id(), 1, GL_RGBA32F, img.width, img.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(tex.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, rgba.data());
    BufferSource s;
    s.texture = tex.id();
    s.format = GL_RGBA32F;
    s.width = img.width;
    s.height = img.height;
    s.vis = vis;
    return s;
}

bool endsWith(const std::string& s, const std::string& t) { return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0; }

}  // namespace

std::string Viewer::description(const std::string& name) {
    if (name == ui::kReferenceName) return "the reference image loaded from an EXR (linear radiance)";
    if (name == ui::kPathTraceName)
        return "the path tracer's progressive render of this view, " + std::to_string(ptSnap_.samples) + " samples per pixel";
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!renderer_->textures().findLayer(name, &e, &layer)) return "";
    return e->decl.description;
}

int Viewer::dataLevel(const std::string& name) {
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!renderer_->textures().findLayer(name, &e, &layer)) return 0;
    const PipelineConfig& c = renderer_->config();
    if (e->decl.name == "Input Radiance") return layer == 1 || !c.seedComposite ? c.tapLevel : 0;
    static const char* const gbuffer[] = {"Depth", "Normal", "Albedo", "Emission", "Specular", "Occlusion", "Object ID", "Motion"};
    const bool layer2GBuffer = layer == 1 && std::find(std::begin(gbuffer), std::end(gbuffer), e->decl.name) != std::end(gbuffer);
    return std::min(layer2GBuffer ? renderer_->lastLayer2Level() : 0, e->decl.levels - 1);
}

FloatImage Viewer::readSource(const std::string& name, int level) {
    if (name == ui::kReferenceName) return refImage_;
    if (name == ui::kPathTraceName) return ptSnap_.final;
    return renderer_->readLayer(name, level, true);
}

std::vector<uint8_t> Viewer::surfaceMask(const std::string& name, int level, bool* applies) {
    *applies = false;
    const TextureRegistry& reg = renderer_->textures();
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    // Per-layer screen buffers (G-buffer, radiosity, AO): a texel is empty where its layer's depth is the clear value.
    // The final images are excluded: their sky is the backdrop, which is data.
    if (!reg.findLayer(name, &e, &layer) || !e->decl.size.screenSized() || endsWith(e->decl.name, "Display") ||
        e->decl.name == "Final Radiance" || !reg.has("Depth"))
        return {};
    const std::string depthLayer = endsWith(name, " 2") ? "Depth 2" : "Depth 1";
    const TextureRegistry::Entry& d = reg.entry("Depth");
    if (d.width != e->width || d.height != e->height || (depthLayer == "Depth 2" && d.decl.layers() < 2) ||
        level >= d.decl.levels || level >= e->decl.levels)
        return {};
    const FloatImage depth = renderer_->readLayer(depthLayer, level, false);  // the same level's depth
    std::vector<uint8_t> mask(size_t(depth.width) * depth.height);
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = depth.pixels[i * depth.channels] < 1.0f ? 1 : 0;
    *applies = true;
    return mask;
}

ui::BufferStats Viewer::stats(const std::string& name, int level) {
    if (name == ui::kReferenceName) return ui::computeStats(refImage_);
    if (name == ui::kPathTraceName) return ui::computeStats(ptSnap_.final);
    try {
        bool masked = false;
        const std::vector<uint8_t> mask = surfaceMask(name, level, &masked);
        const BufferSource src = source(name, level);
        const bool vectors = src.vis == Visualize::Normal;  // decoded to unit xyz: counted as vectors
        ui::BufferStats st = ui::computeStats(renderer_->readLayer(name, level, vectors), mask, vectors);
        if (src.vis == Visualize::ShadowDepth || (gl::isDepthFormat(src.format) && src.vis != Visualize::Depth)) {
            // Depth-like: cleared texels (1.0, nothing drawn there) are empty.
            const FloatImage img = renderer_->readLayer(name, level, false);
            std::vector<uint8_t> m(size_t(img.width) * img.height);
            for (size_t i = 0; i < m.size(); ++i) m[i] = img.pixels[i * img.channels] < 1.0f;
            st = ui::computeStats(img, m, false);
        }
        return st;
    } catch (const std::exception&) {
        return {};
    }
}

ui::EmptyMask Viewer::emptyMask(const std::string& name, int level) {
    const std::string key = name + "#" + std::to_string(level) + "#" + std::to_string(renderer_->width()) + "x" +
                            std::to_string(renderer_->height());
    const double t = nowSeconds();
    if (key == maskKey_ && t - maskTime_ < 0.5) return maskLast_;
    maskKey_ = key;
    maskTime_ = t;
    maskLast_ = {};
    bool applies = false;
    const std::vector<uint8_t> mask = surfaceMask(name, level, &applies);
    if (!applies) return maskLast_;
    const TextureRegistry::Entry& d = renderer_->textures().entry("Depth");
    const int w = std::max(1, d.width >> level), h = std::max(1, d.height >> level);  // the level's texels
    // The mask is of the image; the overlay spans the texture, guard band included (left clear: not counted).
    const int g = renderer_->guardTexels(d, level), mw = w - 2 * g, mh = h - 2 * g;
    // Diagonal grey stripes, 6 texels apart: opaque, so an empty texel never reads as data.
    std::vector<unsigned char> px(size_t(w) * h * 4, 0);
    size_t empty = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x < g || y < g || x >= g + mw || y >= g + mh || mask[size_t(y - g) * mw + (x - g)]) continue;
            ++empty;
            const bool stripe = ((x + y) / 3) % 2 == 0;
            unsigned char* p = &px[(size_t(h - 1 - y) * w + x) * 4];  // GL rows bottom-up
            p[0] = p[1] = p[2] = stripe ? 120 : 60;
            p[3] = 255;
        }
    maskTex_ = gl::createTexture(GL_TEXTURE_2D, "empty texel hatch");
    glTextureStorage2D(maskTex_.id(), 1, GL_RGBA8, w, h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(maskTex_.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glTextureParameteri(maskTex_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(maskTex_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(maskTex_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(maskTex_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float transparent[4] = {0, 0, 0, 0};
    glTextureParameterfv(maskTex_.id(), GL_TEXTURE_BORDER_COLOR, transparent);
    maskLast_.texture = maskTex_.id();
    maskLast_.empty = empty;
    maskLast_.texels = size_t(mw) * mh;
    return maskLast_;
}

ui::ErrorView Viewer::errorView(const std::string& a, const std::string& b, int level, ui::CompareMode mode, float scale) {
    char k[64];
    std::snprintf(k, sizeof(k), "#%d#%d#%g#%llu", level, int(mode), double(scale), (unsigned long long)ptSnap_.samples);
    const std::string key = a + "|" + b + k;
    const double t = nowSeconds();
    if (key == errKey_ && t - errTime_ < 0.5) return errLast_;
    errKey_ = key;
    errTime_ = t;
    errLast_ = {};
    try {
        FloatImage ia = readSource(a, level), ib = readSource(b, level);
        if (ia.width <= 0 || ib.width <= 0) { errLast_.message = "nothing to compare yet"; return errLast_; }
        // Different sizes (a reference or the path tracer at another resolution): box-filter the larger one down.
        if (ia.width != ib.width || ia.height != ib.height) {
            if (size_t(ia.width) * ia.height > size_t(ib.width) * ib.height) ia = downsampleBox(ia, ib.width, ib.height);
            else ib = downsampleBox(ib, ia.width, ia.height);
        }
        bool masked = false;
        std::vector<uint8_t> mask = surfaceMask(a, level, &masked);
        if (mask.size() != size_t(ia.width) * ia.height) mask.clear();
        const ImageFigures f = compareImages(ia, ib, mask);
        errLast_.figures = f.line();
        if (mode == ui::CompareMode::Diff) errLast_.source = upload(errTex_, absDifference(ia, ib), Visualize::Radiance, "inspector |A-B|");
        else if (mode == ui::CompareMode::Relative)
            errLast_.source = upload(errTex_, heatMap(relativeError(ia, ib), scale), Visualize::Display, "inspector relative error");
    } catch (const std::exception& e) {
        errLast_.message = std::string("cannot compare: ") + e.what();
    }
    inspector_.figures = errLast_.figures;
    return errLast_;
}

// ---- path trace this view ----------------------------------------------------------------------------------

void Viewer::afterRender() {
    if (view_.pathTrace == ui::PathTraceMode::Off) {
        if (pathTrace_) pathTrace_->pause();
        return;
    }
    if (renderer_->width() <= 0) return;
    if (!pathTrace_) pathTrace_ = std::make_unique<ViewerPathTrace>(scene_);
    // The whole viewport's size, not the dynamic resolution's: a motion's smaller frames do not restart it twice.
    const int w = std::max(1, fullW_ / kPathTraceDivisor), h = std::max(1, fullH_ / kPathTraceDivisor);
    pathTrace_->request(renderer_->camera(), settings_, w, h);
    ViewerPathTrace::Snapshot snap;
    if (!pathTrace_->latest(snap, ptSnap_.samples, ptSnap_.generation)) return;
    const bool restarted = snap.generation != ptSnap_.generation;
    ptSnap_ = std::move(snap);
    upload(ptTex_, ptSnap_.final, Visualize::Radiance, "path trace this view");
    const double t = nowSeconds();
    if (!restarted && t - ptFiguresTime_ < 0.5) return;  // the figures read the frame back: twice a second at most
    ptFiguresTime_ = t;
    try {
        // Whole image: the frame box-filtered to the path tracer's size against its accumulation.
        // Indirect part (docs/gi-accuracy.md): frame - direct against path traced - direct, with the frame's direct
        // taken as frame - its indirect term albedo * E / pi (E = Output Radiance, the composite's own formula):
        // two buffers read back, no second render.
        const FloatImage fin = renderer_->readLayer("Final Radiance", 0, false);
        FloatImage ind{fin.width, fin.height, 3, std::vector<float>(size_t(fin.width) * fin.height * 3, 0.0f)};
        if (renderer_->config().indirect && renderer_->textures().has("Output Radiance")) {
            const FloatImage alb = renderer_->readLayer("Albedo 1", 0, false), e = renderer_->readLayer("Output Radiance", 0, false);
            const FloatImage depth = renderer_->readLayer("Depth 1", 0, false);
            const float k = renderer_->config().seedComposite ? 1.0f : 1.0f / 3.14159265f;
            const int d = renderer_->config().radiosityDownsample;  // E on the radiosity grid (nearest texel)
            for (int y = 0; y < fin.height; ++y)
                for (int x = 0; x < fin.width; ++x) {
                    const size_t i = size_t(y) * fin.width + x;
                    const size_t j = size_t(std::min(y / d, e.height - 1)) * e.width + size_t(std::min(x / d, e.width - 1));
                    if (depth.pixels[i * depth.channels] < 1.0f)
                        for (int c = 0; c < 3; ++c) ind.pixels[i * 3 + c] = alb.pixels[i * alb.channels + c] * e.pixels[j * e.channels + c] * k;
                }
        }
        const int pw = ptSnap_.final.width, ph = ptSnap_.final.height;
        const FloatImage finS = downsampleBox(fin, pw, ph), indS = downsampleBox(ind, pw, ph);
        FloatImage refInd = ptSnap_.final;
        for (int y = 0; y < ph; ++y)
            for (int x = 0; x < pw; ++x)
                for (int c = 0; c < 3; ++c) refInd.at(x, y, c) -= finS.at(x, y, c) - indS.at(x, y, c);  // - frame's direct
        const ImageFigures whole = compareImages(finS, ptSnap_.final), indirect = compareImages(indS, refInd);
        char buf[320];
        std::snprintf(buf, sizeof(buf),
                      "path traced %d spp | whole: rel L1 (4x4) %.1f%%, ratio of means %.3f | indirect: rel L1 (4x4) %.1f%%, "
                      "ratio of means %.3f",
                      ptSnap_.samples, whole.blockRelL1 * 100.0, whole.ratioOfMeans, indirect.blockRelL1 * 100.0,
                      indirect.ratioOfMeans);
        ptFigures_ = buf;
        ptFiguresSamples_ = ptSnap_.samples;
    } catch (const std::exception& e) {
        ptFigures_ = std::string("figures unavailable: ") + e.what();
    }
}

std::string Viewer::pathTraceFiguresLine() const {
    const std::string st = pathTrace_ ? pathTrace_->status() : std::string("starting");
    return ptFigures_.empty() ? "path tracer: " + st : ptFigures_ + "  (" + st + ")";
}

// ---- profiler, pipeline ------------------------------------------------------------------------------------

std::string Viewer::writeProfilerCsv(const std::string& path) {
    std::ofstream out(path);
    out << profiler_.csv();
    if (!out) return "cannot write " + path;
    return "";
}

void Viewer::showTexture(const std::string& name) {
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!renderer_->textures().findLayer(name, &e, &layer)) {
        setStatus("'" + name + "' is not allocated in the current pipeline");
        return;
    }
    const std::string layerName = e->decl.layerNames.empty() ? name : e->decl.layerNames[size_t(layer)];
    view_.buffer = layerName;
    inspector_.a = layerName;
    inspector_.zoom = 0.0f;
    setStatus("showing " + layerName);
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
