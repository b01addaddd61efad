// The viewer's side of the script (ui/script.h): each verb applied to the viewer's state. A failure throws the
// reason; the runner adds FILE:LINE.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace deepgi {

// The script's keys and viewport drags take the same queue as GLFW's events (handled right after the script's step).
void Viewer::scriptKey(int key, int mods) {
    queueInput({InputEvent::Kind::Key, key, GLFW_PRESS, mods, 0.0, 0.0, true});
    queueInput({InputEvent::Kind::Key, key, GLFW_RELEASE, mods, 0.0, 0.0, true});
}

void Viewer::scriptDrag(int button, glm::dvec2 from, glm::dvec2 to, int mods) {
    if (!inViewport(from.x, from.y)) {  // over a window: the UI sees press, moves and release on successive frames
        if (button != GLFW_MOUSE_BUTTON_LEFT) throw std::runtime_error("a drag over a window must use the left button");
        uiDrag_.push_back({from, false});
        uiDrag_.push_back({from, true});
        for (int i = 1; i <= 8; ++i) uiDrag_.push_back({from + (to - from) * (i / 8.0), true});
        uiDrag_.push_back({to, false});
        return;
    }
    using K = InputEvent::Kind;
    queueInput({K::Cursor, 0, 0, 0, from.x, from.y, true});
    queueInput({K::Button, button, GLFW_PRESS, mods, 0.0, 0.0, true});
    for (int i = 1; i <= 8; ++i) queueInput({K::Cursor, 0, 0, 0, from.x + (to.x - from.x) * i / 8.0, from.y + (to.y - from.y) * i / 8.0, true});
    queueInput({K::Button, button, GLFW_RELEASE, mods, 0.0, 0.0, true});
}

void Viewer::scriptPointer(glm::dvec2 at, int button, bool down, int mods) {
    if (button >= 0) scriptClicks_.push_back({true, at, button, down ? GLFW_PRESS : GLFW_RELEASE, mods});  // see routeScriptClick
    uiInput_ = true;  // the script's pointer is the UI's (a click on the viewport starts no drag)
    scriptPointerSet_ = true;
    scriptPointerAt_ = at;
    if (button >= 0) {
        const int i = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
        scriptButtons_[i] = down;
    }
}

void Viewer::scriptScroll(double notches, const glm::dvec2* at) {
    if (at) {
        scriptWheelAt_ = *at;
        scriptPointerSet_ = true;  // a wheel turns where the pointer is
        scriptPointerAt_ = *at;
    } else {
        scriptWheelAt_ = glm::dvec2((vpX0_ + vpX1_) * 0.5, (vpY0_ + vpY1_) * 0.5);
    }
    scriptWheel_ += notches;
}

void Viewer::scriptSet(const std::string& assignment) { applyAssignment(settings_, assignment); }

void Viewer::scriptShow(const std::string& buffer) {
    const auto names = bufferNames();
    if (std::find(names.begin(), names.end(), buffer) == names.end())
        throw std::runtime_error("no buffer named '" + buffer + "' in the current pipeline");
    view_.buffer = buffer;
}

void Viewer::scriptInspect(const std::string& a, const std::string& b) {
    const auto names = bufferNames();
    if (std::find(names.begin(), names.end(), a) == names.end())
        throw std::runtime_error("no buffer named '" + a + "' in the current pipeline");
    if (!b.empty() && std::find(names.begin(), names.end(), b) == names.end())
        throw std::runtime_error("no buffer named '" + b + "' for B");
    inspector_.open = true;
    inspector_.a = a;
    inspector_.level = dataLevel(a);
    inspector_.zoom = 0.0f;
    if (!b.empty()) inspector_.b = b;
}

void Viewer::scriptCompare(const std::string& mode) {
    if (inspector_.b.empty()) throw std::runtime_error("compare needs a B image: inspect \"A\" \"B\" first");
    inspector_.compare = mode == "a" ? ui::CompareMode::A : mode == "b" ? ui::CompareMode::B : mode == "wipe" ? ui::CompareMode::Wipe
                       : mode == "diff" ? ui::CompareMode::Diff : ui::CompareMode::Relative;
}

void Viewer::scriptReference(const std::string& path) {
    const std::string err = loadReference(path);
    if (!err.empty()) throw std::runtime_error(err);
}

void Viewer::scriptPathTrace(const std::string& mode) {
    view_.pathTrace = mode == "off" ? ui::PathTraceMode::Off : mode == "full" ? ui::PathTraceMode::Full : ui::PathTraceMode::Split;
}

void Viewer::scriptCamera(const std::string& name) {
    auto it = std::find(view_.cameraNames.begin(), view_.cameraNames.end(), name);
    if (it == view_.cameraNames.end()) throw std::runtime_error("no camera named '" + name + "'");
    useSceneCamera(int(it - view_.cameraNames.begin()));
}

void Viewer::scriptPanel(const std::string& name) {
    view_.sidebar = true;
    sidebar_.selectTab = name;
}

void Viewer::scriptResize(int w, int h) { glfwSetWindowSize(window_, w, h); }

