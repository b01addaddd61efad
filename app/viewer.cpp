// The viewer: GLFW window and GL context, main loop, Blender-style input, hot reload, screenshots, scripts and
// the state file. Panels are drawn by ui/; the renderer draws into its own textures.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer.h"

#include "app/camera_controller.h"
#include "app/options.h"
#include "app/viewer_script.h"
#include "renderer/core/image_io.h"
#include "renderer/passes/buffer_view_pass.h"
#include "renderer/renderer.h"
#include "renderer/scene/gltf_loader.h"
#include "ui/viewer_ui.h"

#include <glad/gl.h>
// glad first: GLFW must not pull in the system GL header.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>

namespace fs = std::filesystem;

namespace deepgi {

std::string viewerStatePath() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    if (xdg && *xdg) return std::string(xdg) + "/deepgi/viewer.json";
    const char* home = std::getenv("HOME");
    return std::string(home && *home ? home : ".") + "/.config/deepgi/viewer.json";
}

namespace {

double nowSeconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string fileNameFor(const std::string& layer) {
    std::string s;
    for (char c : layer) s += (c == ' ') ? '_' : char(std::tolower((unsigned char)c));
    return s;
}

enum class Drag { None, Orbit, Pan, Zoom };

class Viewer : public ui::ViewerServices {
public:
    explicit Viewer(const ViewerOptions& o) : opt_(o) {}
    ~Viewer() override;
    int run();

    // ViewerServices
    std::vector<std::string> bufferNames() override;
    BufferSource source(const std::string& name, int level) override;
    GLuint drawView(int slot, const BufferSource& a, const BufferSource* b, const BufferViewParams& p, int w, int h) override;
    TexelBlock readTexels(const BufferSource& s, int x, int y, int w, int h) override {
        return BufferViewPass::readTexels(s, x, y, w, h);
    }
    ui::BufferStats stats(const std::string& name, int level) override;
    std::string loadReference(const std::string& path) override;
    const Camera& camera() const override { return renderer_->camera(); }

    // Input, from GLFW callbacks or the script (fromScript bypasses ImGui's capture flags).
    void onMouseButton(int button, int action, int mods, bool fromScript);
    void onCursor(double x, double y, bool fromScript);
    void onScroll(double dy, bool fromScript);
    void onKey(int key, int action, int mods, bool fromScript);

private:
    bool init();
    void loadState();
    void saveState();
    void frame();
    void drawUi();
    void drawSidebar(float x0, float height);
    void runScript();
    void updateFly(double dt);
    void cut() { renderer_->resetHistory(); }
    void useSceneCamera(int index);
    bool inViewport(double x, double y) const {
        return x >= vpX0_ && x < vpX1_ && y >= vpY0_ && y < vpY1_;
    }
    void capture();
    void writeWindowPng(const std::string& path);
    void setStatus(const std::string& s) { view_.status = s; statusTime_ = nowSeconds(); }

    ViewerOptions opt_;
    GLFWwindow* window_ = nullptr;
    bool imguiReady_ = false;
    std::unique_ptr<Renderer> renderer_;
    std::shared_ptr<Scene> scene_;
    std::unique_ptr<BufferViewPass> views_[2];
    Settings settings_;
    CameraController ctl_, flySaved_;
    std::string iniPath_;
    std::string restoredScene_;

    ui::ViewportState view_;
    ui::SettingsPanelState settingsPanel_;
    ui::ProfilerState profiler_;
    ui::InspectorState inspector_;
    bool captureBuffers_ = false;
    std::string lastCapture_;
    std::string selectTab_;  // sidebar tab to bring to front (script "panel")
    double statusTime_ = 0.0;

