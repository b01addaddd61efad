// The viewer's scene editing: selection (viewport click through the Object ID buffer, light icons, outliner, A /
// Alt+A), Blender's G / R / S through edit::TransformTool, H / Alt+H, undo and redo, the Item tab (outliner and N
// panel), the selection's outline and the light icons over the viewport, the timeline and File > Save As.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include "renderer/scene/animation.h"
#include "renderer/scene/gltf_writer.h"
#include "renderer/scene/lighting.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace deepgi {

namespace {
constexpr float kIconPickRadius = 10.0f;  // window units: a click this near a light's icon selects the light
const char* modeLabel(edit::ToolMode m) {
    return m == edit::ToolMode::Translate ? "Move" : m == edit::ToolMode::Rotate ? "Rotate" : "Scale";
}
// The default sun as a transform target: its direction is the rotation of -Z (how a glTF light points).
glm::quat rotationTo(const glm::vec3& dir) { return edit::rotationBetween(glm::vec3(0.0f, 0.0f, -1.0f), dir); }
}  // namespace

edit::ToolView Viewer::toolView() const {
    edit::ToolView v;
    v.camera = lastCamera_;
    v.width = std::max(vpX1_ - vpX0_, 1.0f);
    v.height = std::max(vpY1_ - vpY0_, 1.0f);
    return v;
}

void Viewer::beforeSceneEdit() {
    // "Path trace this view" reads the scene on its worker thread: it stops before the scene changes (joined) and
    // starts again on the edited scene after the next frame.
    if (!pathTrace_) return;
    pathTrace_.reset();
    ptSnap_ = {};
}

void Viewer::sceneEdited(unsigned changes) {
    if (changes == 0) return;
    renderer_->sceneChanged(changes);
    needRender_ = true;
    lastMotionTime_ = nowSeconds();  // the render follows like a motion (the dynamic resolution)
    framesStill_ = 0;
    outlineKey_ = {};
}

void Viewer::recordEdit(const std::string& label, const edit::EditState& before) {
    if (history_.push(label, before, edit::captureState(*scene_, settings_, selection_))) lastEditLabel_ = label;
}

void Viewer::undoRedo(bool redo) {
    if (tool_.active()) cancelTransform();
    finishPanelEdit();
    std::string label;
    const edit::EditState* s = redo ? history_.redo(&label) : history_.undo(&label);
    if (!s) {
        setStatus(redo ? "nothing to redo" : "nothing to undo");
        return;
    }
    beforeSceneEdit();
    sceneEdited(edit::applyState(*scene_, settings_, selection_, *s));
    setStatus(std::string(redo ? "redo: " : "undo: ") + label);
    lastEditLabel_ = label;
}

// ---- selection ---------------------------------------------------------------------------------------------

void Viewer::selectAt(double x, double y, bool extend) {
    const edit::ToolView v = toolView();
    const glm::vec2 p(float(x - vpX0_), float(y - vpY0_));
    int item = edit::pickLight(edit::lightIcons(*scene_, settings_, v), p, kIconPickRadius);
    if (item == -1 && renderer_->width() > 0 && renderer_->height() > 0) {
        const int px = int(p.x / v.width * float(renderer_->width())), py = int(p.y / v.height * float(renderer_->height()));
        item = renderer_->objectAt(px, py);
    }
    const edit::EditState before = edit::captureState(*scene_, settings_, selection_);
    selection_.click(item, extend);
    recordEdit("Select", before);
}

void Viewer::selectAll(bool all) {
    const edit::EditState before = edit::captureState(*scene_, settings_, selection_);
    selection_.clear();
    if (all) {
        selection_.items = edit::everything(*scene_);
        selection_.active = before.selection.active;  // Blender keeps the active object
    }
    recordEdit(all ? "Select All" : "Select None", before);
}

void Viewer::hideSelected(bool unhideAll) {
    beforeSceneEdit();
    const edit::EditState before = edit::captureState(*scene_, settings_, selection_);
    unsigned changes = 0;
    if (unhideAll) {
        for (int i = 0; i < int(scene_->nodes.size()); ++i) changes |= edit::setVisible(*scene_, i, true);
    } else {
        for (int i : selection_.items) changes |= edit::setVisible(*scene_, i, false);
    }
    sceneEdited(changes);
    recordEdit(unhideAll ? "Reveal Hidden" : "Hide", before);
}

