#pragma once
// `deepgi bench`: speed against error. Renders a path-traced reference per view (cached), sweeps renderer
// configurations, and measures per-pass time, memory, error against the reference (final image and indirect part),
// temporal stability and the error along a short camera path. Writes results.csv, results.md, plots and grids.
#include "bench/reference_cache.h"
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/scene/scene.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace deepgi {
class Renderer;
}

namespace deepgi::bench {

struct BenchConfig {
    std::string name;
    std::string preset;                    // applied first ("" = none)
    std::vector<std::string> assignments;  // key=value, applied after the preset
    std::string description;
};
// The default sweep (see docs/BENCHMARKS.md).
std::vector<BenchConfig> defaultConfigs();
// base <- the configuration's preset <- the user's --set <- the configuration's assignments.
Settings configSettings(const Settings& base, const BenchConfig& c, const std::vector<std::string>& user = {});
// The renderer's final radiance as linear RGB.
FloatImage finalRgb(const Renderer& r);

struct BenchView {
    std::string scenePath, camera;
    std::string cameraFile;  // a camera.json (e.g. a viewer capture); wins over camera
    std::vector<std::string> assignments;  // key=value settings of this view over BenchOptions::base (an OBJ's sun)
};

struct BenchOptions {
    std::vector<BenchView> views;
    int width = 320, height = 180;
    int frames = 24;        // per configuration, still camera
    int timedFrames = 12;   // the last ones: timing medians and stability
    int spp = 256, bounces = 16;
    int pathFrames = 8;     // frames of the sideways dolly after the still frames
    int pathSpp = 64;       // references at the path cameras (mid and end)
    float pathStep = 0.01f; // dolly per frame, as a fraction of the scene's bounding radius
    std::vector<std::string> configs;  // names to run ("" = all)
    std::string outDir = "out/bench";
    std::string cacheDir;   // "" = outDir/cache
    std::string environment;  // --environment: an equirectangular map for every view ("" = none)
    std::string shaderDir;  // "" = the source tree's
    Settings base;          // every configuration starts from these
    std::vector<std::string> userAssignments;  // --set: they win over a configuration's preset
    int wholeFrameWidth = 640, wholeFrameHeight = 360;  // 0 = skip the whole-frame check
    int wholeFrameFrames = 24;
    bool cpuTiming = false;  // per-pass CPU time of this thread with LP_NUM_THREADS=0 (robust on a shared machine)
    std::string context = "osmesa";  // or "egl" (gl/offscreen_context.h)
    bool quiet = false;
};

struct BenchRow {
    std::string scene, camera, config, sameAs, settingsText;
    std::map<std::string, double> passMs;  // median per pass
    double totalMs = 0.0;
    uint64_t memoryBytes = 0;
    int geometryPasses = 0;
    double relMse = 0, meanRelErr = 0, ssim = 0, indRelMse = 0, indMeanRelErr = 0, stability = 0, pathMeanRelErr = 0;
};

struct BenchResult {
    std::vector<BenchRow> rows;
    std::vector<std::string> passNames;  // pipeline order
    std::vector<std::string> ratioLines; // the paper's claims, as measured
    double wholeFrameMs = 0.0;
    std::string glRenderer;
    bool gpuTimed = false;  // passes timed by GL_TIME_ELAPSED queries (a GPU)
};

// Runs the whole bench and writes its files. Needs no current context (creates one).
BenchResult runBench(const BenchOptions& options);

// The CSV header (also checked by the tests).
std::vector<std::string> csvColumns(const std::vector<std::string>& passNames);

}  // namespace deepgi::bench
