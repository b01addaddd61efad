#include "bench/bench.h"

#include "bench/draw.h"
#include "bench/metrics.h"
#include "bench/plot.h"
#include "renderer/core/util.h"
#include "renderer/gl/offscreen_context.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/renderer.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace deepgi::bench {

namespace fs = std::filesystem;

namespace {

std::string slug(const std::string& s) {
    std::string o;
    for (char c : s) o += std::isalnum((unsigned char)c) ? char(std::tolower((unsigned char)c)) : '_';
    return o;
}

std::string fmt(double v, int prec = 3) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", prec, v);
    return b;
}

// key=value for every setting that differs from the defaults.
std::string settingsText(const Settings& s) {
    const Settings def;
    std::string out;
    for (const SettingInfo& info : settingTable()) {
        const double v = info.get(s);
        if (v == info.get(def)) continue;
        if (!out.empty()) out += ' ';
        out += std::string(info.key) + "=" + formatSettingValue(info, v);
    }
    return out.empty() ? "(defaults)" : out;
}

Camera dolly(const Camera& c, float offset) {
    Camera d = c;
    const glm::vec3 right = glm::normalize(glm::vec3(c.cameraToWorld[0]));
    d.cameraToWorld[3] += glm::vec4(right * offset, 0.0f);
    return d;
}

// Per-pixel relative error (mean over channels of |a - r| / (|r| + 0.01)) as a heat map, 1 = 100 %.
OIIO::ImageBuf heatMap(const FloatImage& a, const FloatImage& ref) {
    std::vector<float> e(size_t(a.width) * a.height, 0.0f);
    for (size_t i = 0; i < e.size(); ++i)
        for (int c = 0; c < 3; ++c)
            e[i] += float(std::abs(double(a.pixels[i * 3 + c]) - ref.pixels[i * 3 + c]) / (std::abs(ref.pixels[i * 3 + c]) + 1e-2) / 3.0);
    return draw::heat(e, a.width, a.height);
}

const char* kGiPasses[] = {"Reproject radiance", "Input radiance", "Gather select", "Radiosity gather", "Bilateral blur", "Temporal blend"};

}  // namespace

Settings configSettings(const Settings& base, const BenchConfig& c, const std::vector<std::string>& user) {
    Settings s = base;
    if (!c.preset.empty()) applyPreset(s, c.preset);
    for (const auto& a : user) applyAssignment(s, a);  // what the user set is what runs, preset or not
    for (const auto& a : c.assignments) applyAssignment(s, a);  // what makes the configuration (direct_only)
    return s;
}

FloatImage finalRgb(const Renderer& r) { return rgb(r.readFinalRadiance()); }

std::vector<BenchConfig> defaultConfigs() {
    std::vector<BenchConfig> c = {
        {"default", "", {}, "two layers, predicted (one geometry pass; three with the layer-2 prepass); the defaults = balanced preset"},
        {"direct_only", "", {"radiosity.enabled=false"}, "direct light only"},
        {"layer1", "", {"gbuffer.layer2=false"}, "one layer (plain G-buffer)"},
        {"two_layer_predicted", "", {"gbuffer.generation=predicted", "gbuffer.layer2_prepass=off"},
         "two layers, predicted in one geometry pass (the paper's single pass; the defaults split the layers on software GL)"},
        {"two_layer_peel", "", {"gbuffer.generation=depth_peel"}, "two layers, two-pass depth peeling (oracle)"},
    };
    for (int n : {6, 13, 19, 30, 50})
        c.push_back({"samples_" + std::to_string(n), "", {"radiosity.samples=" + std::to_string(n)}, std::to_string(n) + " taps"});
    for (int m = 0; m <= 3; ++m)
        c.push_back({"min_mip_" + std::to_string(m), "", {"radiosity.min_mip=" + std::to_string(m)}, "finest mip " + std::to_string(m)});
    c.push_back({"blur_on", "", {"blur.enabled=true"}, "bilateral blur on"});
    c.push_back({"blur_off", "", {"blur.enabled=false"}, "bilateral blur off"});
    c.push_back({"temporal_on", "", {"temporal.enabled=true"}, "temporal filter on"});
    c.push_back({"temporal_off", "", {"temporal.enabled=false"}, "temporal filter off"});
    c.push_back({"blur_first", "", {"temporal.order=blur_first"}, "blur, then temporal (the seed)"});
    c.push_back({"temporal_first", "", {"temporal.order=temporal_first"}, "temporal, then blur (the authors' reference)"});
    c.push_back({"composite_physical", "", {"composite.mode=physical"}, "physical composite"});
    c.push_back({"composite_seed", "", {"composite.mode=seed"}, "the seed's composite (E_input1 + E_output * albedo)"});
    for (const char* p : {"performance", "balanced", "quality"}) c.push_back({std::string("preset_") + p, p, {}, std::string(p) + " preset"});
    c.push_back({"ao_same_taps", "", {"ao.enabled=true"}, "defaults + the AO pass with the gather's taps (for the GI/AO ratio)"});
    for (int n : {19, 24, 30, 40, 50})
        c.push_back({"layer1_s" + std::to_string(n), "", {"gbuffer.layer2=false", "radiosity.samples=" + std::to_string(n)},
                     "one layer, " + std::to_string(n) + " taps (equal-time search)"});
    return c;
}

