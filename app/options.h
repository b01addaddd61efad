#pragma once
// Options shared by the sub-commands: scene path, size, settings.
#include "renderer/core/settings.h"
#include "renderer/scene/gltf_loader.h"

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace deepgi {

struct SettingsOptions {
    std::string preset;
    std::string settingsFile;
    std::vector<std::string> assignments;
    void add(CLI::App& sub);
    Settings build() const;  // defaults <- preset <- file <- --set, in that order
};

std::string defaultScenePath();
// `options` with a progress line on stderr for loads that take more than half a second ("loading FILE: meshes
// 40 %", at most twice a second, then "loaded FILE in S s"): small scenes stay quiet.
GltfLoadOptions withLoadProgress(GltfLoadOptions options, const std::string& path);
// "WxH" -> width, height through parseImageSize (renderer/core/util.h): 1..65536 each (0 allowed if allowZero),
// std::runtime_error naming the option and the text for anything else.
void parseSize(const std::string& text, int& w, int& h, bool allowZero = false, const std::string& option = "--size");

}  // namespace deepgi