    // Layout (window units) of the previous frame.
    float vpX0_ = 0, vpY0_ = 0, vpX1_ = 1, vpY1_ = 1, headerH_ = 30.0f;
    // Mouse drag state.
    Drag drag_ = Drag::None;
    double lastX_ = 0, lastY_ = 0;
    bool leftLook_ = false;
    float flySpeed_ = 1.0f;
    // Shader reload / errors.
    double lastPoll_ = 0.0;
    std::string renderError_;
    // Reference image for A/B.
    gl::TextureHandle refTex_;
    FloatImage refImage_;
    // Script.
    std::vector<ScriptAction> script_;
    size_t pc_ = 0;
    int waitFrames_ = 0;
    double sleepUntil_ = 0.0;
    std::string pendingShot_;
    bool scriptFailed_ = false;
    bool quit_ = false;
    double lastFrameTime_ = 0.0;
};

Viewer::~Viewer() {
    // GL objects die with the context: release them first.
    views_[0].reset();
    views_[1].reset();
    refTex_.reset();
    renderer_.reset();
    if (imguiReady_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
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
        captureBuffers_ = j.value("capture_buffers", captureBuffers_);
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
                        {"capture_buffers", captureBuffers_}};
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

// ---- setup -------------------------------------------------------------------------------------------------

Viewer* self(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

bool Viewer::init() {
    settings_ = opt_.settings;
    loadState();
    if (!opt_.scriptPath.empty()) script_ = parseViewerScript(opt_.scriptPath);  // fail before opening a window

    glfwSetErrorCallback([](int code, const char* msg) { std::fprintf(stderr, "deepgi view: GLFW error %d: %s\n", code, msg); });
    if (!glfwInit()) {
        std::fprintf(stderr, "deepgi view needs a display; use deepgi render for headless\n");
        return false;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    window_ = glfwCreateWindow(opt_.width, opt_.height, "deepgi view", nullptr, nullptr);
    if (!window_) {
        std::fprintf(stderr, "deepgi view: cannot create an OpenGL 4.5 core window\n");
        return false;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    if (!gladLoadGL(glfwGetProcAddress)) {
        std::fprintf(stderr, "deepgi view: cannot load OpenGL functions\n");
        return false;
    }
    glClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);  // raw SNORM/float readbacks

    // Our callbacks first: the ImGui backend chains to them.
    glfwSetWindowUserPointer(window_, this);
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int b, int a, int m) { self(w)->onMouseButton(b, a, m, false); });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { self(w)->onCursor(x, y, false); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { self(w)->onScroll(dy, false); });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int k, int, int a, int m) { self(w)->onKey(k, a, m, false); });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    iniPath_ = (fs::path(viewerStatePath()).parent_path() / "imgui.ini").string();
    io.IniFilename = opt_.fresh ? nullptr : iniPath_.c_str();
    if (!opt_.fresh) {
        std::error_code ec;
        fs::create_directories(fs::path(iniPath_).parent_path(), ec);
    }
    ImGui::StyleColorsDark();
    ImGuiStyle& st = ImGui::GetStyle();
    st.WindowRounding = 3.0f;
    st.FrameRounding = 2.0f;
    st.GrabRounding = 2.0f;
    st.FramePadding = ImVec2(5.0f, 3.0f);
    st.ItemSpacing = ImVec2(6.0f, 4.0f);
    st.WindowBorderSize = 1.0f;
    // A script drives the viewport itself; the real pointer (Xvfb's sits mid-screen) must not hover the panels.
    if (!script_.empty()) io.ConfigFlags |= ImGuiConfigFlags_NoMouse;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    imguiReady_ = true;

    RendererOptions ro;
    if (!opt_.shaderDir.empty()) ro.shaderDir = opt_.shaderDir;
    // GPU timer queries where they are reliable; llvmpipe's miss vertex work and bin draws (platform.md).
    const char* glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool software = glRenderer && (std::strstr(glRenderer, "llvmpipe") || std::strstr(glRenderer, "softpipe"));
    ro.timing = software ? TimingMode::WallClock : TimingMode::GpuQueries;
    renderer_ = std::make_unique<Renderer>(ro);
    views_[0] = std::make_unique<BufferViewPass>();
    views_[1] = std::make_unique<BufferViewPass>();

