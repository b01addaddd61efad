#include "app/options.h"

#include "renderer/core/util.h"

#include <stdexcept>
#include <tuple>

namespace deepgi {

void SettingsOptions::add(CLI::App& sub) {
    sub.add_option("--preset", preset, "Preset: performance, balanced or quality");
    sub.add_option("--settings", settingsFile, "Settings JSON file (as written to settings.json)");
    sub.add_option("--set", assignments, "Override one setting: key=value (see `deepgi settings`)");
}

Settings SettingsOptions::build() const {
    Settings s;
    if (!preset.empty()) applyPreset(s, preset);
    if (!settingsFile.empty()) loadSettingsFile(s, settingsFile);
    for (const auto& a : assignments) applyAssignment(s, a);
    return s;
}

std::string defaultScenePath() { return std::string(DEEPGI_ASSET_DIR) + "/atrium/atrium.gltf"; }

void parseSize(const std::string& text, int& w, int& h, bool allowZero, const std::string& option) {
    try {
        std::tie(w, h) = parseImageSize(text, allowZero);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(option + ": " + e.what());
    }
}

}  // namespace deepgi