void Viewer::scriptCapture() {
    capture();
    if (lastCaptureFailed_) throw std::runtime_error(view_.status);
}

void Viewer::scriptProfilerCsv(const std::string& path) {
    const std::string err = writeProfilerCsv(path);
    if (!err.empty()) throw std::runtime_error(err);
}

void Viewer::scriptDumpErrors(const std::string& path) {
    std::ofstream out(path);
    for (const auto& e : renderer_->shaders().errors()) out << e << "\n";
    if (!renderError_.empty()) out << renderError_ << "\n";
    if (!out) throw std::runtime_error("cannot write " + path);
}

void Viewer::scriptDumpFigures(const std::string& path) {
    std::ofstream out(path);
    out << "inspector: " << inspector_.a << (inspector_.b.empty() ? "" : " vs " + inspector_.b) << "\n";
    out << "figures: " << inspector_.figures << "\n";
    std::string readout = inspector_.readout;
    std::replace(readout.begin(), readout.end(), '\n', '|');  // one line per key
    out << "readout: " << readout << "\n";
    out << "stats: " << (inspector_.stats.valid ? "valid" : "none") << " empty " << inspector_.stats.empty << " negative "
        << inspector_.stats.negative << " texels " << inspector_.stats.texels << " vectors " << inspector_.stats.vectors
        << " mean_length " << inspector_.stats.meanLength << "\n";
    out << "pathtrace: " << (view_.pathTrace == ui::PathTraceMode::Off ? std::string("off") : pathTraceFiguresLine()) << "\n";
    out << "pathtrace_samples: " << ptSnap_.samples << " generation " << ptSnap_.generation << " size " << ptSnap_.final.width
        << "x" << ptSnap_.final.height << "\n";
    out << "inspector_zoom: " << inspector_.zoom << "\n";
    const BufferSource ia = source(inspector_.a, inspector_.level);
    out << "inspector_buffer: " << ia.levelWidth() << " " << ia.levelHeight() << "\n";
    const auto& r = inspector_.imageRect;
    const auto& b = inspector_.statsButtonRect;
    out << "inspector_image: " << r.x << " " << r.y << " " << r.z << " " << r.w << "\n";
    out << "stats_button: " << b.x << " " << b.y << " " << b.z << " " << b.w << "\n";
    out << "stats_mean: " << inspector_.stats.mean[0] << " " << inspector_.stats.mean[1] << " " << inspector_.stats.mean[2] << "\n";
    out << "inspector_mode: " << int(inspector_.params.mode) << " channel " << int(inspector_.params.channel) << " range "
        << inspector_.params.useRange << " " << inspector_.params.rangeMin << " " << inspector_.params.rangeMax << "\n";
    out << "viewport_buffer: " << view_.buffer << "\n";
    out << "pipeline_selected: " << pipelinePanel_.selectedPass << "\n";
    for (const auto& [name, rc] : pipelinePanel_.itemRects)
        out << "pipeline " << name << ": " << rc.x << " " << rc.y << " " << rc.z << " " << rc.w << "\n";
    out << "layout: viewport " << vpX0_ << " " << vpX1_ << " inspector " << inspX0_ << " " << inspX1_ << " split "
        << view_.inspectorSplit << "\n";
    if (!out) throw std::runtime_error("cannot write " + path);
}

void Viewer::scriptReload() {
    renderer_->shaders().reloadAll();
    needRender_ = true;
}

void Viewer::scriptStats(const std::string& path) {
    int ww = 0, wh = 0;
    glfwGetWindowSize(window_, &ww, &wh);
    nlohmann::json frames = nlohmann::json::array(), frameMs = nlohmann::json::array();
    for (const auto& f : recentFrames_) {  // oldest first
        frames.push_back({{"frame_ms", f.frameMs}, {"render_ms", f.renderMs}, {"width", f.width}, {"height", f.height},
                          {"moving", f.moving}, {"rendered", f.rendered}});
        frameMs.push_back(f.frameMs);
    }
    const nlohmann::json j = {
        {"target_frame_ms", dynres_.enabled() ? dynres_.target() : 0.0},
        {"dynamic", dynres_.enabled()},
        {"software_gl", softwareGl_},
        {"moving", moving_},
        {"step", dynres_.step()},
        {"scale", dynres_.scale()},
        {"render", {{"width", renderer_->width()}, {"height", renderer_->height()}}},
        {"viewport", {{"width", fullW_}, {"height", fullH_}}},  // framebuffer pixels, times the resolution slider
        {"window", {{"width", ww}, {"height", wh}}},            // window units
        {"frame_ms", frameMs},
        {"frames", frames},
        {"input_events", inputEvents_},
        {"key_presses", keyPresses_},
        {"ui_only_frames", uiOnlyFrames_},
        {"idle_frames", idleFrames_},
        {"converged", converged_},
        {"sidebar", view_.sidebar},
        {"inspector", inspector_.open},
        {"fly_mode", view_.flyMode},
        {"camera_position", {lastCamera_.position().x, lastCamera_.position().y, lastCamera_.position().z}}};
    std::ofstream out(path);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