    scene_ = std::make_shared<Scene>(loadGltf(opt_.scenePath));
    for (const auto& w : scene_->warnings) std::fprintf(stderr, "deepgi view: warning: %s\n", w.c_str());
    renderer_->setScene(scene_);
    for (const auto& c : scene_->cameras) view_.cameraNames.push_back(c.name);
    const bool sameScene = !restoredScene_.empty() && fs::exists(restoredScene_) && fs::exists(scene_->sourcePath) &&
                           fs::equivalent(restoredScene_, scene_->sourcePath);
    if (!opt_.camera.empty()) {
        Camera c = selectCamera(*scene_, opt_.camera);
        ctl_.setFromCamera(c, glm::length(scene_->bounds.center() - c.position()));
        view_.viewName = "Camera: " + opt_.camera;
    } else if (!sameScene) {
        useSceneCamera(0);
    }
    flySpeed_ = std::max(scene_->bounds.radius() * 0.5f, 0.1f);
    lastFrameTime_ = nowSeconds();
    return true;
}

void Viewer::useSceneCamera(int index) {
    Camera c = scene_->cameras.empty() || index < 0 || index >= int(scene_->cameras.size())
                   ? framingCamera(scene_->bounds)
                   : cameraFromDesc(scene_->cameras[size_t(index)], scene_->bounds);
    // Pivot: the scene centre's distance along the view, so orbiting turns about the middle of the scene.
    const float d = glm::dot(scene_->bounds.center() - c.position(), c.forward());
    ctl_.setFromCamera(c, d > 1e-3f ? d : std::max(scene_->bounds.radius(), 1.0f));
    view_.viewName = "Camera: " + (c.name.empty() ? std::string("framing") : c.name);
    cut();
}

// ---- services ----------------------------------------------------------------------------------------------

std::vector<std::string> Viewer::bufferNames() {
    std::vector<std::string> n = renderer_->textures().layerNames();
    if (refTex_) n.push_back(ui::kReferenceName);
    return n;
}

BufferSource Viewer::source(const std::string& name, int level) {
    if (name == ui::kReferenceName) {
        BufferSource s;
        if (!refTex_) return s;
        s.texture = refTex_.id();
        s.format = GL_RGBA32F;
        s.width = refImage_.width;
        s.height = refImage_.height;
        s.vis = Visualize::Radiance;
        return s;
    }
    return bufferSource(renderer_->textures(), name, level);
}

GLuint Viewer::drawView(int slot, const BufferSource& a, const BufferSource* b, const BufferViewParams& p, int w, int h) {
    BufferViewPass& v = *views_[slot == 0 ? 0 : 1];
    try {
        v.draw(renderer_->shaders(), a, b, p, w, h);
    } catch (const std::exception& e) {
        renderError_ = e.what();
    }
    return v.texture();
}

ui::BufferStats Viewer::stats(const std::string& name, int level) {
    if (name == ui::kReferenceName) return ui::computeStats(refImage_);
    try {
        return ui::computeStats(renderer_->readLayer(name, level, false));
    } catch (const std::exception&) {
        return {};
    }
}

