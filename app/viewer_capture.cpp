// The viewer's files: the state file (window, camera, settings, layout between runs) and F12 captures.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include <imgui.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace deepgi {

namespace {

std::string fileNameFor(const std::string& layer) {
    std::string s;
    for (char c : layer) s += (c == ' ') ? '_' : char(std::tolower((unsigned char)c));
    return s;
}

}  // namespace

std::string defaultScreenshotDir() {
    auto env = [](const char* name) {
        const char* v = std::getenv(name);
        return std::string(v && *v ? v : "");
    };
    const std::string home = env("HOME");
    // XDG_PICTURES_DIR is usually set only in ~/.config/user-dirs.dirs; the environment variable wins if present.
    if (!env("XDG_PICTURES_DIR").empty()) return (fs::path(env("XDG_PICTURES_DIR")) / "deepgi").string();
    std::error_code ec;
    if (!home.empty() && fs::is_directory(fs::path(home) / "Pictures", ec)) return (fs::path(home) / "Pictures" / "deepgi").string();
    const std::string data = !env("XDG_DATA_HOME").empty() ? env("XDG_DATA_HOME") : (home.empty() ? std::string("/tmp") : home + "/.local/share");
    return (fs::path(data) / "deepgi" / "screenshots").string();
}

std::string viewerStatePath() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    if (xdg && *xdg) return std::string(xdg) + "/deepgi/viewer.json";
    const char* home = std::getenv("HOME");
    return std::string(home && *home ? home : ".") + "/.config/deepgi/viewer.json";
}

// ---- state file --------------------------------------------------------------------------------------------

void Viewer::loadState() {
    if (opt_.fresh) return;
    const std::string path = viewerStatePath();
    std::ifstream in(path);
    if (!in) return;
    try {
        nlohmann::json j = nlohmann::json::parse(in);
        if (!j.is_object()) throw std::runtime_error("not a JSON object");
        if (!opt_.sizeGiven && j.contains("window")) {
            opt_.width = std::clamp(j["window"].value("width", opt_.width), 64, 16384);
            opt_.height = std::clamp(j["window"].value("height", opt_.height), 64, 16384);
        }
        if (!opt_.settingsGiven && j.contains("settings")) {
            Settings s;
            for (const auto& w : applySettingsJsonLeniently(s, j["settings"], path))
                std::fprintf(stderr, "deepgi view: warning: %s\n", w.c_str());
            settings_ = s;
        }
        restoredScene_ = j.value("scene", std::string());
        if (j.contains("camera")) ctl_.fromJson(j["camera"]);
        view_.buffer = j.value("buffer", view_.buffer);
        view_.sidebar = j.value("sidebar", view_.sidebar);
        view_.emulate3Button = j.value("emulate_3_button", view_.emulate3Button);
        view_.resolutionScale = std::clamp(j.value("resolution_scale", view_.resolutionScale), 0.25f, 1.0f);
        const float target = j.value("target_frame_ms", view_.targetFrameMs);
        view_.targetFrameMs = std::isfinite(target) ? std::min(target, 10000.0f) : -1.0f;  // < 0: automatic
        captureBuffers_ = j.value("capture_buffers", captureBuffers_);
        inspector_.open = j.value("inspector_open", inspector_.open);
        view_.inspectorSplit = std::clamp(j.value("inspector_split", view_.inspectorSplit), ui::kMinSplit, ui::kMaxSplit);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deepgi view: warning: ignoring the state file %s (%s)\n", path.c_str(), e.what());
        settings_ = opt_.settings;
        ctl_ = CameraController{};
        restoredScene_.clear();
    }
}

