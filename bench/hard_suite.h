#pragma once
// `deepgi bench --suite hard`: the hard GI scenes of assets/hard/ (tools/gen_scenes.py) against path-traced
// references (cached), with the figures of ../shared/docs/gi-accuracy.md: indirect relative L1 (4x4 blocks) and
// ratio of means, the same for one bounce against a 1-bounce reference, the thin wall's leak, the furnace's
// deviation from its exact value, the image at scales 0.001 and 1000 against scale 1, a camera path, frame time.
#include "bench/bench.h"
#include "bench/reference_cache.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"

#include <string>
#include <vector>

namespace deepgi::bench {

// The suite's scenes (base names, in its order), comma-separated: for --help and error messages.
std::string hardSceneList();

struct HardOptions {
    std::vector<std::string> scenes;             // base names (offscreen_light, ...); empty = all
    std::vector<double> scales = {1.0, 0.001, 1000.0};
    std::vector<std::string> configs;            // names from defaultConfigs(); empty = {"default"}
    int width = 320, height = 180;
    int frames = 200;       // frames of the full run (still camera): the multi-bounce feedback converges slowly
                            // (sun_patch: indirect ratio 1.48 after 60 frames, 1.65 after 200)
    int oneBounceFrames = 60;  // one bounce has no feedback: temporal alpha 0.92 leaves 0.92^60 < 1 % of the start
    int timedFrames = 20;   // the last ones: frame time median
    int spp = 1024, bounces = 128;   // full references: 4 chunks of spp/4 with seeds 1..4 (noise floor)
    int oneBounceSpp = 4096;         // 1-bounce references (bounces = 1): noise floor 2.3-4.2 % (1024: 4.6-8.4 %)
    int pathSpp = 256;               // references along the camera path
    bool cameraPath = true;
    std::string assetDir;   // "" = the source tree's assets/
    std::string outDir = "out/bench_hard";
    std::string cacheDir;   // "" = outDir/cache
    std::string shaderDir;  // "" = the source tree's shaders/
    std::string context = "osmesa";
    Settings base;          // every configuration starts from these
    std::vector<std::string> userAssignments;  // --set: they win over a configuration's preset
    bool quiet = false;
};

// One view of one scene at one scale under one configuration. NaN = not applicable.
struct HardRow {
    std::string scene, camera, config;  // scene = base name, e.g. "thin_wall"
    double scale = 1.0;
    double frameMs = 0;
    double indRelL1, indRatio, oneRelL1, oneRatio, finalRelL1;
    double leakMean, leakMax, leakMeanRel, leakMaxRel;  // thin wall (dark): absolute, and / the lit side's level
    double furnaceMaxDev, furnaceMeanDev, furnaceRatio;  // furnace: final image against 0.2, per pixel
    double vsScale1;                     // relative L1 of the final image against the same view at scale 1
    double pathIndRelL1, pathIndRatio;   // camera path: mean over its reference frames
};

struct HardResult {
    std::vector<HardRow> rows;
    std::vector<std::string> referenceLines;  // per reference: spp, bounces, floor, time, cache file
    std::string text;                         // the tables printed
};

// The view list: scene base name and camera.
std::vector<std::pair<std::string, std::string>> hardViews();

HardResult runHardSuite(const HardOptions& options);

}  // namespace deepgi::bench