std::vector<std::string> csvColumns(const std::vector<std::string>& passNames) {
    std::vector<std::string> c = {"scene", "camera", "config", "same_as", "settings", "width", "height", "frames",
                                  "timed_frames", "total_ms"};
    for (const auto& p : passNames) c.push_back("ms_" + slug(p));
    for (const char* k : {"memory_bytes", "geometry_passes", "rel_mse", "mean_rel_err", "ssim", "ind_rel_mse",
                          "ind_mean_rel_err", "stability", "path_mean_rel_err"})
        c.push_back(k);
    return c;
}

namespace {

struct ViewData {
    BenchView view;
    std::string label;  // "atrium/courtyard"
    CachedReference ref;
    std::map<std::string, FloatImage> finals;  // for the grid
};

const BenchRow* findRow(const std::vector<BenchRow>& rows, const std::string& scene, const std::string& camera,
                        const std::string& config) {
    for (const auto& r : rows)
        if (r.scene == scene && r.camera == camera && r.config == config) return &r;
    return nullptr;
}

void log(bool quiet, const char* f, const std::string& a) {
    if (!quiet) {
        std::fprintf(stderr, f, a.c_str());
        std::fflush(stderr);
    }
}

}  // namespace

BenchResult runBench(const BenchOptions& o) {
    if (o.views.empty()) throw std::runtime_error("bench: no scene");
    if (o.frames < 2 || o.timedFrames < 1 || o.timedFrames > o.frames)
        throw std::runtime_error("bench: need frames >= 2 and 1 <= timed frames <= frames");
    const std::string cacheDir = o.cacheDir.empty() ? (fs::path(o.outDir) / "cache").string() : o.cacheDir;
    fs::create_directories(o.outDir);

    std::vector<BenchConfig> configs;
    for (const BenchConfig& c : defaultConfigs())
        if (o.configs.empty() || std::find(o.configs.begin(), o.configs.end(), c.name) != o.configs.end()) configs.push_back(c);
    for (const auto& name : o.configs) {
        bool known = false;
        for (const BenchConfig& c : defaultConfigs()) known |= c.name == name;
        if (!known) throw std::runtime_error("bench: unknown configuration '" + name + "' (see deepgi bench --list)");
    }

    BenchResult result;
    if (o.cpuTiming) setenv("LP_NUM_THREADS", "0", 1);  // llvmpipe reads it when the context is created
    gl::OffscreenContext context(o.context);
    result.glRenderer = context.renderer() + " via " + context.description();
    RendererOptions ropt;
    if (!o.shaderDir.empty()) ropt.shaderDir = o.shaderDir;
    // A GPU's passes are timed by timer queries (a glFinish around each would time the driver's round trips).
    const bool gpuTimed = result.gpuTimed = !o.cpuTiming && !context.isSoftware();
    ropt.timing = o.cpuTiming ? TimingMode::ThreadCpu : gpuTimed ? TimingMode::GpuQueries : TimingMode::WallClock;

    std::vector<ViewData> views;
    for (const BenchView& v : o.views) {
        ViewData vd;
        vd.view = v;
        auto scene = std::make_shared<Scene>(loadScene(v.scenePath));
        if (!scene->bounds.valid()) scene->computeBounds();
        attachEnvironment(*scene, o.environment);
        const Camera cam = selectCamera(*scene, v.camera, v.cameraFile);
        Settings viewBase = o.base;
        for (const auto& a : v.assignments) applyAssignment(viewBase, a);
        const std::string sceneName = fs::path(v.scenePath).stem().string();
        const std::string camName = cam.name.empty() ? "default" : cam.name;
        vd.label = sceneName + "/" + camName;
        log(o.quiet, "bench: %s: reference\n", vd.label);
        vd.ref = cachedReference(*scene, cam, viewBase, o.width, o.height, o.spp, o.bounces, cacheDir, o.quiet);
        log(o.quiet, "bench: reference %s\n", vd.ref.path + (vd.ref.cacheHit ? " (cached)" : " (rendered)"));

        // The camera path: a sideways dolly; references at its middle and end.
        const float step = o.pathStep * std::max(scene->bounds.radius(), 1e-3f);
        std::map<int, FloatImage> pathRefs;
        if (o.pathFrames > 0)
            for (int k : {std::max(1, o.pathFrames / 2), o.pathFrames})
                if (!pathRefs.count(k))
                    pathRefs[k] = cachedReference(*scene, dolly(cam, step * float(k)), viewBase, o.width, o.height, o.pathSpp,
                                                  o.bounces, cacheDir, o.quiet).final;

        Renderer r(ropt);
        r.setScene(scene);
        r.resize(o.width, o.height);
        if (result.passNames.empty())
            for (const auto& p : r.passes()) result.passNames.push_back(p->name());

        std::vector<std::pair<Settings, std::string>> done;  // settings already measured -> config name
        for (const BenchConfig& cfg : configs) {
            const Settings s = configSettings(viewBase, cfg, o.userAssignments);
            BenchRow row;
            row.scene = sceneName;
            row.camera = camName;
            row.config = cfg.name;
            row.settingsText = settingsText(s);
            auto same = std::find_if(done.begin(), done.end(), [&](const auto& d) { return d.first == s; });
            if (same != done.end()) {
                const BenchRow* src = findRow(result.rows, sceneName, camName, same->second);
                if (src) {
                    row = *src;
                    row.config = cfg.name;
                    row.sameAs = same->second;
                    result.rows.push_back(row);
                    continue;
                }
            }
            log(o.quiet, "bench:   %s\n", cfg.name);
            // Still camera: converge, then time the last frames and measure the frame-to-frame change.
            r.setCamera(cam);
            r.resetHistory();
            std::map<std::string, std::vector<double>> perPass;
            std::vector<double> totals, changes;
            FloatImage prev;
            for (int f = 0; f < o.frames; ++f) {
                r.render(s);
                if (f < o.frames - o.timedFrames) continue;
                double total = 0.0;
                for (const auto& t : r.timings()) {
                    perPass[t.name].push_back(t.ms);
                    total += t.ms;
                }
                if (!r.timings().empty()) totals.push_back(total);  // timer queries report two frames late
                FloatImage img = finalRgb(r);
                if (!prev.pixels.empty()) changes.push_back(relativeChange(img, prev));
                prev = std::move(img);
            }
            const FloatImage final = prev;
            for (auto& [name, v] : perPass) row.passMs[name] = median(v);
            row.totalMs = median(totals);
            row.memoryBytes = r.textures().memoryReport().totalBytes;
            row.geometryPasses = r.lastGeometryPasses();
            double sum = 0.0;
            for (double c : changes) sum += c;
            row.stability = changes.empty() ? 0.0 : sum / double(changes.size());
            // The camera path, continuing from the converged history.
            std::vector<double> pathErr;
            for (int k = 1; k <= o.pathFrames; ++k) {
                r.setCamera(dolly(cam, step * float(k)));
                r.render(s);
                if (pathRefs.count(k)) pathErr.push_back(meanRelativeError(finalRgb(r), pathRefs[k]));
            }
            sum = 0.0;
            for (double e : pathErr) sum += e;
            row.pathMeanRelErr = pathErr.empty() ? 0.0 : sum / double(pathErr.size());
            // The same configuration without indirect light: its direct part.
            Settings sd = s;
            sd.indirect = false;
            r.setCamera(cam);
            r.resetHistory();
            r.render(sd);
            r.render(sd);
            const FloatImage direct = finalRgb(r);
            const FloatImage indirect = subtract(final, direct);
            row.relMse = relativeMse(final, vd.ref.final);
            row.meanRelErr = meanRelativeError(final, vd.ref.final);
            row.ssim = ssimDisplay(final, vd.ref.final);
            row.indRelMse = relativeMse(indirect, vd.ref.indirect);
            row.indMeanRelErr = meanRelativeError(indirect, vd.ref.indirect);
            vd.finals[cfg.name] = final;
            result.rows.push_back(row);
            done.push_back({s, cfg.name});
            if (!o.quiet)
                std::fprintf(stderr, "bench:     %.1f ms, mean rel err %.3f (indirect %.3f), SSIM %.3f\n", row.totalMs,
                             row.meanRelErr, row.indMeanRelErr, row.ssim);
        }
        views.push_back(std::move(vd));
    }

    // The whole frame of the first view at the whole-frame size, balanced preset.
    std::vector<std::pair<std::string, double>> wholePasses;
    if (o.wholeFrameWidth > 0 && o.wholeFrameHeight > 0) {
        auto scene = std::make_shared<Scene>(loadScene(o.views[0].scenePath));
        attachEnvironment(*scene, o.environment);
        Renderer r(ropt);
        r.setScene(scene);
        r.resize(o.wholeFrameWidth, o.wholeFrameHeight);
        r.setCamera(selectCamera(*scene, o.views[0].camera, o.views[0].cameraFile));
        Settings s = o.base;
        applyPreset(s, "balanced");
        for (const auto& a : o.views[0].assignments) applyAssignment(s, a);
        std::vector<double> totals;
        std::map<std::string, std::vector<double>> perPass;
        const int timed = std::max(1, o.wholeFrameFrames / 2);
        for (int f = 0; f < o.wholeFrameFrames; ++f) {
            r.render(s);
            if (f < o.wholeFrameFrames - timed) continue;
            double total = 0.0;
            for (const auto& t : r.timings()) {
                total += t.ms;
                perPass[t.name].push_back(t.ms);
            }
            if (!r.timings().empty()) totals.push_back(total);
        }
        result.wholeFrameMs = median(totals);
        for (const auto& p : r.passes())
            if (perPass.count(p->name())) wholePasses.push_back({p->name(), median(perPass[p->name()])});
    }

    // ---- the paper's claims as ratios ----
    auto& R = result.ratioLines;
    for (const ViewData& vd : views) {
        const std::string sc = fs::path(vd.view.scenePath).stem().string();
        const std::string cam = vd.label.substr(vd.label.find('/') + 1);
        // The paper's claim is about its single pass; the defaults' row stands in where that configuration was not run.
        const BenchRow* pred = findRow(result.rows, sc, cam, "two_layer_predicted");
        if (!pred) pred = findRow(result.rows, sc, cam, "default");
        const BenchRow* peel = findRow(result.rows, sc, cam, "two_layer_peel");
        if (pred && peel && pred->passMs.count("Deep G-buffer") && peel->passMs.count("Deep G-buffer")) {
            const double a = pred->passMs.at("Deep G-buffer"), b = peel->passMs.at("Deep G-buffer");
            // Predicted is one geometry pass, or three with gbuffer.layer2_prepass (peeling: two, or three).
            auto passes = [](int n) { return std::to_string(n) + (n == 1 ? " geometry pass" : " geometry passes"); };
            R.push_back(vd.label + ": predicted deep G-buffer " + fmt(a, 2) + " ms (" + passes(pred->geometryPasses) +
                        ") vs depth peeling " + fmt(b, 2) + " ms (" + passes(peel->geometryPasses) + "): ratio " + fmt(a / b, 2) + " (target <= 0.70: " + (a / b <= 0.7 ? "met" : "not met") + ")");
        }
        const BenchRow* ao = findRow(result.rows, sc, cam, "ao_same_taps");
        if (ao && ao->passMs.count("Ambient occlusion")) {
            double gi = 0.0;
            for (const char* p : kGiPasses)
                if (ao->passMs.count(p)) gi += ao->passMs.at(p);
            const double a = ao->passMs.at("Ambient occlusion");
            const double gather = ao->passMs.count("Radiosity gather") ? ao->passMs.at("Radiosity gather") : 0.0;
            R.push_back(vd.label + ": GI passes (reproject, input radiance + mips, gather select, gather, blur, temporal) " + fmt(gi, 2) +
                        " ms vs AO pass with the same taps " + fmt(a, 2) + " ms: ratio " + fmt(gi / a, 2) +
                        " (target <= 1.50: " + (gi / a <= 1.5 ? "met" : "not met") + "); gather alone / AO = " + fmt(gather / a, 2));
        }
        const BenchRow* two = findRow(result.rows, sc, cam, "default");
        std::vector<std::pair<double, const BenchRow*>> one;  // (time, row)
        for (const auto& r : result.rows)
            if (r.scene == sc && r.camera == cam && r.sameAs.empty() &&
                (r.config == "layer1" || r.config.rfind("layer1_s", 0) == 0))
                one.push_back({r.totalMs, &r});
        std::sort(one.begin(), one.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        if (two && !one.empty()) {
            const double T = two->totalMs;
            double e1 = 0.0, f1 = 0.0;
            std::string how;
            if (T <= one.front().first) {
                e1 = one.front().second->indMeanRelErr;
                f1 = one.front().second->meanRelErr;
                how = "the cheapest 1-layer run (" + one.front().second->config + ", " + fmt(one.front().first, 1) + " ms) is already slower";
            } else if (T >= one.back().first) {
                e1 = one.back().second->indMeanRelErr;
                f1 = one.back().second->meanRelErr;
                how = "even " + one.back().second->config + " (" + fmt(one.back().first, 1) + " ms) is faster; its error is used";
            } else {
                size_t k = 1;
                while (one[k].first < T) ++k;
                const auto& a = one[k - 1];
                const auto& b = one[k];
                const double t = (T - a.first) / std::max(b.first - a.first, 1e-9);
                e1 = a.second->indMeanRelErr + t * (b.second->indMeanRelErr - a.second->indMeanRelErr);
                f1 = a.second->meanRelErr + t * (b.second->meanRelErr - a.second->meanRelErr);
                how = "interpolated between " + a.second->config + " (" + fmt(a.first, 1) + " ms) and " + b.second->config + " (" +
                      fmt(b.first, 1) + " ms)";
            }
            R.push_back(vd.label + ": equal time (" + fmt(T, 1) + " ms): indirect mean relative error 2 layers " +
                        fmt(two->indMeanRelErr) + " vs 1 layer " + fmt(e1) + ": ratio " + fmt(two->indMeanRelErr / e1, 2) +
                        " (target <= 0.70: " + (two->indMeanRelErr / e1 <= 0.7 ? "met" : "not met") + "); final image " +
                        fmt(two->meanRelErr) + " vs " + fmt(f1) + "; 1-layer error " + how);
        }
    }
    if (result.wholeFrameMs > 0.0) {
        std::string per;
        for (const auto& [n, ms] : wholePasses) per += (per.empty() ? "" : ", ") + n + " " + fmt(ms, 1);
        R.push_back(views[0].label + " at " + std::to_string(o.wholeFrameWidth) + "x" + std::to_string(o.wholeFrameHeight) +
                    " balanced: median frame " + fmt(result.wholeFrameMs, 1) + (o.cpuTiming ? " CPU ms on one llvmpipe thread" : " ms") + " (target <= 100 ms: " +
                    (result.wholeFrameMs <= 100.0 ? "met" : "not met") + "); per pass: " + per);
    }

    // ---- results.csv ----
    {
        std::ofstream f(fs::path(o.outDir) / "results.csv");
        const auto cols = csvColumns(result.passNames);
        for (size_t i = 0; i < cols.size(); ++i) f << (i ? "," : "") << cols[i];
        f << "\n";
        for (const auto& r : result.rows) {
            f << r.scene << "," << r.camera << "," << r.config << "," << r.sameAs << ",\"" << r.settingsText << "\","
              << o.width << "," << o.height << "," << o.frames << "," << o.timedFrames << "," << fmt(r.totalMs, 3);
            for (const auto& p : result.passNames) f << "," << fmt(r.passMs.count(p) ? r.passMs.at(p) : 0.0, 3);
            f << "," << r.memoryBytes << "," << r.geometryPasses << "," << fmt(r.relMse, 5) << "," << fmt(r.meanRelErr, 5) << ","
              << fmt(r.ssim, 5) << "," << fmt(r.indRelMse, 5) << "," << fmt(r.indMeanRelErr, 5) << "," << fmt(r.stability, 5)
              << "," << fmt(r.pathMeanRelErr, 5) << "\n";
        }
    }

    // ---- plots ----
    const draw::Colour palette[] = {{0.12f, 0.47f, 0.71f}, {0.84f, 0.15f, 0.16f}, {0.17f, 0.63f, 0.17f}, {0.58f, 0.40f, 0.74f}, {1.0f, 0.5f, 0.05f}};
    for (int which = 0; which < 2; ++which) {
        std::vector<PlotSeries> series;
        for (size_t v = 0; v < views.size(); ++v) {
            PlotSeries s;
            s.name = views[v].label;
            s.color = palette[v % 5];
            const std::string sc = fs::path(views[v].view.scenePath).stem().string();
            for (const auto& r : result.rows)
                if (r.sameAs.empty() && r.scene + "/" + r.camera == views[v].label) {
                    s.x.push_back(r.totalMs);
                    s.y.push_back(which == 0 ? r.meanRelErr : r.indMeanRelErr);
                    s.labels.push_back(r.config);
                }
            series.push_back(s);
        }
        const OIIO::ImageBuf c = speedErrorPlot(series, which == 0 ? "speed against error: final image" : "speed against error: indirect light",
                                        "median frame time (ms), " + std::to_string(o.width) + "x" + std::to_string(o.height),
                                        which == 0 ? "mean relative error of the final image" : "mean relative error of the indirect part");
        draw::savePng(c, (fs::path(o.outDir) / (which == 0 ? "speed_error.png" : "speed_error_indirect.png")).string());
    }

    // ---- image grids: reference | method | relative-error heat map ----
    for (const ViewData& vd : views) {
        std::vector<std::string> rowsShown;
        for (const char* n : {"default", "layer1", "direct_only", "preset_quality"})
            if (vd.finals.count(n)) rowsShown.push_back(n);
        if (rowsShown.empty() && !vd.finals.empty()) rowsShown.push_back(vd.finals.begin()->first);
        if (rowsShown.empty()) continue;
        const int W = o.width, H = o.height, pad = 16;
        OIIO::ImageBuf cv = draw::canvas(3 * W + 4, int(rowsShown.size()) * (H + pad) + 16);
        draw::text(cv, 2, 1, vd.label + ": reference | method | relative error (black 0, yellow >= 100%)");
        const OIIO::ImageBuf refPx = draw::display(vd.ref.final);
        for (size_t i = 0; i < rowsShown.size(); ++i) {
            const int y = 16 + int(i) * (H + pad);
            const FloatImage& img = vd.finals.at(rowsShown[i]);
            const BenchRow* row = findRow(result.rows, fs::path(vd.view.scenePath).stem().string(),
                                          vd.label.substr(vd.label.find('/') + 1), rowsShown[i]);
            draw::text(cv, 2, y, "reference " + std::to_string(o.spp) + " spp", {0, 0, 0}, 11);
            draw::text(cv, W + 4, y, rowsShown[i] + (row ? "  " + fmt(row->totalMs, 1) + " ms" : ""), {0, 0, 0}, 11);
            draw::text(cv, 2 * W + 4, y, row ? "mean rel err " + fmt(row->meanRelErr) : "", {0, 0, 0}, 11);
            draw::paste(cv, 0, y + pad - 2, refPx);
            draw::paste(cv, W + 2, y + pad - 2, draw::display(img));
            draw::paste(cv, 2 * W + 4, y + pad - 2, heatMap(img, vd.ref.final));
        }
        draw::savePng(cv, (fs::path(o.outDir) / ("grid_" + slug(vd.label) + ".png")).string());
    }

    // ---- results.md ----
    {
        std::ofstream f(fs::path(o.outDir) / "results.md");
        f << "# deepgi bench\n\n";
        f << "Renderer: " << result.glRenderer << "; " << o.width << "x" << o.height << ", " << o.frames
          << " frames per configuration, timing = median of the last " << o.timedFrames
          << (o.cpuTiming ? " (CPU time of the rendering thread per pass, glFinish around each; LP_NUM_THREADS=0: llvmpipe on one thread)"
                          : result.gpuTimed ? " (GL_TIME_ELAPSED queries per pass)" : " (wall clock around glFinish per pass)")
          << "; reference " << o.spp << " spp, " << o.bounces << " bounces; path: "
          << o.pathFrames << " frames of sideways dolly (" << o.pathStep << " x scene radius per frame), references "
          << o.pathSpp << " spp at the middle and the end.\n\n";
        f << "## The paper's claims, measured side by side\n\n";
        for (const auto& l : R) f << "- " << l << "\n";
        f << "\n## Results\n\n";
        f << "Errors against the reference: relMSE = mean (x-r)^2/(r^2+0.01), MRE = mean |x-r|/(|r|+0.01) over pixels and "
             "channels; SSIM of the sRGB-clamped luminance; \"ind\" = the indirect part (final minus the same configuration "
             "rendered without indirect light, against the reference's indirect.exr); stability = mean relative change "
             "between consecutive converged frames (still camera); path MRE = mean relative error along the camera path.\n\n";
        f << "| view | config | same as | ms | G-buffer | gather | blur | memory MB | relMSE | MRE | SSIM | ind relMSE | ind MRE | stability | path MRE |\n";
        f << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        for (const auto& r : result.rows) {
            auto pm = [&](const char* p) { return r.passMs.count(p) ? fmt(r.passMs.at(p), 1) : std::string("-"); };
            f << "| " << r.scene << "/" << r.camera << " | " << r.config << " | " << r.sameAs << " | " << fmt(r.totalMs, 1)
              << " | " << pm("Deep G-buffer") << " | " << pm("Radiosity gather") << " | " << pm("Bilateral blur") << " | "
              << fmt(double(r.memoryBytes) / (1024.0 * 1024.0), 2) << " | " << fmt(r.relMse, 4) << " | " << fmt(r.meanRelErr, 4)
              << " | " << fmt(r.ssim, 4) << " | " << fmt(r.indRelMse, 4) << " | " << fmt(r.indMeanRelErr, 4) << " | "
              << fmt(r.stability, 4) << " | " << fmt(r.pathMeanRelErr, 4) << " |\n";
        }
        f << "\n## Per-pass medians (ms)\n\n| view | config |";
        for (const auto& p : result.passNames) f << " " << p << " |";
        f << "\n|---|---|";
        for (size_t i = 0; i < result.passNames.size(); ++i) f << "---|";
        f << "\n";
        for (const auto& r : result.rows) {
            if (!r.sameAs.empty()) continue;
            f << "| " << r.scene << "/" << r.camera << " | " << r.config << " |";
            for (const auto& p : result.passNames) f << " " << (r.passMs.count(p) ? fmt(r.passMs.at(p), 2) : std::string("-")) << " |";
            f << "\n";
        }
        f << "\n## Configurations\n\n| config | settings | what |\n|---|---|---|\n";
        for (const BenchConfig& c : configs) f << "| " << c.name << " | " << settingsText(configSettings(o.base, c, o.userAssignments)) << " | " << c.description << " |\n";
        f << "\nFigures: `speed_error.png`, `speed_error_indirect.png` (Pareto front ringed and joined), `grid_<view>.png`.\n";
    }
    return result;
}

}  // namespace deepgi::bench
