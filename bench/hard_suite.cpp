#include "bench/hard_suite.h"

#include "bench/draw.h"
#include "bench/gi_figures.h"
#include "bench/metrics.h"
#include "renderer/core/util.h"
#include "renderer/gl/offscreen_context.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/renderer.h"
#include "renderer/scene/scene_loader.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace deepgi::bench {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kFurnaceExact = 0.2, kFurnaceOneBounce = 0.15;  // e / (1 - a) and e + a e, a = 0.5, e = 0.1

std::string num(double v, int prec = 3) {
    if (std::isnan(v)) return "-";
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", prec, v);
    return b;
}
std::string pct(double v) { return std::isnan(v) ? "-" : num(100.0 * v, 2) + " %"; }

std::string scaleName(double s) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", s);
    return b;
}

std::string sceneDirName(const std::string& base, double scale) {
    return scale == 1.0 ? base : base + "_s" + scaleName(scale);
}

double meanLuminance(const FloatImage& img) {
    const LumaImage l = luminance(img);
    double s = 0.0;
    for (double v : l.v) s += v;
    return l.v.empty() ? 0.0 : s / double(l.v.size());
}

Camera lookAtCamera(const Camera& base, const glm::vec3& eye, const glm::vec3& target) {
    Camera c = base;
    c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    return c;
}

struct CameraPath {
    int frames = 0;
    std::vector<int> referenceFrames;
    std::vector<std::pair<glm::vec3, glm::vec3>> keys;  // eye, target
    Camera at(const Camera& base, int frame) const {
        const float t = float(frame) / float(frames) * float(keys.size() - 1);
        const size_t k = std::min(size_t(t), keys.size() - 2);
        const float u = t - float(k);
        return lookAtCamera(base, glm::mix(keys[k].first, keys[k + 1].first, u), glm::mix(keys[k].second, keys[k + 1].second, u));
    }
};

CameraPath loadPath(const fs::path& file) {
    std::ifstream f(file);
    if (!f) throw std::runtime_error("bench: cannot read " + file.string());
    nlohmann::json j;
    try {
        f >> j;
    } catch (const std::exception& e) {
        throw std::runtime_error("bench: " + file.string() + ": not valid JSON: " + e.what());
    }
    CameraPath p;
    auto vec = [&](const nlohmann::json& v) {
        if (!v.is_array() || v.size() != 3) throw std::runtime_error("bench: " + file.string() + ": a key's eye/target must be [x, y, z]");
        return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
    };
    try {
        p.frames = j.at("frames").get<int>();
        for (const auto& r : j.at("reference_frames")) p.referenceFrames.push_back(r.get<int>());
        for (const auto& k : j.at("keys")) p.keys.push_back({vec(k.at("eye")), vec(k.at("target"))});
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error("bench: " + file.string() + ": " + e.what());
    }
    if (p.frames < 1 || p.keys.size() < 2) throw std::runtime_error("bench: " + file.string() + ": needs frames >= 1 and 2 keys or more");
    for (int r : p.referenceFrames)
        if (r < 1 || r > p.frames) throw std::runtime_error("bench: " + file.string() + ": reference frame " + std::to_string(r) + " outside 1.." + std::to_string(p.frames));
    return p;
}

enum class ViewKind { Normal, Dark, Furnace };

struct View {
    std::string scene, camera;
    ViewKind kind;
};

const std::vector<View>& views() {
    static const std::vector<View> v = {
        {"offscreen_light", "corner", ViewKind::Normal}, {"thin_wall", "lit", ViewKind::Normal},
        {"thin_wall", "dark", ViewKind::Dark},           {"hidden_emitter", "front", ViewKind::Normal},
        {"sun_patch", "corner", ViewKind::Normal},       {"furnace", "inside", ViewKind::Furnace},
        {"occluder", "above", ViewKind::Normal}};
    return v;
}

// The images of one run of one configuration.
struct RunImages {
    FloatImage final, direct, oneBounce;
    double frameMs = 0.0;
    std::vector<FloatImage> pathFinals, pathDirects;
};

