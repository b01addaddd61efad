// The script verbs of scene editing (ui/script.h): the viewport's clicks and pointer moves, dump_scene, save,
// timeline.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include "renderer/scene/lighting.h"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace deepgi {

namespace {
nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

void Viewer::scriptMouseMove(glm::dvec2 at) {
    queueInput({InputEvent::Kind::Cursor, 0, 0, 0, at.x, at.y, true});
    scriptPointerSet_ = true;  // the UI's pointer follows (hover)
    scriptPointerAt_ = at;
}

void Viewer::routeScriptClick() {
    // ImGui's NewFrame has found the window under the pointer: a press no window took is the viewport's, as a
    // real click would be (selection, confirming or cancelling a transform).
    while (!scriptClicks_.empty()) {
        const PendingClick c = scriptClicks_.front();
        scriptClicks_.pop_front();
        if (c.action == GLFW_PRESS && (ImGui::GetIO().WantCaptureMouse || !inViewport(c.at.x, c.at.y))) continue;
        lastX_ = c.at.x;
        lastY_ = c.at.y;
        onMouseButton(c.button, c.action, c.mods, true);
    }
}

void Viewer::scriptSave(const std::string& path) {
    saveMessage_ = saveScene(path);
    view_.saveMessage = saveMessage_;
    setStatus(saveMessage_);
}

void Viewer::scriptTimeline(const std::string& what) {
    if (scene_->animations.empty()) throw std::runtime_error("the scene has no animations");
    if (what == "play") playing_ = true;
    else if (what == "pause") playing_ = false;
    else {
        animTime_ = std::min(float(std::strtod(what.c_str(), nullptr)), scene_->animationDuration());
        applyAnimationNow();
    }
}

void Viewer::scriptDumpScene(const std::string& path) {
    const Scene& s = *scene_;
    nlohmann::json nodes = nlohmann::json::array(), lights = nlohmann::json::array(), icons = nlohmann::json::array();
    for (const auto& n : s.nodes) {
        const glm::quat q = n.local.rotation;
        nodes.push_back({{"name", n.name}, {"parent", n.parent}, {"translation", vec(n.local.translation)},
                         {"rotation", {q.w, q.x, q.y, q.z}}, {"euler_degrees", vec(edit::eulerDegrees(q))},
                         {"scale", vec(n.local.scale)}, {"world_position", vec(glm::vec3(n.world[3]))},
                         {"visible", n.visible}, {"light", n.light}, {"parts", n.parts.size()}});
    }
    for (const auto& l : s.lights)
        lights.push_back({{"name", l.name}, {"type", int(l.type)}, {"color", vec(l.color)}, {"intensity", l.intensity},
                          {"position", vec(l.position)}, {"direction", vec(l.direction)}, {"node", l.node}});
    for (const auto& i : edit::lightIcons(s, settings_, toolView()))
        icons.push_back({{"item", i.item}, {"x", vpX0_ + i.screen.x}, {"y", vpY0_ + i.screen.y}, {"on_screen", i.onScreen}});
    // Where each node shows in the last frame (from the Object ID buffer): its pixel nearest the centroid of its
    // pixels, in window units, and how many pixels it covers; for tests that click on an object.
    nlohmann::json picks = nlohmann::json::object();
    try {
        const FloatImage ids = renderer_->readLayer("Object ID 1", 0, false);
        std::vector<glm::dvec3> sum(s.nodes.size(), glm::dvec3(0.0));
        for (int y = 0; y < ids.height; ++y)
            for (int x = 0; x < ids.width; ++x) {
                const int n = int(ids.at(x, y, 0)) - 1;
                if (n >= 0 && n < int(sum.size())) sum[size_t(n)] += glm::dvec3(x, y, 1.0);
            }
        const double kx = (vpX1_ - vpX0_) / std::max(ids.width, 1), ky = (vpY1_ - vpY0_) / std::max(ids.height, 1);
        // One more pass: per node, the pixel nearest its centroid, inner pixels (all 8 neighbours the same) first.
        std::vector<double> best(sum.size(), 1e300);
        std::vector<glm::dvec2> at(sum.size(), glm::dvec2(0.0));
        auto idAt = [&](int x, int y) { return int(ids.at(x, y, 0)) - 1; };
        for (int y = 0; y < ids.height; ++y)
            for (int x = 0; x < ids.width; ++x) {
                const int n = idAt(x, y);
                if (n < 0 || n >= int(sum.size())) continue;
                bool inner = x > 0 && y > 0 && x + 1 < ids.width && y + 1 < ids.height;
                for (int dy = -1; dy <= 1 && inner; ++dy)
                    for (int dx = -1; dx <= 1 && inner; ++dx) inner = idAt(x + dx, y + dy) == n;
                const glm::dvec2 c(sum[size_t(n)].x / sum[size_t(n)].z, sum[size_t(n)].y / sum[size_t(n)].z);
                const double d = glm::length(glm::dvec2(x, y) - c) + (inner ? 0.0 : 1e6);
                if (d < best[size_t(n)]) best[size_t(n)] = d, at[size_t(n)] = glm::dvec2(x + 0.5, y + 0.5);
            }
        for (size_t n = 0; n < sum.size(); ++n)
            if (sum[n].z > 0.0)
                picks[s.nodes[n].name] = {{"x", vpX0_ + at[n].x * kx}, {"y", vpY0_ + at[n].y * ky}, {"pixels", sum[n].z}};
    } catch (const std::exception&) {
    }
    nlohmann::json rows = nlohmann::json::object();
    for (const auto& [k, r] : scenePanel_.rects) rows[k] = {r.x, r.y, r.z, r.w};
    const glm::vec3 sun = defaultSunDirection(settings_);
    const nlohmann::json j = {
        {"nodes", nodes},
        {"lights", lights},
        {"light_icons", icons},
        {"selection", selection_.items},
        {"active", selection_.active},
        {"tool", {{"active", tool_.active()}, {"mode", int(tool_.mode())}, {"header", tool_.header()}}},
        {"undo", {{"steps", history_.size()}, {"undoable", history_.undoable()}, {"last", lastEditLabel_}}},
        {"sun", {{"azimuth", settings_.sunAzimuth}, {"elevation", settings_.sunElevation}, {"intensity", settings_.sunIntensity},
                 {"direction", vec(sun)}}},
        {"timeline", {{"time", animTime_}, {"playing", playing_}, {"duration", s.animationDuration()}, {"animations", s.animations.size()}}},
        {"save_message", saveMessage_},
        {"outliner", rows},
        {"outline_pixels", outlinePixels_},
        {"picks", picks},
        {"viewport", {vpX0_, vpY0_, vpX1_, vpY1_}},
        {"render", {renderer_->width(), renderer_->height()}}};
    std::ofstream out(path);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
