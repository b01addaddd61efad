#include "app/options.h"

#include "renderer/core/util.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <tuple>

namespace deepgi {

GltfLoadOptions withLoadProgress(GltfLoadOptions options, const std::string& path) {
    using Clock = std::chrono::steady_clock;
    struct State { Clock::time_point start = Clock::now(), last; bool printed = false; };
    auto state = std::make_shared<State>();
    const std::string name = std::filesystem::path(path).filename().string();
    options.progress = [state, name](const char* stage, double fraction) {
        const Clock::time_point now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - state->start).count();
        if (std::string(stage) == "done") {
            if (state->printed) std::fprintf(stderr, "deepgi: loaded %s in %.1f s\n", name.c_str(), elapsed);
            return;
        }
        if (elapsed < 0.5 || (state->printed && now - state->last < std::chrono::milliseconds(500))) return;
        std::fprintf(stderr, "deepgi: loading %s: %s %3.0f %%\n", name.c_str(), stage, 100.0 * fraction);
        state->printed = true;
        state->last = now;
    };
    return options;
}


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