void Viewer::toggleVisible(int node) {
    if (node < 0 || node >= int(scene_->nodes.size())) return;
    beforeSceneEdit();
    const edit::EditState before = edit::captureState(*scene_, settings_, selection_);
    sceneEdited(edit::setVisible(*scene_, node, !scene_->nodes[size_t(node)].visible));
    recordEdit(scene_->nodes[size_t(node)].visible ? "Show" : "Hide", before);
}

// ---- G / R / S ---------------------------------------------------------------------------------------------

bool Viewer::beginTransform(edit::ToolMode mode) {
    if (tool_.active()) cancelTransform();  // G during R: start over as G from where it began
    toolNodes_ = edit::transformRoots(*scene_, selection_);
    std::vector<edit::TransformTarget> targets = edit::targetsOf(*scene_, toolNodes_);
    toolSun_ = selection_.contains(edit::kDefaultSun) && scene_->lights.empty();
    if (toolSun_ && mode != edit::ToolMode::Rotate) {
        toolSun_ = false;  // the default sun is a direction only
        if (targets.empty()) {
            setStatus("the default sun has a direction only: R turns it (or drag it on the N panel's sphere)");
            return false;
        }
    }
    glm::vec3 pivot = edit::medianPoint(*scene_, toolNodes_);
    if (toolSun_) {
        edit::TransformTarget sun;
        for (const auto& icon : edit::lightIcons(*scene_, settings_, toolView()))
            if (icon.item == edit::kDefaultSun) sun.local.translation = icon.position;
        sun.local.rotation = rotationTo(defaultSunDirection(settings_));
        if (targets.empty()) pivot = sun.local.translation;
        else pivot = (pivot * float(targets.size()) + sun.local.translation) / float(targets.size() + 1);
        targets.push_back(sun);
    }
    if (targets.empty()) {
        setStatus(std::string(modeLabel(mode)) + ": nothing selected (click an object, or A for all)");
        return false;
    }
    toolBefore_ = edit::captureState(*scene_, settings_, selection_);
    tool_.begin(mode, targets, pivot, toolView(), glm::vec2(float(lastX_ - vpX0_), float(lastY_ - vpY0_)));
    return true;
}

void Viewer::applyTransform() {
    beforeSceneEdit();
    const std::vector<edit::Trs> r = tool_.current();
    unsigned changes = 0;
    if (!toolNodes_.empty()) {
        const std::vector<edit::Trs> nodes(r.begin(), r.begin() + std::ptrdiff_t(std::min(r.size(), toolNodes_.size())));
        changes |= edit::setLocals(*scene_, toolNodes_, nodes);
    }
    if (toolSun_ && r.size() > toolNodes_.size()) {
        const glm::vec2 ae = edit::sunAngles(r.back().rotation * glm::vec3(0.0f, 0.0f, -1.0f));
        settings_.sunAzimuth = ae.x;
        settings_.sunElevation = ae.y;
        changes |= unsigned(SceneChange::Lights);
    }
    sceneEdited(changes);
}

void Viewer::confirmTransform() {
    const edit::ToolMode mode = tool_.mode();
    applyTransform();
    tool_.confirm();
    recordEdit(modeLabel(mode), toolBefore_);
}

void Viewer::cancelTransform() {
    beforeSceneEdit();
    tool_.cancel();
    edit::Selection keep = selection_;
    sceneEdited(edit::applyState(*scene_, settings_, keep, toolBefore_));  // exactly as before
}

bool Viewer::editKey(int key, int mods) {
    const bool shift = mods & GLFW_MOD_SHIFT, ctrl = mods & GLFW_MOD_CONTROL, alt = mods & GLFW_MOD_ALT;
    if (tool_.active()) {
        char c = 0;
        if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) c = char('0' + key - GLFW_KEY_0);
        else if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) c = char('0' + key - GLFW_KEY_KP_0);
        else if (key == GLFW_KEY_PERIOD || key == GLFW_KEY_KP_DECIMAL) c = '.';
        else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) c = '-';
        else if (key == GLFW_KEY_SLASH || key == GLFW_KEY_KP_DIVIDE) c = '/';
        if (c) tool_.type(c);
        else if (key == GLFW_KEY_X || key == GLFW_KEY_Y || key == GLFW_KEY_Z) tool_.axis(key - GLFW_KEY_X, shift);
        else if (key == GLFW_KEY_BACKSPACE) tool_.backspace();
        else if (key == GLFW_KEY_TAB) tool_.tab();
        else if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) { confirmTransform(); return true; }
        else if (key == GLFW_KEY_ESCAPE) { cancelTransform(); return true; }
        else if (key == GLFW_KEY_G) { beginTransform(edit::ToolMode::Translate); return true; }
        else if (key == GLFW_KEY_R) { beginTransform(edit::ToolMode::Rotate); return true; }
        else if (key == GLFW_KEY_S) { beginTransform(edit::ToolMode::Scale); return true; }
        applyTransform();
        return true;  // every other key waits until the transform ends
    }
    if (ctrl && key == GLFW_KEY_Z) { undoRedo(shift); return true; }
    if (ctrl || (alt && key != GLFW_KEY_A && key != GLFW_KEY_H)) return false;
    switch (key) {
        case GLFW_KEY_G: beginTransform(edit::ToolMode::Translate); return true;
        case GLFW_KEY_R: beginTransform(edit::ToolMode::Rotate); return true;
        case GLFW_KEY_S: beginTransform(edit::ToolMode::Scale); return true;
        case GLFW_KEY_A: selectAll(!alt); return true;
        case GLFW_KEY_H: hideSelected(alt); return true;
        default: return false;
    }
}

