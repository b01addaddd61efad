// deepgi render: headless (OSMesa) frames of a glTF scene to PNG/EXR, buffers, timings and settings.
#include "app/command.h"
#include "app/options.h"
#include "app/render_job.h"

#include <cstdio>

namespace deepgi {
namespace {

CommandRegistrar registrar("render", "Render a glTF scene headless (OSMesa) to a folder", 10, [](CLI::App& sub) {
    auto job = std::make_shared<RenderJob>();
    auto size = std::make_shared<std::string>("640x360");
    auto settings = std::make_shared<SettingsOptions>();
    sub.add_option("scene", job->scenePath, "glTF/glb or OBJ file (default: the atrium in assets/)");
    sub.add_option("--size", *size, "Image size WxH")->capture_default_str();
    sub.add_option("--frames", job->frames, "Frames to render (temporal passes converge over them)")->capture_default_str()->check(CLI::Range(1, 100000));
    sub.add_option("--warmup", job->warmupFrames, "Frames rendered before the --frames that are timed (e.g. until the probes "
                                                  "settle: timings.json says whether they had)")->capture_default_str()->check(CLI::Range(0, 1000000));
    sub.add_option("--camera", job->camera, "glTF camera name (default: the scene's first, else a framing camera)");
    sub.add_option("--camera-file", job->cameraFile, "Camera from a JSON file (a viewer capture's camera.json); wins over --camera");
    sub.add_option("--buffers", job->buffers, "Buffers to dump as EXR: all, or comma-separated layer names (see `deepgi buffers`)");
    sub.add_option("--environment", job->environment, "Equirectangular environment map (EXR, HDR, ... via OpenImageIO; +Y up, u = 0.5 along +X): seen as the backdrop, lights the scene (environment.*)");
    sub.add_option("--out", job->outDir, "Output folder")->capture_default_str();
    sub.add_option("--shaders", job->shaderDir, "Shader folder (default: the source tree's shaders/)");
    sub.add_option("--context", job->context, "OpenGL context: osmesa (llvmpipe) or egl (headless EGL: Mesa surfaceless or a GPU)")->capture_default_str();
    sub.add_option("--time", job->time, "Seconds of the scene's glTF animations to render (the scene at that instant)")
        ->check(CLI::Range(0.0, 1e7));
    sub.add_option("--animate", job->animateFps, "Frames per second of animation time: each frame advances the clock by 1/FPS "
                                                 "(--frames N then spans N/FPS seconds from --time)")->check(CLI::Range(0.0, 1e4));
    sub.add_flag("--sequence", job->sequence, "Also write every frame as frame_NNNNN.png");
    settings->add(sub);
    return [job, size, settings, &sub]() {
        job->timeSet = sub.count("--time") > 0;
        parseSize(*size, job->width, job->height);
        job->settings = settings->build();
        if (job->scenePath.empty()) job->scenePath = defaultScenePath();
        RenderJobResult r = runRenderJob(*job);
        char warmup[48] = "";
        if (job->warmupFrames > 0) std::snprintf(warmup, sizeof warmup, " after %d warm-up frames", job->warmupFrames);
        std::printf("deepgi: rendered %s (%dx%d, %d frames%s, %zu triangles) on %s\n", job->scenePath.c_str(), job->width,
                    job->height, job->frames, warmup, r.triangles, r.glRenderer.c_str());
        char gpu[64] = "";
        if (r.gpuTimed) std::snprintf(gpu, sizeof gpu, " wall (passes %.2f ms on the GPU)", r.medianGpuPassesMs);
        const char* probes = !r.hasProbes ? "" : r.probesSettled ? " (probes settled)" : " (probes still updating)";
        std::printf("deepgi: median frame %.1f ms%s%s; wrote %s/final.png, final.exr, timings.json, settings.json%s\n",
                    r.medianFrameMs, gpu, probes, job->outDir.c_str(), r.buffersWritten ? " and buffers" : "");
        for (const auto& w : r.warnings) std::fprintf(stderr, "deepgi: warning: %s\n", w.c_str());
        return 0;
    };
});

}  // namespace
}  // namespace deepgi
