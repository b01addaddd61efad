#pragma once
// Options shared by the sub-commands: scene path, size, settings.
#include "renderer/core/settings.h"

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
// "WxH" -> width, height; throws std::runtime_error naming the text for anything else (0 allowed if allowZero).
void parseSize(const std::string& text, int& w, int& h, bool allowZero = false);

}  // namespace deepgi
