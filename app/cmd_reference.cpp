// deepgi reference: the ground-truth image of a scene from the Embree path tracer.
#include "app/command.h"
#include "app/options.h"
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene_loader.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace deepgi {
namespace {

struct ReferenceArgs {
    std::string scene = std::string(DEEPGI_ASSET_DIR) + "/atrium/atrium.gltf";
    std::string camera;
    std::string cameraFile;
    std::string size = "320x180";
    int spp = 256;
    int bounces = 16;
    uint64_t seed = 1;
    int threads = 0;
    std::vector<std::string> assignments;
    std::string preset;
    std::string out = "out/reference";
    std::string environment;
    bool quiet = false;
};

int runReference(const ReferenceArgs& a) {
    ReferenceOptions opt;
    parseSize(a.size, opt.width, opt.height);
    if (a.spp < 1) throw std::runtime_error("--spp must be at least 1, got " + std::to_string(a.spp));
    if (a.bounces < 0) throw std::runtime_error("--bounces must be 0 or more, got " + std::to_string(a.bounces));
    if (a.threads < 0) throw std::runtime_error("--threads must be 0 (all cores) or more, got " + std::to_string(a.threads));
    opt.spp = a.spp;
    opt.maxBounces = a.bounces;
    opt.seed = a.seed;
    opt.threads = a.threads;
    opt.progress = !a.quiet;

    Settings settings;
    if (!a.preset.empty()) applyPreset(settings, a.preset);
    for (const std::string& kv : a.assignments) applyAssignment(settings, kv);

    Scene scene = loadScene(a.scene, withLoadProgress(gltfLoadOptions(settings), a.scene));
    if (!scene.bounds.valid()) scene.computeBounds();
    attachEnvironment(scene, a.environment);
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "deepgi: warning: %s\n", w.c_str());
    const Camera camera = selectCamera(scene, a.camera, a.cameraFile);

    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(a.out, ec);
    if (ec) throw std::runtime_error("cannot create output directory '" + a.out + "': " + ec.message());

    const int threads = a.threads > 0 ? a.threads : int(std::thread::hardware_concurrency());
    if (!a.quiet)
        std::fprintf(stderr, "reference: %s, %zu triangles, %dx%d, %d spp, %d bounces, seed %llu, %d threads\n",
                     a.scene.c_str(), scene.triangleCount(), opt.width, opt.height, opt.spp, opt.maxBounces,
                     (unsigned long long)opt.seed, threads);
    ReferenceTracer tracer(scene);
    const ReferenceResult r = tracer.render(camera, settings, opt);

    const fs::path dir(a.out);
    writeExr((dir / "final.exr").string(), r.final);
    writeExr((dir / "direct.exr").string(), r.direct);
    writeExr((dir / "indirect.exr").string(), r.indirect);
    writeExr((dir / "stderr.exr").string(), r.stdError);
    writePng8((dir / "final.png").string(), r.final.width, r.final.height, 3, toSrgb8(r.final, settings.exposure));

    nlohmann::json j;
    j["scene"] = a.scene;
    j["camera"] = camera.name;
    j["width"] = opt.width;
    j["height"] = opt.height;
    j["spp"] = opt.spp;
    j["bounces"] = opt.maxBounces;
    j["seed"] = opt.seed;
    j["threads"] = threads;
    j["time_s"] = r.seconds;
    j["rays"] = r.rays;
    j["rays_per_s"] = r.raysPerSecond();
    j["mean_relative_std_error"] = r.meanRelStdError;
    j["noise_note"] = "per-pixel standard error of the mean of the grey value (r+g+b)/3 divided by its mean, "
                      "averaged over pixels with mean > 1e-3; per-channel standard error in stderr.exr";
    j["files"] = {"final.exr", "direct.exr", "indirect.exr", "stderr.exr", "final.png"};
    if (!a.environment.empty()) j["environment"] = a.environment;
    j["settings"] = settingsToJson(settings);
    const std::string jsonPath = (dir / "reference.json").string();
    std::ofstream f(jsonPath);
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + jsonPath);

    if (!a.quiet)
        std::fprintf(stderr, "reference: %.2f s, %.2f Mrays/s, mean relative standard error %.4f -> %s\n", r.seconds,
                     r.raysPerSecond() * 1e-6, r.meanRelStdError, a.out.c_str());
    return 0;
}

const CommandRegistrar kReference(
    "reference", "Path-traced ground truth (Embree): final/direct/indirect EXR, PNG and noise report", 40,
    [](CLI::App& sub) -> std::function<int()> {
        auto a = std::make_shared<ReferenceArgs>();
        sub.add_option("scene", a->scene, "glTF (.gltf/.glb) or OBJ scene")->capture_default_str();
        sub.add_option("--camera", a->camera, "Camera name (default: the scene's first, or a framing camera)");
        sub.add_option("--camera-file", a->cameraFile, "Camera from a JSON file (a viewer capture's camera.json); wins over --camera");
        sub.add_option("--size", a->size, "Image size WxH")->capture_default_str();
        sub.add_option("--spp", a->spp, "Samples per pixel")->capture_default_str();
        sub.add_option("--bounces", a->bounces, "Maximum bounces after the camera ray (0 = direct light only)")
            ->capture_default_str();
        sub.add_option("--seed", a->seed, "Random seed (the image depends on it, not on the thread count)")
            ->capture_default_str();
        sub.add_option("--threads", a->threads, "Render threads (0 = all cores)")->capture_default_str();
        sub.add_option("--set", a->assignments, "Setting key=value (repeatable; see `deepgi settings`)")
            ->allow_extra_args(false);
        sub.add_option("--preset", a->preset, "Settings preset applied before --set");
        sub.add_option("--out", a->out, "Output directory")->capture_default_str();
        sub.add_option("--environment", a->environment, "Equirectangular environment map (EXR, HDR, ... via OpenImageIO; +Y up, u = 0.5 along +X), importance-sampled");
        sub.add_flag("--quiet", a->quiet, "No progress output");
        return [a] { return runReference(*a); };
    });

}  // namespace
}  // namespace deepgi