std::string Viewer::loadReference(const std::string& path) {
    try {
        FloatImage img = readImage(path);
        FloatImage rgba{img.width, img.height, 4, {}};
        rgba.pixels.resize(size_t(img.width) * img.height * 4);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                for (int c = 0; c < 4; ++c) {
                    const float v = c < img.channels ? img.at(x, y, c) : (c == 3 ? 1.0f : img.channels == 1 ? img.at(x, y, 0) : 0.0f);
                    rgba.pixels[(size_t(img.height - 1 - y) * img.width + x) * 4 + c] = v;  // GL rows bottom-up
                }
        refTex_ = gl::createTexture(GL_TEXTURE_2D, "reference image");
        glTextureStorage2D(refTex_.id(), 1, GL_RGBA32F, img.width, img.height);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(refTex_.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, rgba.pixels.data());
        refImage_ = std::move(img);
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

// ---- input -------------------------------------------------------------------------------------------------

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
    if (action != GLFW_PRESS) return;
    if (!fromScript && imguiReady_ && ImGui::GetIO().WantCaptureKeyboard) return;
    const bool ctrl = mods & GLFW_MOD_CONTROL, shift = mods & GLFW_MOD_SHIFT;
    if (view_.flyMode) {
        if (key == GLFW_KEY_ESCAPE) { ctl_ = flySaved_; view_.flyMode = false; }
        if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) view_.flyMode = false;
        if (!view_.flyMode) glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
        return;
    }
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
            break;
        }
        case GLFW_KEY_F12: capture(); break;
        case GLFW_KEY_N: view_.sidebar = !view_.sidebar; break;
        case GLFW_KEY_I: inspector_.open = !inspector_.open; break;
        default: break;
    }
}

void Viewer::updateFly(double dt) {
    if (!view_.flyMode) return;
    glm::vec3 d(0.0f);
    auto down = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS; };
    if (down(GLFW_KEY_W)) d.z += 1.0f;
    if (down(GLFW_KEY_S)) d.z -= 1.0f;
    if (down(GLFW_KEY_D)) d.x += 1.0f;
    if (down(GLFW_KEY_A)) d.x -= 1.0f;
    if (down(GLFW_KEY_E)) d.y += 1.0f;
    if (down(GLFW_KEY_Q)) d.y -= 1.0f;
    float speed = flySpeed_ * float(dt);
    if (down(GLFW_KEY_LEFT_SHIFT)) speed *= 4.0f;
    if (down(GLFW_KEY_LEFT_ALT)) speed *= 0.25f;
    if (d != glm::vec3(0.0f)) ctl_.moveEye(d * speed);
}

// ---- screenshots -------------------------------------------------------------------------------------------

