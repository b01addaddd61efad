#pragma once
// The headless render job behind `deepgi render` (also used by tests through the binary).
#include "renderer/core/settings.h"

#include <string>
#include <vector>

namespace deepgi {

struct RenderJob {
    std::string scenePath;
    std::string camera;
    std::string cameraFile;  // --camera-file: a capture's camera.json (wins over camera)
    int width = 640, height = 360;
    int frames = 16;
    int warmupFrames = 0;  // --warmup: frames rendered before the timed ones (they converge, nothing is timed)
    std::string buffers;  // "", "all" or comma-separated layer names
    std::string outDir = "out/render";
    std::string shaderDir;  // "" = the source tree's shaders/
    std::string environment;  // --environment: an equirectangular map ("" = none)
    std::string context = "osmesa";  // or "egl" (renderer/gl/offscreen_context.h)
    double time = 0.0;        // --time: the glTF animations' clock (seconds) of the first frame
    bool timeSet = false;     // --time given
    double animateFps = 0.0;  // --animate: > 0 advances the clock by 1/fps each frame
    bool sequence = false;    // --sequence: every frame as frame_NNNNN.png
    Settings settings;
};

struct RenderJobResult {
    double medianFrameMs = 0.0;  // software GL: the passes' sum (glFinish around each); a GPU: wall clock per frame
    double medianGpuPassesMs = 0.0;  // a GPU: the passes' GL_TIME_ELAPSED sum (0 on software GL)
    bool gpuTimed = false;
    bool probesSettled = false;  // after the last frame: the probes' updates have stopped (probes.settle_updates)
    bool hasProbes = false;
    size_t triangles = 0;
    bool buffersWritten = false;
    std::string glRenderer;
    std::vector<std::string> warnings;
};

RenderJobResult runRenderJob(const RenderJob& job);

}  // namespace deepgi