RunImages runView(Renderer& r, const Camera& cam, const Settings& s, const HardOptions& o, const CameraPath* path) {
    RunImages out;
    std::vector<double> totals;
    r.setCamera(cam);
    r.resetHistory();
    for (int f = 0; f < o.frames; ++f) {
        r.render(s);
        if (f < o.frames - o.timedFrames) continue;
        double t = 0.0;
        for (const auto& p : r.timings()) t += p.ms;
        totals.push_back(t);
    }
    out.frameMs = median(totals);
    out.final = finalRgb(r);
    std::vector<Camera> pathCams;
    if (path) {  // continues from the converged history
        for (int k = 1; k <= path->frames; ++k) {
            const Camera c = path->at(cam, k);
            r.setCamera(c);
            r.render(s);
            if (std::find(path->referenceFrames.begin(), path->referenceFrames.end(), k) != path->referenceFrames.end()) {
                out.pathFinals.push_back(finalRgb(r));
                pathCams.push_back(c);
            }
        }
    }
    Settings sd = s;
    sd.indirect = false;
    auto direct = [&](const Camera& c) {
        r.setCamera(c);
        r.resetHistory();
        r.render(sd);
        r.render(sd);
        return finalRgb(r);
    };
    out.direct = direct(cam);
    for (const Camera& c : pathCams) out.pathDirects.push_back(direct(c));
    Settings s1 = s;
    s1.damping = 1.0f;
    r.setCamera(cam);
    r.resetHistory();
    for (int f = 0; f < o.oneBounceFrames; ++f) r.render(s1);
    out.oneBounce = finalRgb(r);
    return out;
}

// Heat-map values: |block mean difference| / mean L_ref, 1 = 100 %, nearest-upsampled to pixels.
std::vector<float> blockErrorMap(const FloatImage& test, const FloatImage& ref, double norm) {
    const LumaImage t = blockMeans(luminance(test)), rr = blockMeans(luminance(ref));
    std::vector<float> v(size_t(test.width) * test.height);
    for (int y = 0; y < test.height; ++y)
        for (int x = 0; x < test.width; ++x) {
            const size_t b = size_t(y / 4) * t.width + x / 4;
            v[size_t(y) * test.width + x] = norm > 0.0 ? float(std::abs(t.v[b] - rr.v[b]) / norm) : 1.0f;
        }
    return v;
}

struct GridRow {
    std::string label, refCaption, testCaption, heatCaption;
    FloatImage ref, test;
    std::vector<float> heat;
    float scale;
};

void writeGrid(const std::string& title, const std::vector<GridRow>& rows, int w, int h, const std::string& path) {
    const int head = 18, cap = 16, gap = 4;
    OIIO::ImageBuf g = draw::canvas(3 * w + 2 * gap, head + int(rows.size()) * (cap + h + gap));
    draw::text(g, 2, 2, title, {0, 0, 0}, 13);
    for (size_t i = 0; i < rows.size(); ++i) {
        const GridRow& r = rows[i];
        const int y = head + int(i) * (cap + h + gap);
        draw::text(g, 2, y + 1, r.refCaption, {0, 0, 0}, 11);
        draw::text(g, w + gap + 2, y + 1, r.testCaption, {0, 0, 0}, 11);
        draw::text(g, 2 * (w + gap) + 2, y + 1, r.heatCaption, {0, 0, 0}, 11);
        draw::paste(g, 0, y + cap, draw::display(r.ref, r.scale));
        draw::paste(g, w + gap, y + cap, draw::display(r.test, r.scale));
        draw::paste(g, 2 * (w + gap), y + cap, draw::heat(r.heat, w, h));
    }
    draw::savePng(g, path);
}

void log(const HardOptions& o, const std::string& s) {
    if (o.quiet) return;
    std::fprintf(stderr, "bench hard: %s\n", s.c_str());
    std::fflush(stderr);
}

}  // namespace

