// deepgi passtime: per-pass times of two shader folders side by side in one process (A/B), for performance work on a
// shared machine: both renderers converge on the same scene, then each pass is re-run alone, alternating A and B,
// and timed by wall clock (glFinish) and by this thread's CPU time (meaningful with LP_NUM_THREADS=0, where llvmpipe
// rasterises in the calling thread, so other processes' load does not count).
#include "app/command.h"
#include "app/options.h"
#include "bench/metrics.h"
#include "renderer/core/util.h"
#include "renderer/gl/headless_context.h"
#include "renderer/renderer.h"
#include "renderer/scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <sstream>

namespace deepgi {
namespace {

struct PassTimeArgs {
    std::string scene, camera = "courtyard", size = "640x360", shadersA, shadersB, passes;
    int frames = 12, repeats = 9;
    SettingsOptions settings;
};

int runPassTime(const PassTimeArgs& a) {
    int w, h;
    parseSize(a.size, w, h);
    const Settings s = a.settings.build();
    auto scene = std::make_shared<Scene>(loadScene(a.scene.empty() ? defaultScenePath() : a.scene, gltfLoadOptions(s)));
    const Camera cam = selectCamera(*scene, a.scene.empty() ? a.camera : a.camera);
    gl::HeadlessContext context;
    std::vector<std::string> dirs = {a.shadersA, a.shadersB};
    std::vector<std::unique_ptr<Renderer>> rs;
    for (const auto& d : dirs) {
        RendererOptions o;
        if (!d.empty()) o.shaderDir = d;
        o.timing = TimingMode::WallClock;
        rs.push_back(std::make_unique<Renderer>(o));
        rs.back()->setScene(scene);
        rs.back()->resize(w, h);
        rs.back()->setCamera(cam);
        for (int f = 0; f < a.frames; ++f) rs.back()->render(s);
    }
    const double diff = bench::meanRelativeError(bench::rgb(rs[1]->readFinalRadiance()), bench::rgb(rs[0]->readFinalRadiance()));
    std::vector<std::string> names;
    if (a.passes.empty()) {
        for (const auto& t : rs[0]->timings()) names.push_back(t.name);
    } else {
        std::stringstream ss(a.passes);
        std::string item;
        while (std::getline(ss, item, ',')) names.push_back(item);
    }
    std::map<std::string, std::vector<double>> wall[2], cpu[2];
    using clock = std::chrono::steady_clock;
    for (int k = 0; k < a.repeats; ++k)
        for (int i = 0; i < 2; ++i) {
            const int r = (k % 2) ? 1 - i : i;  // ABBA order
            for (const auto& n : names) {
                glFinish();
                const auto t0 = clock::now();
                const double c0 = threadCpuMs();
                rs[r]->executePass(n, s);
                glFinish();
                cpu[r][n].push_back(threadCpuMs() - c0);
                wall[r][n].push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
            }
        }
    std::printf("%s %dx%d, %d repeats alternating A/B; A = %s, B = %s\n", context.renderer().c_str(), w, h, a.repeats,
                dirs[0].empty() ? "(default shaders)" : dirs[0].c_str(), dirs[1].empty() ? "(default shaders)" : dirs[1].c_str());
    std::printf("%-20s %12s %12s %8s %12s %12s %8s\n", "pass", "A wall ms", "B wall ms", "B/A", "A cpu ms", "B cpu ms", "B/A");
    for (const auto& n : names) {
        const double wa = median(wall[0][n]), wb = median(wall[1][n]), ca = median(cpu[0][n]), cb = median(cpu[1][n]);
        std::printf("%-20s %12.2f %12.2f %8.3f %12.2f %12.2f %8.3f\n", n.c_str(), wa, wb, wb / wa, ca, cb, cb / std::max(ca, 1e-9));
    }
    std::printf("final image after %d frames: mean relative difference B vs A = %.5f\n", a.frames, diff);
    return 0;
}

CommandRegistrar registrar("passtime", "Time passes of two shader folders side by side (A/B) in one process", 36, [](CLI::App& sub) {
    auto a = std::make_shared<PassTimeArgs>();
    sub.add_option("scene", a->scene, "glTF/glb or OBJ scene (default: the atrium)");
    sub.add_option("--camera", a->camera, "Camera name")->capture_default_str();
    sub.add_option("--size", a->size, "Image size WxH")->capture_default_str();
    sub.add_option("--frames", a->frames, "Frames rendered first (convergence)")->capture_default_str()->check(CLI::Range(1, 10000));
    sub.add_option("--repeats", a->repeats, "Timed runs of each pass per folder")->capture_default_str()->check(CLI::Range(1, 10000));
    sub.add_option("--shaders-a", a->shadersA, "Shader folder A (default: the source tree's)");
    sub.add_option("--shaders-b", a->shadersB, "Shader folder B (default: the source tree's)");
    sub.add_option("--passes", a->passes, "Comma-separated pass names (default: every pass of a frame)");
    a->settings.add(sub);
    return [a]() { return runPassTime(*a); };
});

}  // namespace
}  // namespace deepgi
