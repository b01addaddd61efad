// The viewer's input: Blender-style mouse and keys over the viewport, fly mode, and the script's pointer.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace deepgi {

// ---- input -------------------------------------------------------------------------------------------------

namespace {
// The fly keys, as bits of Viewer::flyHeld_ / flyPressed_.
constexpr int kFlyKeys[] = {GLFW_KEY_W, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_A, GLFW_KEY_E, GLFW_KEY_Q};
int flyBit(int key) {
    for (int i = 0; i < 6; ++i)
        if (kFlyKeys[i] == key) return 1 << i;
    return 0;
}
}  // namespace

void Viewer::handleInput() {
    // Events queued since the last frame (GLFW callbacks during glfwPollEvents, the script's keys and drags), in
    // order: a key pressed and released between two frames is handled like any other.
    while (!input_.empty()) {
        const InputEvent e = input_.front();
        input_.pop_front();
        ++inputEvents_;
        // Real input the panels take (pointer over a window, a text field typing) is UI input: see frame().
        if (!e.fromScript && imguiReady_)
            uiInput_ = uiInput_ || (e.kind == InputEvent::Kind::Key ? ImGui::GetIO().WantCaptureKeyboard : ImGui::GetIO().WantCaptureMouse);
        switch (e.kind) {
            case InputEvent::Kind::Button: onMouseButton(e.code, e.action, e.mods, e.fromScript); break;
            case InputEvent::Kind::Cursor: onCursor(e.x, e.y, e.fromScript); break;
            case InputEvent::Kind::Scroll: onScroll(e.y, e.fromScript); break;
            case InputEvent::Kind::Key: onKey(e.code, e.action, e.mods, e.fromScript); break;
        }
    }
}

void Viewer::onMouseButton(int button, int action, int mods, bool fromScript) {
    const bool captured = !fromScript && imguiReady_ && ImGui::GetIO().WantCaptureMouse;
    if (view_.flyMode) {
        if (action == GLFW_PRESS && button == GLFW_MOUSE_BUTTON_LEFT) {  // confirm
            view_.flyMode = false;
            glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
        } else if (action == GLFW_PRESS && button == GLFW_MOUSE_BUTTON_RIGHT) {  // cancel
            view_.flyMode = false;
            ctl_ = flySaved_;
            glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
        }
        return;
    }
    if (editButton(button, action, mods, captured)) return;  // selection, confirming or cancelling a transform
    if (action == GLFW_RELEASE) {
        if (button == GLFW_MOUSE_BUTTON_MIDDLE || button == GLFW_MOUSE_BUTTON_LEFT) drag_ = Drag::None;
        return;
    }
    const bool middle = button == GLFW_MOUSE_BUTTON_MIDDLE ||
                        (view_.emulate3Button && button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_ALT));
    if (!middle || captured || !inViewport(lastX_, lastY_)) return;
    drag_ = (mods & GLFW_MOD_SHIFT) ? Drag::Pan : (mods & GLFW_MOD_CONTROL) ? Drag::Zoom : Drag::Orbit;
}

void Viewer::onCursor(double x, double y, bool fromScript) {
    const double dx = x - lastX_, dy = y - lastY_;
    lastX_ = x;
    lastY_ = y;
    if (view_.flyMode) {
        ctl_.look(float(dx), float(dy));
        return;
    }
    if (tool_.active()) {  // G / R / S follow the pointer
        editCursor();
        return;
    }
    switch (drag_) {
        case Drag::Orbit: ctl_.orbit(float(dx), float(dy)); break;
        case Drag::Pan: ctl_.pan(float(dx), float(dy), vpY1_ - vpY0_); break;
        case Drag::Zoom: ctl_.zoomDrag(float(dy)); break;
        case Drag::None: return;
    }
    if (view_.viewName.rfind("User", 0) != 0) view_.viewName = ctl_.perspective ? "User Perspective" : "User Orthographic";
}

void Viewer::onScroll(double dy, bool fromScript) {
    if (!fromScript && imguiReady_ && ImGui::GetIO().WantCaptureMouse) return;
    if (view_.flyMode) {
        flySpeed_ *= float(std::pow(1.25, dy));
        setStatus("fly speed " + std::to_string(flySpeed_));
        return;
    }
    ctl_.zoomSteps(float(dy));
}