bool Viewer::editButton(int button, int action, int mods, bool captured) {
    if (tool_.active()) {
        if (action != GLFW_PRESS) return true;
        if (button == GLFW_MOUSE_BUTTON_LEFT) confirmTransform();
        else if (button == GLFW_MOUSE_BUTTON_RIGHT) cancelTransform();
        return true;
    }
    if (action != GLFW_PRESS || button != GLFW_MOUSE_BUTTON_LEFT || captured || !inViewport(lastX_, lastY_)) return false;
    if (view_.emulate3Button && (mods & GLFW_MOD_ALT)) return false;  // Alt+left orbits
    selectAt(lastX_, lastY_, mods & (GLFW_MOD_SHIFT | GLFW_MOD_CONTROL));
    return true;
}

void Viewer::editCursor() {
    if (!tool_.active()) return;
    tool_.setView(toolView());
    tool_.pointer(glm::vec2(float(lastX_ - vpX0_), float(lastY_ - vpY0_)));
    applyTransform();
}

// ---- the Item tab ------------------------------------------------------------------------------------------

void Viewer::finishPanelEdit() {
    if (!panelEditPending_) return;
    panelEditPending_ = false;
    recordEdit(panelEditLabel_, panelEditBefore_);
}

void Viewer::drawItemTab() {
    ui::ScenePanelModel m;
    m.scene = scene_.get();
    m.selected = &selection_.items;
    m.active = selection_.active;
    m.undoSteps = history_.undoable();
    m.redoSteps = history_.size() - history_.undoable();
    m.lastUndo = lastEditLabel_;
    const bool node = m.active >= 0 && m.active < int(scene_->nodes.size());
    if (node) {
        const SceneNode& n = scene_->nodes[size_t(m.active)];
        m.hasTransform = true;
        m.location = n.local.translation;
        m.scale = n.local.scale;
        // The Euler angles the panel shows stay the ones last typed while the rotation is still theirs (a
        // quaternion has two Euler forms: re-deriving them each frame would make the fields jump while dragging).
        if (eulerNode_ != m.active || eulerQuat_ != n.local.rotation) {
            eulerNode_ = m.active;
            eulerQuat_ = n.local.rotation;
            eulerShown_ = edit::eulerDegrees(n.local.rotation);
        }
        m.rotationDegrees = eulerShown_;
        m.light = n.light;
        if (n.light >= 0 && n.light < int(scene_->lights.size())) {
            const Light& l = scene_->lights[size_t(n.light)];
            m.color = l.color;
            m.intensity = l.intensity;
            m.direction = l.direction;
        }
    } else if (m.active == edit::kDefaultSun && scene_->lights.empty()) {
        m.sun = true;
        m.intensity = settings_.sunIntensity;
        m.direction = defaultSunDirection(settings_);
    }
    const ui::ScenePanelActions a = ui::drawScenePanel(m, scenePanel_);
    auto beginPanelEdit = [&](const char* label) {
        beforeSceneEdit();
        if (panelEditPending_) return;
        panelEditPending_ = true;
        panelEditLabel_ = label;
        panelEditBefore_ = edit::captureState(*scene_, settings_, selection_);
    };
    if (a.clicked) {
        const edit::EditState before = edit::captureState(*scene_, settings_, selection_);
        selection_.click(a.click, a.extend);
        recordEdit("Select", before);
    }
    if (a.toggleVisible >= 0) toggleVisible(a.toggleVisible);
    if (a.undo) undoRedo(false);
    if (a.redo) undoRedo(true);
    if (node && a.transformEdited) {
        beginPanelEdit("Transform (N panel)");
        edit::Trs t = edit::toTrs(scene_->nodes[size_t(m.active)].local);
        t.translation = a.location;
        if (a.rotationDegrees != eulerShown_) {
            t.rotation = edit::fromEulerDegrees(a.rotationDegrees);
            eulerShown_ = a.rotationDegrees;
            eulerQuat_ = t.rotation;
        }
        for (int k = 0; k < 3; ++k)  // 0 would make the normal matrix singular: the field shows what is used
            t.scale[k] = std::abs(a.scale[k]) < 1e-4f ? (a.scale[k] < 0.0f ? -1e-4f : 1e-4f) : a.scale[k];
        sceneEdited(edit::setLocals(*scene_, {m.active}, {t}));
    }
    if (a.lightEdited) {
        beginPanelEdit("Light");
        if (m.sun) {
            settings_.sunIntensity = a.intensity;
        } else if (m.light >= 0) {
            scene_->lights[size_t(m.light)].color = glm::clamp(a.color, glm::vec3(0.0f), glm::vec3(1e6f));
            scene_->lights[size_t(m.light)].intensity = a.intensity;
        }
        sceneEdited(unsigned(SceneChange::Lights));
    }
    if (a.directionEdited) {
        beginPanelEdit("Light Direction");
        if (m.sun) {
            const glm::vec2 ae = edit::sunAngles(a.direction);
            settings_.sunAzimuth = ae.x;
            settings_.sunElevation = ae.y;
            sceneEdited(unsigned(SceneChange::Lights));
        } else if (node) {  // turn the light's node so that its -Z is the new direction
            const SceneNode& n = scene_->nodes[size_t(m.active)];
            const glm::quat q = edit::rotationBetween(m.direction, a.direction);
            const glm::quat qp = n.parent >= 0 ? edit::rotationOf(scene_->nodes[size_t(n.parent)].world) : glm::quat(1, 0, 0, 0);
            edit::Trs t = edit::toTrs(n.local);
            t.rotation = glm::normalize(glm::inverse(qp) * q * qp * t.rotation);
            sceneEdited(edit::setLocals(*scene_, {m.active}, {t}));
        }
    }
    if (panelEditPending_ && !ImGui::IsAnyItemActive()) finishPanelEdit();
}

