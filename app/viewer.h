#pragma once
// `deepgi view`: the interactive GLFW + Dear ImGui viewer over the renderer.
#include "renderer/core/settings.h"

#include <string>

namespace deepgi {

struct ViewerOptions {
    std::string scenePath;
    std::string environment;  // --environment: an equirectangular map ("" = none)
    std::string camera;          // glTF camera name ("" = restored view, else the scene's first camera)
    std::string cameraFile;      // --camera-file: a capture's camera.json (wins over camera)
    std::string scriptPath;      // --script: timed actions, exits at the end
    std::string shaderDir;       // --shaders ("" = the built-in folder)
    std::string screenshotDir;   // "" = defaultScreenshotDir()
    int width = 1280, height = 720;
    bool sizeGiven = false;      // --size overrides the restored window size
    Settings settings;
    bool settingsGiven = false;  // --preset/--settings/--set override the restored settings
    bool fresh = false;          // --fresh: ignore (and do not write) the state file
    double targetFrameMs = -1.0; // --target-frame-ms: the dynamic resolution's target (0 off; < 0 the restored or
                                 // automatic one: 100 ms on software GL, 16.7 ms on a GPU)
};

// Returns the process exit code. Prints "deepgi view needs a display; ..." and returns 1 without a display.
int runViewer(const ViewerOptions& options);

// $XDG_CONFIG_HOME/deepgi/viewer.json, else ~/.config/deepgi/viewer.json.
std::string viewerStatePath();
// Where F12 captures go by default, never the working tree: $XDG_PICTURES_DIR/deepgi, else ~/Pictures/deepgi if
// ~/Pictures exists, else $XDG_DATA_HOME/deepgi/screenshots (~/.local/share/deepgi/screenshots).
std::string defaultScreenshotDir();

}  // namespace deepgi
