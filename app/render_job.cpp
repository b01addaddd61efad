#include "app/render_job.h"
#include "app/options.h"

#include "renderer/scene/animation.h"

#include "renderer/core/image_io.h"
#include "renderer/core/util.h"
#include "renderer/gl/gl.h"
#include "renderer/gl/offscreen_context.h"
#include "renderer/probes/probe_volume.h"
#include "renderer/renderer.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene_loader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace deepgi {

static std::string fileNameFor(const std::string& layer) {
    std::string s;
    for (char c : layer) s += (c == ' ') ? '_' : char(std::tolower((unsigned char)c));
    return s;
}

RenderJobResult runRenderJob(const RenderJob& job) {
    RenderJobResult result;
    auto scene = std::make_shared<Scene>(loadScene(job.scenePath, withLoadProgress(gltfLoadOptions(job.settings), job.scenePath)));
    attachEnvironment(*scene, job.environment);
    result.warnings = scene->warnings;
    result.triangles = scene->triangleCount();
    Camera camera = selectCamera(*scene, job.camera, job.cameraFile);

    gl::OffscreenContext context(job.context);
    result.glRenderer = context.renderer();
    RendererOptions options;
    if (!job.shaderDir.empty()) options.shaderDir = job.shaderDir;
    // A GPU runs the passes asynchronously: a glFinish around each would time the driver's round trips, so the
    // passes are timed by timer queries and the frame by the wall clock to its glFinish (probe rays are CPU work).
    result.gpuTimed = !context.isSoftware();
    if (result.gpuTimed) options.timing = TimingMode::GpuQueries;
    Renderer renderer(options);
    renderer.setScene(scene);
    renderer.resize(job.width, job.height);
    renderer.setCamera(camera);

    std::map<std::string, std::vector<double>> perPass;
    std::vector<std::string> passOrder;
    std::vector<double> frameMs, gpuPassesMs, probeCpuMs, probeSpanMs;
    const bool animate = job.animateFps > 0.0;
    if ((job.timeSet || animate) && scene->animations.empty())
        result.warnings.push_back(job.scenePath + ": --time/--animate given, but the scene has no animations");
    if (job.timeSet && !animate) {  // the scene at that instant, every frame
        applyAnimation(*scene, float(job.time));
        renderer.sceneChanged(SceneChange::Transforms | SceneChange::Lights);
        if (job.cameraFile.empty() && !scene->cameras.empty()) renderer.setCamera(selectCamera(*scene, job.camera));
    }
    std::filesystem::create_directories(job.outDir);
    // Warm-up frames are ordinary frames (the same image as rendering them timed) whose times are not kept: the
    // figures of a converged or settled frame, e.g. after the probes' updates have stopped.
    const int totalFrames = job.warmupFrames + job.frames;
    for (int f = 0; f < totalFrames; ++f) {
        if (animate) {
            applyAnimation(*scene, float(job.time + double(f) / job.animateFps));
            renderer.sceneChanged(SceneChange::Transforms);
            if (job.cameraFile.empty() && !scene->cameras.empty()) renderer.setCamera(selectCamera(*scene, job.camera));  // an animated camera node
        }
        const ProbeVolume* volume = renderer.probeVolume();
        const uint64_t probeUpdatesBefore = volume ? volume->updateCount() : 0;
        const auto start = std::chrono::steady_clock::now();
        renderer.render(job.settings);
        if (result.gpuTimed) glFinish();
        const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (job.sequence) {
            char name[32];
            std::snprintf(name, sizeof(name), "/frame_%05d.png", f);
            writePng8(job.outDir + name, job.width, job.height, 4, renderer.readDisplay());
        }
        if (f < job.warmupFrames) continue;
        // The probe update's own figures: with probes.overlap its rays are traced beside the G-buffer, so its pass
        // time shows only what was left; these say what the rays cost (frames that updated the probes only).
        volume = renderer.probeVolume();
        if (volume && volume->updateCount() != probeUpdatesBefore && volume->lastUpdate().probesUpdated > 0) {
            probeCpuMs.push_back(volume->lastUpdate().cpuMilliseconds);
            probeSpanMs.push_back(volume->lastUpdate().milliseconds);
        }
        double total = 0.0;
        for (const auto& t : renderer.timings()) {
            if (!perPass.count(t.name)) passOrder.push_back(t.name);
            perPass[t.name].push_back(t.ms);
            total += t.ms;
        }
        if (!result.gpuTimed) frameMs.push_back(total);
        else {
            frameMs.push_back(wallMs);
            if (!renderer.timings().empty()) gpuPassesMs.push_back(total);  // the queries report two frames late
        }
    }
    result.medianFrameMs = median(frameMs);
    if (const ProbeVolume* probes = renderer.probeVolume()) {
        result.hasProbes = true;
        result.probesSettled = probes->settled(job.settings);
    }
    if (!gpuPassesMs.empty()) result.medianGpuPassesMs = median(gpuPassesMs);

    const std::string out = job.outDir + "/";
    writePng8(out + "final.png", job.width, job.height, 4, renderer.readDisplay());
    FloatImage final = renderer.readFinalRadiance();
    FloatImage rgb{final.width, final.height, 3, {}};
    rgb.pixels.reserve(size_t(final.width) * final.height * 3);
    for (size_t i = 0; i < size_t(final.width) * final.height; ++i)
        for (int c = 0; c < 3; ++c) rgb.pixels.push_back(final.pixels[i * final.channels + c]);
    writeExr(out + "final.exr", rgb);

    if (!job.buffers.empty()) {
        std::vector<std::string> names;
        if (job.buffers == "all") names = renderer.textures().layerNames();
        else {
            std::stringstream ss(job.buffers);
            std::string item;
            while (std::getline(ss, item, ',')) if (!item.empty()) names.push_back(item);
        }
        for (const auto& n : names) writeExr(out + fileNameFor(n) + ".exr", renderer.readLayer(n));
        result.buffersWritten = !names.empty();
    }

    nlohmann::json timings;
    timings["unit"] = "ms";
    timings["method"] = result.gpuTimed ? "passes: GL_TIME_ELAPSED queries; frame: wall clock from render() to glFinish"
                                        : "wall clock around glFinish per pass (llvmpipe timer queries miss vertex work)";
    timings["frames"] = job.frames;
    timings["warmup_frames"] = job.warmupFrames;
    timings["frames_ms"] = frameMs;  // each timed frame, in order (the medians hide a transient such as the probes')
    if (result.hasProbes) {
        timings["probes_settled"] = result.probesSettled;
        // Medians over the timed frames that updated the probes (0 when none did): CPU time of the threads that
        // traced them, and wall time from the update's start to its commit (beside the draws with probes.overlap).
        timings["probe_update_frames"] = probeCpuMs.size();
        timings["probe_update_cpu_ms"] = probeCpuMs.empty() ? 0.0 : median(probeCpuMs);
        timings["probe_update_span_ms"] = probeSpanMs.empty() ? 0.0 : median(probeSpanMs);
    }
    timings["gl_renderer"] = result.glRenderer;
    timings["size"] = {job.width, job.height};
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& n : passOrder) passes.push_back({{"pass", n}, {"median_ms", median(perPass[n])}});
    timings["passes"] = passes;
    timings["frame_median_ms"] = result.medianFrameMs;
    if (result.gpuTimed) timings["gpu_passes_median_ms"] = result.medianGpuPassesMs;
    timings["geometry_passes"] = renderer.lastGeometryPasses();
    std::ofstream(out + "timings.json") << timings.dump(2) << "\n";
    nlohmann::json settings = settingsToJson(job.settings);
    std::ofstream(out + "settings.json") << settings.dump(2) << "\n";
    return result;
}

}  // namespace deepgi
