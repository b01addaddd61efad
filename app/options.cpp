#include "app/options.h"

#include "renderer/reference/path_tracer.h"

#include <tuple>
#include <stdexcept>

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

void parseSize(const std::string& text, int& w, int& h, bool allowZero) {
    if (allowZero && (text == "0x0" || text == "0X0")) {
        w = h = 0;
        return;
    }
    try {
        std::tie(w, h) = parseImageSize(text);  // the one WxH parser (render, reference, bench, view, buffers)
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("--size: ") + e.what() + (allowZero ? " (or 0x0 for none)" : ""));
    }
}

}  // namespace deepgi
