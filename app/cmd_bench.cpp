// deepgi bench: speed against error over a sweep of configurations, against path-traced references.
#include "app/command.h"
#include "app/options.h"
#include "bench/bench.h"
#include "bench/hard_suite.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

namespace deepgi {
namespace {

struct BenchArgs {
    std::vector<std::string> scenes, cameras, cameraFiles;
    std::string size = "320x180";
    std::string wholeSize = "640x360";
    std::string configs;
    bool list = false;
    std::string suite = "standard";
    std::string hardScenes, scales = "1,0.001,1000";
    int oneBounceSpp = bench::HardOptions{}.oneBounceSpp, oneBounceFrames = bench::HardOptions{}.oneBounceFrames;
    bool noPath = false;
    SettingsOptions settings;
    bench::BenchOptions o;
};

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

int runHard(BenchArgs& a, const CLI::App& sub) {
    bench::HardOptions h;
    parseSize(a.size, h.width, h.height);
    h.scenes = splitList(a.hardScenes);
    h.scales.clear();
    for (const auto& s : splitList(a.scales)) {
        size_t used = 0;
        double v = 0.0;
        try {
            v = std::stod(s, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != s.size() || !(v == 1.0 || v == 0.001 || v == 1000.0))
            throw std::runtime_error("bench: --scales takes 1, 0.001 and 1000 (the generated scenes), got '" + s + "'");
        h.scales.push_back(v);
    }
    if (h.scales.empty() || h.scales.front() != 1.0) h.scales.insert(h.scales.begin(), 1.0);  // the scale-1 run is the comparison
    h.configs = splitList(a.configs);
    if (sub.count("--frames")) h.frames = a.o.frames;
    if (sub.count("--timed-frames")) h.timedFrames = a.o.timedFrames;
    h.timedFrames = std::min(h.timedFrames, h.frames);
    if (sub.count("--spp")) h.spp = a.o.spp;
    if (sub.count("--bounces")) h.bounces = a.o.bounces;
    if (sub.count("--path-spp")) h.pathSpp = a.o.pathSpp;
    h.oneBounceSpp = a.oneBounceSpp;
    h.oneBounceFrames = a.oneBounceFrames;
    h.cameraPath = !a.noPath;
    h.outDir = sub.count("--out") ? a.o.outDir : "out/bench_hard";
    h.cacheDir = a.o.cacheDir;
    h.shaderDir = a.o.shaderDir;
    h.context = a.o.context;
    h.base = a.settings.build();
    h.userAssignments = a.settings.assignments;
    h.quiet = a.o.quiet;
    const bench::HardResult r = bench::runHardSuite(h);
    std::printf("%s\n", r.text.c_str());
    std::printf("references:\n");
    for (const auto& l : r.referenceLines) std::printf("  %s\n", l.c_str());
    std::printf("wrote %s/results_hard.md, results_hard.csv, grid_*.png\n", h.outDir.c_str());
    return 0;
}

CommandRegistrar registrar("bench", "Speed against error: sweep configurations against path-traced references", 35, [](CLI::App& sub) {
    auto a = std::make_shared<BenchArgs>();
    sub.add_option("--scene", a->scenes, "glTF/glb or OBJ scene (repeatable; default: the atrium, the Cornell box and, when ../shared/scenes has them, Crytek Sponza and the OBJ Cornell box)");
    sub.add_option("--camera", a->cameras, "Camera of each --scene, in order (default: courtyard and front; '' = the scene's first)");
    sub.add_option("--camera-file", a->cameraFiles, "Camera JSON of each --scene, in order (a viewer capture's camera.json); wins over --camera");
    sub.add_option("--size", a->size, "Image size WxH")->capture_default_str();
    sub.add_option("--frames", a->o.frames, "Frames per configuration (still camera; --suite hard: 200)")->capture_default_str()->check(CLI::Range(2, 10000));
    sub.add_option("--timed-frames", a->o.timedFrames, "The last frames: timing medians and stability (--suite hard: 20)")->capture_default_str()->check(CLI::Range(1, 10000));
    sub.add_option("--spp", a->o.spp, "Reference samples per pixel (--suite hard: 1024)")->capture_default_str()->check(CLI::Range(1, 1 << 20));
    sub.add_option("--bounces", a->o.bounces, "Reference bounces (--suite hard: 128)")->capture_default_str()->check(CLI::Range(0, 1000));
    sub.add_option("--path-frames", a->o.pathFrames, "Frames of the sideways camera path (0 = none)")->capture_default_str()->check(CLI::Range(0, 1000));
    sub.add_option("--path-spp", a->o.pathSpp, "Samples per pixel of the path references (--suite hard: 256)")->capture_default_str()->check(CLI::Range(1, 1 << 20));
    sub.add_option("--configs", a->configs, "Comma-separated configurations to run (default: all; see --list)");
    sub.add_flag("--list", a->list, "List the configurations and exit");
    sub.add_option("--suite", a->suite, "standard (atrium and Cornell box sweep) or hard (the hard GI scenes of assets/hard: "
                                        "indirect, one-bounce, leak, furnace, scale figures; default configs: default)")
        ->capture_default_str()->check(CLI::IsMember({"standard", "hard"}));
    sub.add_option("--hard-scenes", a->hardScenes, "--suite hard: comma-separated scenes (" + bench::hardSceneList() + "; default all)");
    sub.add_option("--scales", a->scales, "--suite hard: comma-separated scales among 1, 0.001, 1000")->capture_default_str();
    sub.add_option("--one-bounce-spp", a->oneBounceSpp, "--suite hard: samples per pixel of the 1-bounce references")->capture_default_str()->check(CLI::Range(4, 1 << 20));
    sub.add_option("--one-bounce-frames", a->oneBounceFrames, "--suite hard: frames of the one-bounce runs (no feedback to converge)")->capture_default_str()->check(CLI::Range(1, 10000));
    sub.add_flag("--no-path", a->noPath, "--suite hard: skip the camera path");
    sub.add_option("--whole-frame-size", a->wholeSize, "Size of the whole-frame check of the first scene, balanced preset (0x0 = skip)")->capture_default_str();
    sub.add_option("--out", a->o.outDir, "Output folder (--suite hard: out/bench_hard)")->capture_default_str();
    sub.add_option("--environment", a->o.environment, "Equirectangular environment map for every scene (EXR, HDR, ... via OpenImageIO): seen and lighting, in the renderer and the references");
    sub.add_option("--cache", a->o.cacheDir, "Reference cache folder (default: OUT/cache)");
    sub.add_option("--shaders", a->o.shaderDir, "Shader folder (default: the source tree's shaders/)");
    sub.add_flag("--quiet", a->o.quiet, "No progress output");
    sub.add_flag("--cpu-time", a->o.cpuTiming, "Time passes by this thread's CPU time with llvmpipe on one thread (LP_NUM_THREADS=0): robust when other processes share the cores");
    sub.add_option("--context", a->o.context, "OpenGL context: osmesa (llvmpipe) or egl (headless EGL: Mesa surfaceless or a GPU)")->capture_default_str();
    a->settings.add(sub);
    return [a, &sub]() {
        if (a->suite == "hard") {
            if (!a->o.environment.empty())
                throw std::runtime_error("bench: --environment applies to the standard suite (the hard scenes have their own lights)");
            return runHard(*a, sub);
        }
        if (a->list) {
            for (const auto& c : bench::defaultConfigs()) std::printf("%-20s %s\n", c.name.c_str(), c.description.c_str());
            return 0;
        }
        bench::BenchOptions& o = a->o;
        parseSize(a->size, o.width, o.height);
        parseSize(a->wholeSize, o.wholeFrameWidth, o.wholeFrameHeight, true, "--whole-frame-size");
        o.base = a->settings.build();
        o.userAssignments = a->settings.assignments;
        if (a->scenes.empty()) {
            o.views = {{std::string(DEEPGI_ASSET_DIR) + "/atrium/atrium.gltf", a->cameras.size() > 0 ? a->cameras[0] : "courtyard", "", {}},
                       {std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf", a->cameras.size() > 1 ? a->cameras[1] : "front", "", {}}};
            // The real OBJ scenes beside the checkout (../shared/scenes), when present: Crytek Sponza looking down the
            // atrium with the sun along it (the default sun leaves its floor in shadow), and the original Cornell box
            // under the default sun shining in through its open front and its emissive ceiling light (lit by the
            // small emitter alone, the 256-spp reference's relative standard error is 0.56 instead of 0.29).
            const std::string shared = DEEPGI_SHARED_SCENES;
            const std::string views = std::string(DEEPGI_ASSET_DIR) + "/views/";
            if (std::filesystem::exists(shared + "/CrytekSponza/sponza.obj"))
                o.views.push_back({shared + "/CrytekSponza/sponza.obj", "", views + "crytek_sponza_atrium.json",
                                   {"light.sun_azimuth=90", "light.sun_elevation=70"}});
            if (std::filesystem::exists(shared + "/CornellBox/CornellBox-Original.obj"))
                o.views.push_back({shared + "/CornellBox/CornellBox-Original.obj", "", views + "cornell_box_obj_front.json", {}});
        } else {
            if (a->cameras.size() > a->scenes.size()) throw std::runtime_error("bench: more --camera than --scene options");
            for (size_t i = 0; i < a->scenes.size(); ++i) o.views.push_back({a->scenes[i], i < a->cameras.size() ? a->cameras[i] : "", "", {}});
        }
        if (a->cameraFiles.size() > o.views.size()) throw std::runtime_error("bench: more --camera-file than views");
        for (size_t i = 0; i < a->cameraFiles.size(); ++i) o.views[i].cameraFile = a->cameraFiles[i];
        std::stringstream ss(a->configs);
        std::string item;
        while (std::getline(ss, item, ','))
            if (!item.empty()) o.configs.push_back(item);
        o.timedFrames = std::min(o.timedFrames, o.frames);
        const bench::BenchResult r = bench::runBench(o);
        std::printf("deepgi bench on %s: %zu rows -> %s/results.csv, results.md, speed_error.png, grid_*.png\n",
                    r.glRenderer.c_str(), r.rows.size(), o.outDir.c_str());
        for (const auto& l : r.ratioLines) std::printf("  %s\n", l.c_str());
        return 0;
    };
});

}  // namespace
}  // namespace deepgi