// ---- over the viewport -------------------------------------------------------------------------------------

void Viewer::updateOutline() {
    if (selection_.items.empty() || !renderer_->textures().has("Object ID") || renderer_->frameIndex() == 0) {
        outlineKey_ = {};
        return;
    }
    OutlineKey key{renderer_->frameIndex(), selection_.items, selection_.active};
    if (key == outlineKey_ && outlineTex_) return;
    outlineKey_ = key;
    FloatImage ids;
    try {
        ids = renderer_->readLayer("Object ID 1", 0, false);
    } catch (const std::exception&) {
        return;
    }
    const int w = ids.width, h = ids.height;
    if (w <= 0 || h <= 0) return;
    // 0 = not selected, 1 = selected, 2 = the active object.
    std::vector<uint8_t> sel(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int node = int(ids.at(x, y, 0)) - 1;
            if (node >= 0 && selection_.contains(node)) sel[size_t(y) * w + x] = node == selection_.active ? 2 : 1;
        }
    // An outline: selected pixels with an unselected (or differently selected) pixel within 1 px, plus that ring.
    std::vector<uint8_t> rgba(size_t(w) * h * 4, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint8_t s = sel[size_t(y) * w + x];
            uint8_t edge = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
                    const uint8_t o = sel[size_t(yy) * w + xx];
                    if (o != s) edge = std::max(edge, std::max(o, s));
                }
            if (!edge) continue;
            uint8_t* p = &rgba[((size_t(h - 1 - y)) * w + x) * 4];  // GL rows bottom-up
            const bool active = edge == 2;
            p[0] = 255, p[1] = active ? 170 : 110, p[2] = active ? 60 : 20, p[3] = 255;
        }
    if (!outlineTex_ || outlineW_ != w || outlineH_ != h) {
        outlineTex_ = gl::createTexture(GL_TEXTURE_2D, "selection outline");
        glTextureStorage2D(outlineTex_.id(), 1, GL_RGBA8, w, h);
        glTextureParameteri(outlineTex_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(outlineTex_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        outlineW_ = w;
        outlineH_ = h;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(outlineTex_.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    outlinePixels_ = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) outlinePixels_ += rgba[i + 3] != 0;
}

void Viewer::drawEditOverlay() {
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    updateOutline();
    if (!selection_.items.empty() && outlineTex_ && view_.pathTrace != ui::PathTraceMode::Full)
        ImGui::GetBackgroundDrawList()->AddImage((ImTextureID)(intptr_t)outlineTex_.id(), ImVec2(vpX0_, vpY0_), ImVec2(vpX1_, vpY1_),
                                                 ImVec2(0, 1), ImVec2(1, 0));
    // The lights: a disc per light at its place (the default sun beyond the scene, towards it), a line along its
    // direction for suns and spots; white ring when selected.
    const edit::ToolView v = toolView();
    dl->PushClipRect(ImVec2(vpX0_, vpY0_), ImVec2(vpX1_, vpY1_), true);
    for (const auto& icon : edit::lightIcons(*scene_, settings_, v)) {
        if (!icon.onScreen) continue;
        const ImVec2 c(vpX0_ + icon.screen.x, vpY0_ + icon.screen.y);
        const bool sel = selection_.contains(icon.item);
        const ImU32 col = icon.type == LightType::Directional ? IM_COL32(255, 200, 60, 255) : IM_COL32(255, 240, 150, 255);
        if (icon.type != LightType::Point) {
            glm::vec2 tip = icon.screen;
            const float len = std::max(scene_->bounds.radius(), 0.5f) * 0.25f;
            edit::projectToView(v, icon.position + icon.direction * len, tip);  // off screen is fine: clipped
            dl->AddLine(c, ImVec2(vpX0_ + tip.x, vpY0_ + tip.y), col, 2.0f);
        }
        dl->AddCircleFilled(c, 6.0f, IM_COL32(0, 0, 0, 160), 16);
        dl->AddCircleFilled(c, 4.5f, col, 16);
        if (sel) dl->AddCircle(c, 8.5f, selection_.active == icon.item ? IM_COL32(255, 255, 255, 255) : IM_COL32(255, 140, 40, 255), 16, 2.0f);
    }
    dl->PopClipRect();
    if (tool_.active()) {
        const std::string h = tool_.header();
        const float y = vpY0_ + 6 + 2 * ImGui::GetTextLineHeightWithSpacing();
        dl->AddText(ImVec2(vpX0_ + 9, y + 1), IM_COL32(0, 0, 0, 200), h.c_str());
        dl->AddText(ImVec2(vpX0_ + 8, y), IM_COL32(255, 255, 255, 255), h.c_str());
    }
}

// ---- timeline, save ----------------------------------------------------------------------------------------

void Viewer::advanceAnimation(double dt) {
    if (scene_->animations.empty() || !playing_) return;
    const float duration = scene_->animationDuration();
    animTime_ = duration > 0.0f ? std::fmod(animTime_ + float(dt), duration) : 0.0f;
    applyAnimationNow();
}

void Viewer::applyAnimationNow() {
    beforeSceneEdit();
    applyAnimation(*scene_, animTime_);
    sceneEdited(unsigned(SceneChange::Transforms) | unsigned(SceneChange::Lights));
}

void Viewer::drawTimeline() {
    if (scene_->animations.empty()) return;
    const float h = ImGui::GetFrameHeightWithSpacing() + 10.0f;
    ImGui::SetNextWindowPos(ImVec2(vpX0_ + 8.0f, vpY1_ - h - 30.0f));
    ImGui::SetNextWindowSize(ImVec2(std::max(vpX1_ - vpX0_ - 16.0f, 120.0f), h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing;
    ImGui::SetNextWindowBgAlpha(0.75f);
    if (ImGui::Begin("##timeline", nullptr, flags)) {
        if (ImGui::Button(playing_ ? "Pause" : "Play", ImVec2(50.0f, 0.0f))) playing_ = !playing_;
        ImGui::SameLine();
        ImGui::SetNextItemWidth(-1.0f);
        float t = animTime_;
        const float duration = scene_->animationDuration();
        if (ImGui::SliderFloat("##time", &t, 0.0f, duration, "%.2f s") && t != animTime_) {
            animTime_ = std::clamp(t, 0.0f, duration);
            applyAnimationNow();
        }
    }
    ImGui::End();
}

std::string Viewer::saveScene(const std::string& path) {
    if (path.empty()) return "Save As: give a file name (.gltf or .glb)";
    try {
        saveGltf(*scene_, path);
        return "saved " + path;
    } catch (const std::exception& e) {
        return std::string("Save As failed: ") + e.what();
    }
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