std::string hardSceneList() {
    std::vector<std::string> names;
    for (const View& v : views())
        if (std::find(names.begin(), names.end(), v.scene) == names.end()) names.push_back(v.scene);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

std::vector<std::pair<std::string, std::string>> hardViews() {
    std::vector<std::pair<std::string, std::string>> v;
    for (const View& x : views()) v.push_back({x.scene, x.camera});
    return v;
}

HardResult runHardSuite(const HardOptions& options) {
    // The GI figures compare diffuse against diffuse: every material Lambertian (albedo = base colour) in the
    // renderer and the references alike, whatever a scene's materials say (material.diffuse_only).
    HardOptions o = options;
    o.base.diffuseOnly = true;
    if (o.frames < 2 || o.timedFrames < 1 || o.timedFrames > o.frames || o.oneBounceFrames < 1)
        throw std::runtime_error("bench: need frames >= 2, 1 <= timed frames <= frames and one-bounce frames >= 1");
    const auto tStart = std::chrono::steady_clock::now();
    const fs::path assets = o.assetDir.empty() ? fs::path(DEEPGI_ASSET_DIR) : fs::path(o.assetDir);
    const std::string cacheDir = o.cacheDir.empty() ? (fs::path(o.outDir) / "cache").string() : o.cacheDir;
    fs::create_directories(o.outDir);
    for (const auto& s : o.scenes) {
        bool known = false;
        for (const View& v : views()) known |= v.scene == s;
        if (!known) throw std::runtime_error("bench: unknown hard scene '" + s + "' (" + hardSceneList() + ")");
    }
    std::vector<BenchConfig> configs;
    const std::vector<std::string> names = o.configs.empty() ? std::vector<std::string>{"default"} : o.configs;
    for (const auto& n : names) {
        bool found = false;
        for (const BenchConfig& c : defaultConfigs())
            if (c.name == n) {
                configs.push_back(c);
                found = true;
            }
        if (!found) throw std::runtime_error("bench: unknown configuration '" + n + "' (see deepgi bench --list)");
    }

    gl::OffscreenContext context(o.context);
    RendererOptions ropt;
    if (!o.shaderDir.empty()) ropt.shaderDir = o.shaderDir;
    ropt.timing = TimingMode::WallClock;

    HardResult result;
    std::map<std::string, double> litLevel;  // scale-1 lit-side indirect level per scene (thin wall)
    std::ostringstream text;
    for (const View& view : views()) {
        if (!o.scenes.empty() && std::find(o.scenes.begin(), o.scenes.end(), view.scene) == o.scenes.end()) continue;
        const std::string label = view.scene + "/" + view.camera;
        auto load = [&](double scale) {
            const std::string dir = sceneDirName(view.scene, scale);
            const fs::path file = assets / "hard" / dir / (dir + ".gltf");
            if (!fs::exists(file)) throw std::runtime_error("bench: " + file.string() + " not found (run /usr/bin/python3 tools/gen_scenes.py)");
            auto scene = std::make_shared<Scene>(loadScene(file.string()));
            if (!scene->bounds.valid()) scene->computeBounds();
            return std::make_pair(scene, file);
        };
        auto [scene1, file1] = load(1.0);
        const Camera cam1 = selectCamera(*scene1, view.camera);

        // ---- references (scale 1; the scaled scenes have the same true image) ----
        FloorReference full, one;
        std::string refInfo;
        if (view.kind == ViewKind::Furnace) {
            full.final = constantImage(o.width, o.height, float(kFurnaceExact));
            one.final = constantImage(o.width, o.height, float(kFurnaceOneBounce));
            refInfo = "exact: radiance 0.2 everywhere (0.15 after one bounce), no reference needed";
        } else {
            const int spp = view.kind == ViewKind::Dark ? 16 : o.spp;  // dark: only checks the truth is 0
            log(o, label + ": reference " + std::to_string(spp) + " spp, " + std::to_string(o.bounces) + " bounces");
            full = floorReference(*scene1, cam1, o.base, o.width, o.height, spp, o.bounces, cacheDir, o.quiet);
            refInfo = "reference " + std::to_string(spp) + " spp x " + std::to_string(o.bounces) + " bounces, " +
                      num(full.seconds, 1) + " s" + (full.cacheHit ? " (cached)" : "") + ", noise floor indirect " +
                      pct(full.floorIndirect) + " / final " + pct(full.floorFinal);
            if (view.kind == ViewKind::Normal) {
                log(o, label + ": 1-bounce reference " + std::to_string(o.oneBounceSpp) + " spp");
                one = floorReference(*scene1, cam1, o.base, o.width, o.height, o.oneBounceSpp, 1, cacheDir, o.quiet);
                refInfo += "; 1-bounce reference " + std::to_string(o.oneBounceSpp) + " spp, " + num(one.seconds, 1) + " s" +
                           (one.cacheHit ? " (cached)" : "") + ", floor " + pct(one.floorIndirect);
                if (view.scene == "thin_wall") litLevel[view.scene] = meanLuminance(full.indirect);
            } else {
                const Leak truth = leak(full.final);
                refInfo += "; reference luminance in view: mean " + num(truth.mean, 6) + ", max " + num(truth.max, 6) +
                           " (exactly 0 by construction)";
            }
        }
        result.referenceLines.push_back(label + ": " + refInfo + (full.path.empty() ? "" : "; cache " + full.path));

        // ---- camera path (scale 1 only) ----
        CameraPath path;
        bool withPath = false;
        std::vector<FloorReference> pathRefs;
        if (o.cameraPath && fs::exists(file1.parent_path() / "path.json") && view.kind == ViewKind::Normal) {
            path = loadPath(file1.parent_path() / "path.json");
            withPath = true;
            for (int k : path.referenceFrames) {
                log(o, label + ": path reference at frame " + std::to_string(k) + ", " + std::to_string(o.pathSpp) + " spp");
                pathRefs.push_back(floorReference(*scene1, path.at(cam1, k), o.base, o.width, o.height, o.pathSpp, o.bounces, cacheDir, o.quiet));
                result.referenceLines.push_back(label + " path frame " + std::to_string(k) + ": " + std::to_string(o.pathSpp) +
                                                " spp, " + num(pathRefs.back().seconds, 1) + " s" +
                                                (pathRefs.back().cacheHit ? " (cached)" : "") + ", floor indirect " +
                                                pct(pathRefs.back().floorIndirect));
            }
        }

        // ---- deepgi ----
        std::map<std::string, FloatImage> finalAtScale1;
        std::vector<HardRow> viewRows;
        for (double scale : o.scales) {
            auto [scene, file] = scale == 1.0 ? std::make_pair(scene1, file1) : load(scale);
            const Camera cam = selectCamera(*scene, view.camera);
            Renderer r(ropt);
            r.setScene(scene);
            r.resize(o.width, o.height);
            std::vector<GridRow> grid;
            for (const BenchConfig& cfg : configs) {
                const Settings s = configSettings(o.base, cfg, o.userAssignments);
                log(o, label + " scale " + scaleName(scale) + ": " + cfg.name);
                const RunImages run = runView(r, cam, s, o, withPath && scale == 1.0 ? &path : nullptr);
                HardRow row{view.scene, view.camera, cfg.name, scale, run.frameMs,
                            kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
                const FloatImage ind = subtract(run.final, run.direct);
                const FloatImage ind1 = subtract(run.oneBounce, run.direct);
                const FloatImage refInd = subtract(full.final, run.direct);
                const FloatImage refInd1 = view.kind == ViewKind::Dark ? FloatImage{} : subtract(one.final, run.direct);
                const double refMean = meanLuminance(refInd);
                if (view.kind == ViewKind::Dark) {
                    const Leak k = leak(run.final);
                    row.leakMean = k.mean;
                    row.leakMax = k.max;
                    const double level = litLevel.count(view.scene) ? litLevel[view.scene] : kNaN;
                    row.leakMeanRel = k.mean / level;
                    row.leakMaxRel = k.max / level;
                    std::vector<float> heat(size_t(o.width) * o.height);
                    const LumaImage l = luminance(run.final);
                    for (size_t i = 0; i < heat.size(); ++i) heat[i] = float(l.v[i] / (0.05 * level));
                    grid.push_back({cfg.name, "reference: exactly 0", cfg.name + " final, " + num(run.frameMs, 1) + " ms",
                                    "luminance / (5 % of lit level): leak mean " + pct(row.leakMeanRel) + " max " + pct(row.leakMaxRel),
                                    full.final, run.final, heat, float(0.4 / std::max(level, 1e-30))});
                } else {
                    row.indRelL1 = relativeL1(ind, refInd);
                    row.indRatio = ratioOfMeans(ind, refInd);
                    row.oneRelL1 = relativeL1(ind1, refInd1);
                    row.oneRatio = ratioOfMeans(ind1, refInd1);
                    row.finalRelL1 = relativeL1(run.final, full.final);
                    const float dispScale = float(0.4 / std::max(refMean, 1e-30));
                    if (view.kind == ViewKind::Furnace) {
                        const Deviation d = deviationFromConstant(run.final, kFurnaceExact);
                        row.furnaceMaxDev = d.maxRel;
                        row.furnaceMeanDev = d.meanRel;
                        row.furnaceRatio = d.ratio;
                        std::vector<float> heat(size_t(o.width) * o.height);
                        const LumaImage l = luminance(run.final);
                        for (size_t i = 0; i < heat.size(); ++i) heat[i] = float(std::abs(l.v[i] / kFurnaceExact - 1.0) / 0.1);
                        grid.push_back({cfg.name, "exact final 0.2", cfg.name + " final, " + num(run.frameMs, 1) + " ms",
                                        "|L/0.2 - 1| / 10 %: max " + pct(d.maxRel) + ", mean " + pct(d.meanRel),
                                        full.final, run.final, heat, float(0.4 / kFurnaceExact)});
                    } else {
                        grid.push_back({cfg.name, "reference indirect", cfg.name + " indirect, " + num(run.frameMs, 1) + " ms",
                                        "|block error| / mean: relL1 " + num(row.indRelL1) + ", ratio " + num(row.indRatio),
                                        refInd, ind, blockErrorMap(ind, refInd, refMean), dispScale});
                        const double ref1Mean = meanLuminance(refInd1);
                        grid.push_back({cfg.name, "1-bounce reference indirect", cfg.name + " one bounce (bounce_damping=1)",
                                        "relL1 " + num(row.oneRelL1) + ", ratio " + num(row.oneRatio), refInd1, ind1,
                                        blockErrorMap(ind1, refInd1, ref1Mean), dispScale});
                    }
                }
                if (scale == 1.0) finalAtScale1[cfg.name] = run.final;
                else if (finalAtScale1.count(cfg.name)) {
                    row.vsScale1 = relativeL1(run.final, finalAtScale1[cfg.name]);
                    // Both black (no light at scale 1): the same image when this one is black too.
                    if (std::isnan(row.vsScale1)) row.vsScale1 = leak(run.final).max == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
                }
                if (!run.pathFinals.empty()) {
                    double l1 = 0, ratio = 0;
                    for (size_t k = 0; k < run.pathFinals.size(); ++k) {
                        const FloatImage pi = subtract(run.pathFinals[k], run.pathDirects[k]);
                        const FloatImage pr = subtract(pathRefs[k].final, run.pathDirects[k]);
                        l1 += relativeL1(pi, pr);
                        ratio += ratioOfMeans(pi, pr);
                    }
                    row.pathIndRelL1 = l1 / double(run.pathFinals.size());
                    row.pathIndRatio = ratio / double(run.pathFinals.size());
                }
                viewRows.push_back(row);
                result.rows.push_back(row);
            }
            const std::string gridName = "grid_" + view.scene + "_" + view.camera + (scale == 1.0 ? "" : "_s" + scaleName(scale)) + ".png";
            writeGrid(label + " at scale " + scaleName(scale) + " (" + std::to_string(o.width) + "x" + std::to_string(o.height) + ", " +
                          std::to_string(o.frames) + " frames)",
                      grid, o.width, o.height, (fs::path(o.outDir) / gridName).string());
        }

        // ---- the table of this view ----
        text << "\n### " << label << "\n\n" << refInfo << "\n\n";
        if (view.kind == ViewKind::Dark) {
            text << "Leak: luminance of deepgi's final image where the truth is exactly 0 (the whole view), absolute and as a "
                    "fraction of the lit side's indirect level (mean luminance of the reference indirect seen by thin_wall/lit: "
                 << num(litLevel.count(view.scene) ? litLevel[view.scene] : kNaN, 5) << ").\n\n";
            text << "| config | scale | ms | leak mean | leak max | mean / lit level | max / lit level | vs scale 1 |\n|---|---|---|---|---|---|---|---|\n";
            for (const HardRow& r : viewRows)
                text << "| " << r.config << " | " << scaleName(r.scale) << " | " << num(r.frameMs, 1) << " | " << num(r.leakMean, 5) << " | "
                     << num(r.leakMax, 5) << " | " << pct(r.leakMeanRel) << " | " << pct(r.leakMaxRel) << " | " << num(r.vsScale1) << " |\n";
        } else if (view.kind == ViewKind::Furnace) {
            text << "| config | scale | ms | max dev | mean dev | final ratio | ind relL1 | ind ratio | 1b relL1 | 1b ratio | vs scale 1 |\n"
                    "|---|---|---|---|---|---|---|---|---|---|---|\n";
            for (const HardRow& r : viewRows)
                text << "| " << r.config << " | " << scaleName(r.scale) << " | " << num(r.frameMs, 1) << " | " << pct(r.furnaceMaxDev) << " | "
                     << pct(r.furnaceMeanDev) << " | " << num(r.furnaceRatio) << " | " << num(r.indRelL1) << " | " << num(r.indRatio)
                     << " | " << num(r.oneRelL1) << " | " << num(r.oneRatio) << " | " << num(r.vsScale1) << " |\n";
        } else {
            text << "| config | scale | ms | ind relL1 | ind ratio | 1b relL1 | 1b ratio | final relL1 | vs scale 1 | path ind relL1 | path ind ratio |\n"
                    "|---|---|---|---|---|---|---|---|---|---|---|\n";
            for (const HardRow& r : viewRows)
                text << "| " << r.config << " | " << scaleName(r.scale) << " | " << num(r.frameMs, 1) << " | " << num(r.indRelL1) << " | "
                     << num(r.indRatio) << " | " << num(r.oneRelL1) << " | " << num(r.oneRatio) << " | " << num(r.finalRelL1) << " | "
                     << num(r.vsScale1) << " | " << num(r.pathIndRelL1) << " | " << num(r.pathIndRatio) << " |\n";
        }
    }
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - tStart).count();
    std::ostringstream head;
    head << "# deepgi bench --suite hard\n\n" << o.width << "x" << o.height << ", " << o.frames << " frames per run (" << o.oneBounceFrames
         << " for one bounce; frame time: median of the last "
         << o.timedFrames << ", wall clock), figures of ../shared/docs/gi-accuracy.md: indirect = final - direct (the same "
         << "configuration with radiosity.enabled=false) against reference final - deepgi direct; relL1 over 4x4 block means of "
         << "luminance; 1b = radiosity.bounce_damping=1 against a 1-bounce reference; scaled scenes use the scale-1 reference "
         << "(the true image does not depend on the scale) and 'vs scale 1' is the relative L1 of the final image against scale 1. "
         << "Suite time " << num(total, 0) << " s.\n";
    result.text = head.str() + text.str();
    {
        std::ofstream f(fs::path(o.outDir) / "results_hard.md");
        f << result.text << "\n## References\n\n";
        for (const auto& l : result.referenceLines) f << "- " << l << "\n";
    }
    {
        std::ofstream f(fs::path(o.outDir) / "results_hard.csv");
        f << "scene,camera,config,scale,frame_ms,ind_rel_l1,ind_ratio,one_rel_l1,one_ratio,final_rel_l1,leak_mean,leak_max,"
             "leak_mean_rel,leak_max_rel,furnace_max_dev,furnace_mean_dev,furnace_ratio,vs_scale1,path_ind_rel_l1,path_ind_ratio\n";
        auto c = [](double v) { return std::isnan(v) ? std::string() : num(v, 6); };
        for (const HardRow& r : result.rows)
            f << r.scene << "," << r.camera << "," << r.config << "," << scaleName(r.scale) << "," << c(r.frameMs) << "," << c(r.indRelL1)
              << "," << c(r.indRatio) << "," << c(r.oneRelL1) << "," << c(r.oneRatio) << "," << c(r.finalRelL1) << "," << c(r.leakMean)
              << "," << c(r.leakMax) << "," << c(r.leakMeanRel) << "," << c(r.leakMaxRel) << "," << c(r.furnaceMaxDev) << ","
              << c(r.furnaceMeanDev) << "," << c(r.furnaceRatio) << "," << c(r.vsScale1) << "," << c(r.pathIndRelL1) << ","
              << c(r.pathIndRatio) << "\n";
    }
    return result;
}

}  // namespace deepgi::bench
