// deepgi view: the interactive viewer (GLFW + Dear ImGui), see app/viewer.cpp.
#include "app/command.h"
#include "app/options.h"
#include "app/viewer.h"

#include <cstdio>
#include <memory>

namespace deepgi {
namespace {

CommandRegistrar registrar("view", "Interactive viewer: Blender-style navigation, settings, buffer inspector, profiler", 5,
                           [](CLI::App& sub) {
    auto opt = std::make_shared<ViewerOptions>();
    auto size = std::make_shared<std::string>();
    auto settings = std::make_shared<SettingsOptions>();
    sub.add_option("scene", opt->scenePath, "glTF/glb or OBJ file (default: the atrium in assets/)");
    sub.add_option("--size", *size, "Window size WxH (default: the last one, else 1280x720)");
    sub.add_option("--camera", opt->camera, "Start from this glTF camera");
    sub.add_option("--camera-file", opt->cameraFile, "Start from the camera in a JSON file (a capture's camera.json)");
    sub.add_option("--environment", opt->environment, "Equirectangular environment map (EXR, HDR, ... via OpenImageIO; +Y up, u = 0.5 along +X): seen as the backdrop, lights the scene (environment.*)");
    sub.add_option("--script", opt->scriptPath, "Run timed actions from FILE and exit at its end (see ui/script.h)");
    sub.add_option("--shaders", opt->shaderDir, "Shader folder (default: the source tree's shaders/); edits reload live");
    sub.add_option("--screenshots", opt->screenshotDir, "Folder for F12 screenshots (default: $XDG_PICTURES_DIR/deepgi, ~/Pictures/deepgi or $XDG_DATA_HOME/deepgi/screenshots)");
    sub.add_option("--target-frame-ms", opt->targetFrameMs,
                   "Dynamic resolution: while the camera moves, render at the fraction of the viewport that holds this "
                   "frame time (0 = always full size; default: the last one, else 100 on software GL, 16.7 on a GPU)")
        ->check(CLI::Range(0.0, 10000.0));
    sub.add_flag("--fresh", opt->fresh, "Ignore the saved viewer state and do not write it");
    settings->add(sub);
    return [opt, size, settings]() {
#ifdef DEEPGI_HAVE_UI
        if (!size->empty()) {
            parseSize(*size, opt->width, opt->height);
            opt->sizeGiven = true;
        }
        opt->settings = settings->build();
        opt->settingsGiven = !settings->preset.empty() || !settings->settingsFile.empty() || !settings->assignments.empty();
        if (opt->scenePath.empty()) opt->scenePath = defaultScenePath();
        if (opt->screenshotDir.empty()) opt->screenshotDir = defaultScreenshotDir();
        return runViewer(*opt);
#else
        std::fprintf(stderr, "deepgi view: this build has no UI (ui/ had no sources)\n");
        return 1;
#endif
    };
});

}  // namespace
}  // namespace deepgi