void Viewer::saveState() {
    if (opt_.fresh || !window_) return;
    int w = opt_.width, h = opt_.height;
    if (!glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) glfwGetWindowSize(window_, &w, &h);
    nlohmann::json j = {{"version", 1},
                        {"window", {{"width", w}, {"height", h}}},
                        {"scene", scene_ ? scene_->sourcePath : std::string()},
                        {"camera", ctl_.toJson()},
                        {"settings", settingsToJson(settings_)},
                        {"buffer", view_.buffer},
                        {"sidebar", view_.sidebar},
                        {"emulate_3_button", view_.emulate3Button},
                        {"resolution_scale", view_.resolutionScale},
                        {"target_frame_ms", view_.targetFrameMs},
                        {"capture_buffers", captureBuffers_},
                        {"inspector_open", inspector_.open},
                        {"inspector_split", view_.inspectorSplit}};
    const std::string path = viewerStatePath();
    try {
        fs::create_directories(fs::path(path).parent_path());
        const std::string tmp = path + ".tmp";
        {
            std::ofstream out(tmp);
            out << j.dump(2) << "\n";
            if (!out) throw std::runtime_error("write failed");
        }
        fs::rename(tmp, path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deepgi view: warning: cannot write the state file %s (%s)\n", path.c_str(), e.what());
    }
}

// ---- screenshots -------------------------------------------------------------------------------------------

void Viewer::renderFullSize(int frames) {
    if (fullW_ <= 0 || (renderer_->width() == fullW_ && renderer_->height() == fullH_)) return;
    renderer_->resize(fullW_, fullH_);
    try {
        for (int i = 0; i < frames; ++i) renderer_->render(settings_);
    } catch (const std::exception& e) {
        renderError_ = e.what();
    }
    lastSample_.valid = false;  // not a typical frame
}

void Viewer::capture() {
    // A capture is of the whole viewport, also while the dynamic resolution renders less: a few frames at full
    // size first (the temporal history starts over with the new size).
    renderFullSize(4);
    if (renderer_->width() <= 0 || !renderer_->textures().has("Final Display")) {
        setStatus("nothing rendered yet: no screenshot");
        lastCaptureFailed_ = true;
        return;
    }
    lastCaptureFailed_ = false;
    char stamp[64];
    const std::time_t t = std::time(nullptr);
    std::strftime(stamp, sizeof(stamp), "%Y-%m-%d_%H-%M-%S", std::localtime(&t));
    fs::path dir = fs::path(opt_.screenshotDir) / stamp;
    for (int i = 2; fs::exists(dir); ++i) dir = fs::path(opt_.screenshotDir) / (std::string(stamp) + "_" + std::to_string(i));
    try {
        fs::create_directories(dir);
        const auto& e = renderer_->textures().entry("Final Display");
        writePng8((dir / "final.png").string(), renderer_->width(), renderer_->height(), 4, renderer_->readDisplay());
        int n = 0;
        if (captureBuffers_)
            for (const auto& name : renderer_->textures().layerNames()) {
                writeExr((dir / (fileNameFor(name) + ".exr")).string(), renderer_->readLayer(name, 0, false));
                ++n;
            }
        saveSettingsFile(settings_, (dir / "settings.json").string());
        if (view_.pathTrace != ui::PathTraceMode::Off && ptSnap_.samples > 0) {
            writeExr((dir / "pathtrace.exr").string(), ptSnap_.final);  // the live path trace, as accumulated
            std::ofstream((dir / "pathtrace.json").string())
                << nlohmann::json{{"samples", ptSnap_.samples}, {"width", ptSnap_.final.width}, {"height", ptSnap_.final.height},
                                  {"figures", ptFigures_}}.dump(2) << "\n";
        }
        // The renderer's camera exactly (`render/reference/bench --camera-file` read it), the render size, and the
        // orbit state so that `view --camera-file` resumes the same navigation.
        nlohmann::json cam = cameraToJson(renderer_->camera());
        cam["width"] = e.width;
        cam["height"] = e.height;
        cam["scene"] = scene_->sourcePath;
        cam["viewer_orbit"] = ctl_.toJson();
        std::ofstream((dir / "camera.json").string()) << cam.dump(2) << "\n";
        lastCapture_ = fs::absolute(dir).string();
        setStatus("saved " + lastCapture_ + (n ? " (final.png, " + std::to_string(n) + " EXR buffers, settings.json, camera.json)" : " (final.png, settings.json, camera.json)"));
        std::printf("deepgi view: screenshot %s\n", lastCapture_.c_str());
        std::fflush(stdout);
    } catch (const std::exception& ex) {
        setStatus(std::string("screenshot failed: ") + ex.what());
        lastCaptureFailed_ = true;
        std::fprintf(stderr, "deepgi view: %s\n", view_.status.c_str());
    }
}

void Viewer::writeWindowPng(const std::string& path) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w <= 0 || h <= 0) return;
    std::vector<unsigned char> px(size_t(w) * h * 3), flipped(px.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px.data());
    const size_t row = size_t(w) * 3;
    for (int y = 0; y < h; ++y) std::memcpy(&flipped[size_t(y) * row], &px[size_t(h - 1 - y) * row], row);
    if (fs::path(path).has_parent_path()) fs::create_directories(fs::path(path).parent_path());
    writePng8(path, w, h, 3, flipped);
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
