#include "app/options.h"

#include <regex>
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
    static const std::regex re(R"((\d{1,6})[xX](\d{1,6}))");
    std::smatch m;
    if (!std::regex_match(text, m, re)) throw std::runtime_error("--size expects WxH (e.g. 640x360), got '" + text + "'");
    w = std::stoi(m[1]);
    h = std::stoi(m[2]);
    if (!allowZero && (w == 0 || h == 0)) throw std::runtime_error("--size " + text + ": width and height must be at least 1");
}

}  // namespace deepgi