void Viewer::onKey(int key, int action, int mods, bool fromScript) {
    if (view_.flyMode && flyBit(key)) {  // held from press to release; a press always moves at least one frame
        if (action == GLFW_PRESS) flyHeld_ |= unsigned(flyBit(key)), flyPressed_ |= unsigned(flyBit(key));
        if (action == GLFW_RELEASE) flyHeld_ &= ~unsigned(flyBit(key));
    }
    if (action != GLFW_PRESS) return;
    ++keyPresses_;
    if (!fromScript && imguiReady_ && ImGui::GetIO().WantCaptureKeyboard) return;
    const bool ctrl = mods & GLFW_MOD_CONTROL, shift = mods & GLFW_MOD_SHIFT;
    if (view_.flyMode) {
        if (key == GLFW_KEY_ESCAPE) { ctl_ = flySaved_; view_.flyMode = false; }
        if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) view_.flyMode = false;
        if (!view_.flyMode) glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
        return;
    }
    if (editKey(key, mods)) return;  // G / R / S and their modal keys, A / Alt+A, H / Alt+H, Ctrl+Z / Shift+Ctrl+Z
    const char* proj = ctl_.perspective ? " Perspective" : " Orthographic";
    using AV = CameraController::AxisView;
    switch (key) {
        case GLFW_KEY_KP_1: ctl_.setAxisView(ctrl ? AV::Back : AV::Front); view_.viewName = std::string(ctrl ? "Back" : "Front") + proj; cut(); break;
        case GLFW_KEY_KP_3: ctl_.setAxisView(ctrl ? AV::Left : AV::Right); view_.viewName = std::string(ctrl ? "Left" : "Right") + proj; cut(); break;
        case GLFW_KEY_KP_7: ctl_.setAxisView(ctrl ? AV::Bottom : AV::Top); view_.viewName = std::string(ctrl ? "Bottom" : "Top") + proj; cut(); break;
        case GLFW_KEY_KP_5:
            ctl_.togglePerspective();
            view_.viewName = ctl_.perspective ? "User Perspective" : "User Orthographic";
            cut();
            break;
        case GLFW_KEY_KP_0: useSceneCamera(0); break;
        case GLFW_KEY_HOME: ctl_.frame(scene_->bounds); cut(); break;
        case GLFW_KEY_GRAVE_ACCENT:
            if (shift) {
                flySaved_ = ctl_;
                view_.flyMode = true;
                if (!fromScript) glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_DISABLED);
                setStatus("Fly: mouse looks, WASD move, Q/E down/up, wheel speed; click/Enter confirm, Esc/right-click cancel");
            }
            break;
        case GLFW_KEY_F5: {
            const int n = renderer_->shaders().reloadAll();
            setStatus("reloaded " + std::to_string(n) + " shader programs");
            needRender_ = true;
            break;
        }
        case GLFW_KEY_F12: capture(); break;
        case GLFW_KEY_N: view_.sidebar = !view_.sidebar; break;
        case GLFW_KEY_I: inspector_.open = !inspector_.open; break;
        default: break;
    }
}

void Viewer::updateFly(double dt) {
    const unsigned keys = flyHeld_ | flyPressed_;
    flyPressed_ = 0;
    if (!view_.flyMode) {
        flyHeld_ = 0;
        return;
    }
    glm::vec3 d(0.0f);
    auto down = [&](int k) { return (keys & unsigned(flyBit(k))) != 0; };
    if (down(GLFW_KEY_W)) d.z += 1.0f;
    if (down(GLFW_KEY_S)) d.z -= 1.0f;
    if (down(GLFW_KEY_D)) d.x += 1.0f;
    if (down(GLFW_KEY_A)) d.x -= 1.0f;
    if (down(GLFW_KEY_E)) d.y += 1.0f;
    if (down(GLFW_KEY_Q)) d.y -= 1.0f;
    float speed = flySpeed_ * float(dt);
    if (glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS) speed *= 4.0f;
    if (glfwGetKey(window_, GLFW_KEY_LEFT_ALT) == GLFW_PRESS) speed *= 0.25f;
    if (d != glm::vec3(0.0f)) ctl_.moveEye(d * speed);
}

// ---- the script's pointer ----------------------------------------------------------------------------------
// Under --script the UI's pointer is the script's (Xvfb's real one sits mid-screen): hover/click reach any window,
// and the wheel goes to whatever is under its position, as a real wheel would.

void Viewer::applyScriptPointer() {
    if (!script_.active()) return;
    ImGuiIO& io = ImGui::GetIO();
    if (!uiDrag_.empty()) {
        scriptPointerSet_ = true;
        scriptPointerAt_ = uiDrag_.front().first;
        scriptButtons_[0] = uiDrag_.front().second;
        uiDrag_.pop_front();
    }
    io.MousePos = scriptPointerSet_ ? ImVec2(float(scriptPointerAt_.x), float(scriptPointerAt_.y)) : ImVec2(-FLT_MAX, -FLT_MAX);
    for (int i = 0; i < 3; ++i) io.MouseDown[i] = scriptButtons_[i];
    if (scriptWheel_ != 0.0) {
        io.MousePos = ImVec2(float(scriptWheelAt_.x), float(scriptWheelAt_.y));
        io.MouseWheel += float(scriptWheel_);
    }
}

void Viewer::routeScriptWheel() {
    if (scriptWheel_ == 0.0) return;
    // ImGui's NewFrame has found the window under the pointer: if none, the wheel is the viewport's.
    if (!ImGui::GetIO().WantCaptureMouse && inViewport(scriptWheelAt_.x, scriptWheelAt_.y)) onScroll(scriptWheel_, true);
    scriptWheel_ = 0.0;
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