void Viewer::capture() {
    if (renderer_->width() <= 0 || !renderer_->textures().has("Final Display")) {
        setStatus("nothing rendered yet: no screenshot");
        return;
    }
    char stamp[64];
    const std::time_t t = std::time(nullptr);
    std::strftime(stamp, sizeof(stamp), "%Y-%m-%d_%H-%M-%S", std::localtime(&t));
    fs::path dir = fs::path(opt_.screenshotDir) / stamp;
    for (int i = 2; fs::exists(dir); ++i) dir = fs::path(opt_.screenshotDir) / (std::string(stamp) + "_" + std::to_string(i));
    try {
        fs::create_directories(dir);
        const auto& e = renderer_->textures().entry("Final Display");
        writePng8((dir / "final.png").string(), e.width, e.height, 4, renderer_->readDisplay());
        int n = 0;
        if (captureBuffers_)
            for (const auto& name : renderer_->textures().layerNames()) {
                writeExr((dir / (fileNameFor(name) + ".exr")).string(), renderer_->readLayer(name, 0, false));
                ++n;
            }
        saveSettingsFile(settings_, (dir / "settings.json").string());
        std::ofstream((dir / "camera.json").string()) << ctl_.toJson().dump(2) << "\n";
        lastCapture_ = fs::absolute(dir).string();
        setStatus("saved " + lastCapture_ + (n ? " (final.png, " + std::to_string(n) + " EXR buffers, settings.json)" : " (final.png, settings.json)"));
        std::printf("deepgi view: screenshot %s\n", lastCapture_.c_str());
    } catch (const std::exception& ex) {
        setStatus(std::string("screenshot failed: ") + ex.what());
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

// ---- script ------------------------------------------------------------------------------------------------

void Viewer::runScript() {
    if (script_.empty() && opt_.scriptPath.empty()) return;
    if (waitFrames_ > 0) { --waitFrames_; return; }
    if (nowSeconds() < sleepUntil_) return;
    while (pc_ < script_.size()) {
        const ScriptAction& a = script_[pc_++];
        const std::string where = opt_.scriptPath + ":" + std::to_string(a.line) + ": ";
        auto mods = [&](size_t from) {
            int m = 0;
            for (size_t i = from; i < a.args.size(); ++i) {
                if (a.args[i] == "shift") m |= GLFW_MOD_SHIFT;
                else if (a.args[i] == "ctrl") m |= GLFW_MOD_CONTROL;
                else if (a.args[i] == "alt") m |= GLFW_MOD_ALT;
            }
            return m;
        };
        try {
            if (a.verb == "wait") { waitFrames_ = std::max(0, std::stoi(a.args[0]) - 1); return; }
            if (a.verb == "sleep") { sleepUntil_ = nowSeconds() + std::stod(a.args[0]); return; }
            if (a.verb == "key") {
                const int k = glfwKeyFromName(a.args[0]);
                onKey(k, GLFW_PRESS, mods(1), true);
                onKey(k, GLFW_RELEASE, mods(1), true);
            } else if (a.verb == "drag") {
                const int button = a.args[0] == "left" ? GLFW_MOUSE_BUTTON_LEFT : a.args[0] == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE : GLFW_MOUSE_BUTTON_RIGHT;
                const double x0 = std::stod(a.args[1]), y0 = std::stod(a.args[2]), x1 = std::stod(a.args[3]), y1 = std::stod(a.args[4]);
                const int m = mods(5);
                onCursor(x0, y0, true);
                onMouseButton(button, GLFW_PRESS, m, true);
                for (int i = 1; i <= 8; ++i) onCursor(x0 + (x1 - x0) * i / 8.0, y0 + (y1 - y0) * i / 8.0, true);
                onMouseButton(button, GLFW_RELEASE, m, true);
            } else if (a.verb == "scroll") {
                onScroll(std::stod(a.args[0]), true);
            } else if (a.verb == "set") {
                applyAssignment(settings_, a.args[0]);
            } else if (a.verb == "show" || a.verb == "inspect") {
                const auto names = bufferNames();
                if (std::find(names.begin(), names.end(), a.args[0]) == names.end())
                    throw std::runtime_error("no buffer named '" + a.args[0] + "' in the current pipeline");
                if (a.verb == "show") view_.buffer = a.args[0];
                else { inspector_.open = true; inspector_.a = a.args[0]; inspector_.zoom = 0.0f; }
                if (a.verb == "inspect" && a.args.size() > 1) {
                    if (std::find(names.begin(), names.end(), a.args[1]) == names.end())
                        throw std::runtime_error("no buffer named '" + a.args[1] + "' for B");
                    inspector_.b = a.args[1];
                }
            } else if (a.verb == "reference") {
                const std::string err = loadReference(a.args[0]);
                if (!err.empty()) throw std::runtime_error(err);
            } else if (a.verb == "camera") {
                auto it = std::find(view_.cameraNames.begin(), view_.cameraNames.end(), a.args[0]);
                if (it == view_.cameraNames.end()) throw std::runtime_error("no camera named '" + a.args[0] + "'");
                useSceneCamera(int(it - view_.cameraNames.begin()));
            } else if (a.verb == "screenshot") {
                pendingShot_ = a.args[0];
                return;  // taken at the end of this frame
            } else if (a.verb == "panel") {
                if (a.args[0] != "settings" && a.args[0] != "profiler" && a.args[0] != "view")
                    throw std::runtime_error("panel must be settings, profiler or view");
                view_.sidebar = true;
                selectTab_ = a.args[0];
            } else if (a.verb == "resize") {
                int w = 0, h = 0;
                parseSize(a.args[0], w, h);
                glfwSetWindowSize(window_, w, h);
            } else if (a.verb == "capture") {
                capture();
            } else if (a.verb == "shell") {
                const int rc = std::system(a.args[0].c_str());
                if (rc != 0) std::fprintf(stderr, "deepgi view: %sshell command returned %d\n", where.c_str(), rc);
            } else if (a.verb == "dump_errors") {
                std::ofstream out(a.args[0]);
                for (const auto& e : renderer_->shaders().errors()) out << e << "\n";
                if (!renderError_.empty()) out << renderError_ << "\n";
            } else if (a.verb == "reload") {
                renderer_->shaders().reloadAll();
            } else if (a.verb == "converge") {
                for (int i = 0, n = std::stoi(a.args[0]); i < n; ++i) renderer_->render(settings_);
            } else if (a.verb == "quit") {
                quit_ = true;
                return;
            }
        } catch (const std::exception& e) {
            std::fprintf(stderr, "deepgi view: %s%s\n", where.c_str(), e.what());
            scriptFailed_ = true;
            quit_ = true;
            return;
        }
    }
    quit_ = true;  // end of the script
}

// ---- frame -------------------------------------------------------------------------------------------------

void Viewer::frame() {
    const double t = nowSeconds();
    const double dt = std::min(t - lastFrameTime_, 0.25);
    lastFrameTime_ = t;

    // Hot reload: poll the mtimes of every file the programs used, twice a second.
    if (t - lastPoll_ > 0.5) {
        lastPoll_ = t;
        const int n = renderer_->shaders().reloadChanged();
        if (n > 0) {
            setStatus("reloaded " + std::to_string(n) + " shader program(s)");
            renderError_.clear();
        }
    }
    runScript();
    updateFly(dt);

    int fbw = 0, fbh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    glfwGetWindowSize(window_, &ww, &wh);
    if (fbw <= 0 || fbh <= 0 || ww <= 0 || wh <= 0) {  // minimised
        renderer_->resize(0, 0);
        return;
    }
    const float scaleX = float(fbw) / float(ww), scaleY = float(fbh) / float(wh);
    const float sidebarW = view_.sidebar ? std::clamp(float(ww) * 0.3f, 280.0f, 420.0f) : 0.0f;
    vpX0_ = 0.0f;
    vpX1_ = std::max(float(ww) - sidebarW, 1.0f);
    vpY0_ = headerH_;
    vpY1_ = float(wh);
    const int rw = std::max(1, int((vpX1_ - vpX0_) * scaleX * view_.resolutionScale));
    const int rh = std::max(1, int((vpY1_ - vpY0_) * scaleY * view_.resolutionScale));

    renderer_->resize(rw, rh);
    renderer_->setCamera(ctl_.camera(scene_->bounds));
    const double r0 = nowSeconds();
    try {
        renderer_->render(settings_);
        if (renderer_->shaders().errors().empty()) renderError_.clear();
    } catch (const std::exception& e) {
        renderError_ = e.what();
    }
    profiler_.record(renderer_->timings(), (nowSeconds() - r0) * 1000.0);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    drawUi();
    ImGui::Render();

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.16f, 0.16f, 0.17f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (!pendingShot_.empty()) {
        try {
            writeWindowPng(pendingShot_);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "deepgi view: screenshot %s failed: %s\n", pendingShot_.c_str(), e.what());
            scriptFailed_ = true;
        }
        pendingShot_.clear();
    }
    glfwSwapBuffers(window_);
}

void Viewer::drawUi() {
    ImGuiIO& io = ImGui::GetIO();
    const float ww = io.DisplaySize.x, wh = io.DisplaySize.y;
    headerH_ = ui::drawViewportHeader(view_, *this, vpX0_, vpX1_);
    if (view_.cameraChoice >= 0) {
        useSceneCamera(view_.cameraChoice);
        view_.cameraChoice = -1;
    }

    // The viewport: the chosen buffer, fitted with its aspect ratio kept.
    BufferSource src = source(view_.buffer, 0);
    if (!src.valid()) src = source("Final Display", 0);
    const float vw = vpX1_ - vpX0_, vh = vpY1_ - vpY0_;
    const int ow = std::max(1, int(vw * io.DisplayFramebufferScale.x)), oh = std::max(1, int(vh * io.DisplayFramebufferScale.y));
    if (src.valid()) {
        BufferViewParams p = view_.params;
        const float sw = float(src.levelWidth()), sh = float(src.levelHeight());
        const float tpp = std::max(sw / float(ow), sh / float(oh));  // texels per output pixel (fit)
        p.texelsPerPixel = tpp;
        p.origin = glm::vec2(sw, sh) * 0.5f - glm::vec2(float(ow), float(oh)) * 0.5f * tpp;
        p.grid = false;
        const Camera& c = renderer_->camera();
        p.znear = c.znear;
        p.zfar = c.zfar;
        p.perspective = c.perspective;
        p.background = glm::vec4(0.16f, 0.16f, 0.17f, 1.0f);
        const GLuint tex = drawView(0, src, nullptr, p, ow, oh);
        ImGui::GetBackgroundDrawList()->AddImage((ImTextureID)(intptr_t)tex, ImVec2(vpX0_, vpY0_), ImVec2(vpX1_, vpY1_),
                                                 ImVec2(0, 1), ImVec2(1, 0));
    }

    // Overlay text: view name, sizes, timing, status.
    {
        ImDrawList* dl = ImGui::GetForegroundDrawList();
        const float fm = profiler_.cpuFrameMs.empty() ? 0.0f : profiler_.cpuFrameMs.back();
        char line[256];
        std::snprintf(line, sizeof(line), "%s | %s | %dx%d | %.0f ms", view_.viewName.c_str(), view_.buffer.c_str(),
                      renderer_->width(), renderer_->height(), double(fm));
        dl->AddText(ImVec2(vpX0_ + 9, vpY0_ + 7), IM_COL32(0, 0, 0, 200), line);
        dl->AddText(ImVec2(vpX0_ + 8, vpY0_ + 6), IM_COL32(235, 235, 235, 255), line);
        if (!view_.status.empty() && nowSeconds() - statusTime_ < 8.0) {
            dl->AddText(ImVec2(vpX0_ + 9, vpY1_ - 21), IM_COL32(0, 0, 0, 200), view_.status.c_str());
            dl->AddText(ImVec2(vpX0_ + 8, vpY1_ - 22), IM_COL32(255, 230, 140, 255), view_.status.c_str());
        }
    }

    if (view_.sidebar) drawSidebar(vpX1_, wh);
    ui::drawInspector(inspector_, *this, nowSeconds());

    std::vector<std::string> errors = renderer_->shaders().errors();
    if (!renderError_.empty() && std::find(errors.begin(), errors.end(), renderError_) == errors.end()) errors.push_back(renderError_);
    ui::drawShaderErrors(errors, vpX0_, vpY1_ - 26.0f, vpX1_ - vpX0_);
    (void)ww;
}

void Viewer::drawSidebar(float x0, float height) {
    ImGui::SetNextWindowPos(ImVec2(x0, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(ImGui::GetIO().DisplaySize.x - x0, height));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoTitleBar;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
    if (ImGui::Begin("Sidebar", nullptr, flags)) {
        auto tabFlags = [&](const char* name) {
            return selectTab_ == name ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None;
        };
        if (ImGui::BeginTabBar("tabs")) {
            if (ImGui::BeginTabItem("Settings", nullptr, tabFlags("settings"))) {
                ui::SettingsActions a = ui::drawSettingsPanel(settings_, settingsPanel_);
                if (a.resetHistory) renderer_->resetHistory();
                if (a.convergeFrames > 0) {
                    try {
                        for (int i = 0; i < a.convergeFrames; ++i) renderer_->render(settings_);
                        setStatus("converged over " + std::to_string(a.convergeFrames) + " frames");
                    } catch (const std::exception& e) {
                        renderError_ = e.what();
                    }
                }
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Profiler", nullptr, tabFlags("profiler"))) {
                ui::drawProfilerPanel(profiler_, renderer_->textures().memoryReport(), renderer_->width(), renderer_->height());
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("View", nullptr, tabFlags("view"))) {
                ImGui::TextDisabled("Scene");
                ImGui::TextWrapped("%s", scene_->sourcePath.c_str());
                ImGui::Text("%zu triangles, %zu lights, %zu cameras", scene_->triangleCount(), scene_->lights.size(), scene_->cameras.size());
                ImGui::Separator();
                ImGui::TextDisabled("Cameras");
                if (ImGui::Selectable("Frame all (Home)")) { ctl_.frame(scene_->bounds); cut(); }
                for (int i = 0; i < int(view_.cameraNames.size()); ++i)
                    if (ImGui::Selectable((view_.cameraNames[size_t(i)] + (i == 0 ? "  (Numpad 0)" : "")).c_str())) useSceneCamera(i);
                ImGui::Separator();
                ImGui::Checkbox("Emulate 3-button mouse (Alt+left)", &view_.emulate3Button);
                ImGui::SliderFloat("resolution", &view_.resolutionScale, 0.25f, 1.0f, "%.2f x");
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("Render at a fraction of the viewport (llvmpipe is slow)");
                bool persp = ctl_.perspective;
                if (ImGui::Checkbox("Perspective (Numpad 5)", &persp)) { ctl_.perspective = persp; cut(); }
                float fov = glm::degrees(ctl_.yfov);
                if (ImGui::SliderFloat("vertical fov", &fov, 10.0f, 120.0f, "%.0f deg")) ctl_.yfov = glm::radians(fov);
                ImGui::Checkbox("Inspector window (I)", &inspector_.open);
                ImGui::Separator();
                ImGui::TextDisabled("Shaders");
                ImGui::TextWrapped("%s", renderer_->shaders().directory().c_str());
                if (ImGui::Button("Reload all (F5)")) renderer_->shaders().reloadAll();
                ImGui::SameLine();
                ImGui::TextDisabled(renderer_->shaders().errors().empty() ? "no errors" : "%zu error(s)", renderer_->shaders().errors().size());
                ImGui::Separator();
                ImGui::TextDisabled("Screenshot (F12)");
                ImGui::Checkbox("also every buffer as EXR (raw values)", &captureBuffers_);
                if (ImGui::Button("Save screenshot")) capture();
                if (!lastCapture_.empty()) ImGui::TextWrapped("last: %s", lastCapture_.c_str());
                ImGui::Separator();
                ImGui::TextDisabled("Keys");
                ImGui::TextWrapped("MMB orbit, Shift+MMB pan, wheel/Ctrl+MMB zoom; Numpad 1/3/7 front/right/top (Ctrl: opposite), "
                                   "5 persp/ortho, 0 camera; Home frame all; Shift+` fly; F5 reload shaders; F12 screenshot; "
                                   "N sidebar; I inspector.");
                ImGui::EndTabItem();
            }
            ImGui::EndTabBar();
            selectTab_.clear();
        }
    }
    ImGui::End();
    ImGui::PopStyleVar();
}

int Viewer::run() {
    try {
        if (!init()) return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deepgi view: error: %s\n", e.what());
        return 1;
    }
    while (!glfwWindowShouldClose(window_) && !quit_) {
        if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) glfwWaitEventsTimeout(0.1);
        else glfwPollEvents();
        frame();
    }
    saveState();
    return scriptFailed_ ? 1 : 0;
}

}  // namespace

int runViewer(const ViewerOptions& options) {
    Viewer v(options);
    return v.run();
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
