// The viewer: GLFW window and GL context, main loop (with the dynamic resolution's and the UI frames' choices), the
// services the panels use. The viewport's drawing is in viewer_viewport.cpp, input in viewer_input.cpp, files
// (state, captures) in viewer_capture.cpp, the script host in viewer_script_host.cpp; panels and the script
// interpreter in ui/.
#ifdef DEEPGI_HAVE_UI
#include "app/viewer_app.h"
#include "app/options.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "renderer/core/image_io.h"
#include "renderer/probes/probe_volume.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace deepgi {

double nowSeconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

void Viewer::setStatus(const std::string& s) {
    view_.status = s;
    statusTime_ = nowSeconds();
}

Viewer::~Viewer() {
    // GL objects die with the context: release them first.
    views_[0].reset();
    views_[1].reset();
    pathTrace_.reset();  // joins the worker
    refTex_.reset();
    outlineTex_.reset();
    ptTex_.reset();
    errTex_.reset();
    maskTex_.reset();
    renderer_.reset();
    if (imguiReady_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

// ---- setup -------------------------------------------------------------------------------------------------

Viewer* self(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

bool Viewer::init() {
    settings_ = opt_.settings;
    if (opt_.screenshotDir.empty()) opt_.screenshotDir = defaultScreenshotDir();  // never the current folder
    loadState();
    if (opt_.targetFrameMs >= 0.0) view_.targetFrameMs = float(opt_.targetFrameMs);  // the command line wins
    if (!opt_.scriptPath.empty()) script_ = ui::ScriptRunner(opt_.scriptPath, ui::parseViewerScript(opt_.scriptPath));  // fail before opening a window

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

    // Our callbacks first: the ImGui backend chains to them. They queue; the frame handles the queue in order.
    using K = InputEvent::Kind;
    glfwSetWindowUserPointer(window_, this);
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int b, int a, int m) { self(w)->queueInput({K::Button, b, a, m}); });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { self(w)->queueInput({K::Cursor, 0, 0, 0, x, y}); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { self(w)->queueInput({K::Scroll, 0, 0, 0, 0.0, dy}); });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int k, int, int a, int m) { self(w)->queueInput({K::Key, k, a, m}); });

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
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    imguiReady_ = true;

    RendererOptions ro;
    if (!opt_.shaderDir.empty()) ro.shaderDir = opt_.shaderDir;
    ro.sceneEditing = true;  // click-select, the outline and G/R/S read Object ID and Motion
    // GPU timer queries where they are reliable; llvmpipe's miss vertex work and bin draws (platform.md).
    const bool software = gl::currentContextIsSoftware();
    ro.timing = software ? TimingMode::WallClock : TimingMode::GpuQueries;
    softwareGl_ = software;
    renderer_ = std::make_unique<Renderer>(ro);
    views_[0] = std::make_unique<BufferViewPass>();
    views_[1] = std::make_unique<BufferViewPass>();

    {
        Scene loaded = loadScene(opt_.scenePath, withLoadProgress({}, opt_.scenePath));
        attachEnvironment(loaded, opt_.environment);
        scene_ = std::make_shared<Scene>(std::move(loaded));
    }
    for (const auto& w : scene_->warnings) std::fprintf(stderr, "deepgi view: warning: %s\n", w.c_str());
    renderer_->setScene(scene_);
    for (const auto& c : scene_->cameras) view_.cameraNames.push_back(c.name);
    const bool sameScene = !restoredScene_.empty() && fs::exists(restoredScene_) && fs::exists(scene_->sourcePath) &&
                           fs::equivalent(restoredScene_, scene_->sourcePath);
    if (!opt_.cameraFile.empty()) {
        const Camera c = loadCameraFile(opt_.cameraFile);
        ctl_.setFromCamera(c, std::max(glm::dot(scene_->bounds.center() - c.position(), c.forward()), 1e-3f));
        // A capture also holds the orbit state: resume exactly that navigation.
        std::ifstream in(opt_.cameraFile);
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (j.is_object() && j.contains("viewer_orbit") && j["viewer_orbit"].is_object()) ctl_.fromJson(j["viewer_orbit"]);
        view_.viewName = "Camera file: " + fs::path(opt_.cameraFile).filename().string();
    } else if (!opt_.camera.empty()) {
        Camera c = selectCamera(*scene_, opt_.camera);
        ctl_.setFromCamera(c, glm::length(scene_->bounds.center() - c.position()));
        view_.viewName = "Camera: " + opt_.camera;
    } else if (!sameScene) {
        useSceneCamera(0);
    }
    std::printf("deepgi view: F12 screenshots go to %s\n", fs::absolute(opt_.screenshotDir).string().c_str());
    std::fflush(stdout);
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
    if (ptTex_) n.push_back(ui::kPathTraceName);
    return n;
}

BufferSource Viewer::source(const std::string& name, int level) {
    if (name == ui::kPathTraceName) {
        BufferSource s;
        if (!ptTex_) return s;
        s.texture = ptTex_.id();
        s.format = GL_RGBA32F;
        s.width = ptSnap_.final.width;
        s.height = ptSnap_.final.height;
        s.vis = Visualize::Radiance;
        return s;
    }
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
        ++referenceLoads_;
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

// ---- frame -------------------------------------------------------------------------------------------------

double Viewer::targetFrameMs() const {
    if (view_.targetFrameMs >= 0.0f) return double(view_.targetFrameMs);
    return softwareGl_ ? 100.0 : 1000.0 / 60.0;
}

void Viewer::frame() {
    const double t = nowSeconds();
    const double frameMs = (t - lastFrameTime_) * 1000.0;  // the previous frame, whole: input, render, UI, swap
    const double dt = std::min(t - lastFrameTime_, 0.25);
    lastFrameTime_ = t;
    FrameSample last = lastSample_;
    last.frameMs = frameMs;
    if (lastRenderW_ > 0) {
        recentFrames_.push_back({frameMs, last.renderMs, lastRenderW_, lastRenderH_, lastMoving_, lastRendered_});
        if (recentFrames_.size() > 120) recentFrames_.pop_front();
    }
    lastSample_.valid = true;  // this frame, unless something below makes it untypical

    // Hot reload: poll the mtimes of every file the programs used, twice a second.
    if (t - lastPoll_ > 0.5) {
        lastPoll_ = t;
        const int n = renderer_->shaders().reloadChanged();
        if (n > 0) {
            setStatus("reloaded " + std::to_string(n) + " shader program(s)");
            renderError_.clear();
            lastSample_.valid = false;
            needRender_ = true;
        }
    }
    uiInput_ = false;
    script_.step(*this, t);
    if (script_.finished()) quit_ = true;
    uiInput_ = uiInput_ || !uiDrag_.empty();
    handleInput();
    updateFly(dt);
    advanceAnimation(dt);

    int fbw = 0, fbh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    glfwGetWindowSize(window_, &ww, &wh);
    if (fbw <= 0 || fbh <= 0 || ww <= 0 || wh <= 0) {  // minimised
        renderer_->resize(0, 0);
        lastRenderW_ = 0;
        lastSample_.valid = false;
        return;
    }
    const float scaleX = float(fbw) / float(ww), scaleY = float(fbh) / float(wh);
    const float sidebarW = view_.sidebar ? std::clamp(float(ww) * 0.3f, 280.0f, 420.0f) : 0.0f;
    // Fixed split layout: viewport | divider | inspector | sidebar; the divider's place is remembered.
    const float mainW = std::max(float(ww) - sidebarW, 2.0f);
    vpX0_ = 0.0f;
    vpX1_ = inspector_.open ? std::max(std::round(mainW * view_.inspectorSplit), 1.0f) : mainW;
    inspX0_ = vpX1_ + (inspector_.open ? ui::kDividerWidth : 0.0f);
    inspX1_ = mainW;
    vpY0_ = headerH_;
    vpY1_ = float(wh);
    fullW_ = std::max(1, int((vpX1_ - vpX0_) * scaleX * view_.resolutionScale));
    fullH_ = std::max(1, int((vpY1_ - vpY0_) * scaleY * view_.resolutionScale));

    // Dynamic resolution: the camera moved in the last half second (and the last 3 frames) = moving.
    const Camera cam = ctl_.camera(scene_->bounds);
    const bool changed = haveLastCamera_ &&
                         (cam.cameraToWorld != lastCamera_.cameraToWorld || cam.perspective != lastCamera_.perspective ||
                          cam.yfov != lastCamera_.yfov || cam.orthoHalfHeight != lastCamera_.orthoHalfHeight);
    lastCamera_ = cam;
    haveLastCamera_ = true;
    if (changed) {
        lastMotionTime_ = t;
        framesStill_ = 0;
    } else if (framesStill_ < (1 << 20)) {
        ++framesStill_;
    }
    moving_ = framesStill_ < 3 || t - lastMotionTime_ < 0.5;
    dynres_.setTarget(targetFrameMs());
    // A UI frame: while the panels are being used (pointer over them, a text field typing) and nothing the render
    // depends on changed, the frame is not rendered again: the UI answers at its own cost, the viewport keeps the
    // last frame (still camera: the same image). Anything that changes the render renders the next frame.
    const bool unchanged = !moving_ && !needRender_ && convergePending_ == 0 && renderer_->frameIndex() > 0 &&
                           settings_ == renderedSettings_ && renderer_->width() == fullW_ && renderer_->height() == fullH_ &&
                           renderError_.empty() && renderer_->shaders().errors().empty();
    // Converged: still and unchanged for as many frames as the temporal history needs to fall under 1 % (and the
    // probes no longer updating): the frames after it would be the same image, so they only draw the UI.
    const uint64_t probeUpdates = renderer_->probeVolume() ? renderer_->probeVolume()->updateCount() : 0;
    if (!unchanged || probeUpdates != lastProbeUpdates_ || view_.pathTrace != ui::PathTraceMode::Off) stillFrames_ = 0;
    lastProbeUpdates_ = probeUpdates;
    const float alpha = std::clamp(settings_.hysteresis, 0.0f, 0.995f);
    const int convergeFrames = 4 + (settings_.temporal && alpha > 0.0f ? int(std::ceil(std::log(0.01) / std::log(double(alpha)))) : 0);
    converged_ = stillFrames_ >= convergeFrames;
    const bool uiOnly = unchanged && (uiInput_ || converged_);
    needRender_ = false;
    lastRendered_ = !uiOnly;
    lastMoving_ = moving_;
    if (uiOnly) {
        ++uiOnlyFrames_;
        if (converged_) ++idleFrames_;
        if (view_.pathTrace != ui::PathTraceMode::Off) afterRender();  // its samples keep arriving
        lastSample_.valid = false;
        lastSample_.renderMs = 0.0;
        drawFrameUi(fbw, fbh);
        return;
    }
    const int step = dynres_.next(moving_, last);
    const int rw = std::max(1, int(std::lround(fullW_ * double(step) / DynamicResolution::kSteps)));
    const int rh = std::max(1, int(std::lround(fullH_ * double(step) / DynamicResolution::kSteps)));
    if (rw != renderer_->width() || rh != renderer_->height() || convergePending_ > 0) lastSample_.valid = false;

    renderer_->resize(rw, rh);
    renderer_->setCamera(cam);
    const double r0 = nowSeconds();
    try {
        // `converge N` (script or Settings panel): N - 1 frames now, the Nth below as usual.
        for (; convergePending_ > 1; --convergePending_) renderer_->render(settings_);
        convergePending_ = 0;
        renderer_->render(settings_);
        if (renderer_->shaders().errors().empty()) renderError_.clear();
    } catch (const std::exception& e) {
        renderError_ = e.what();
        convergePending_ = 0;
    }
    const double renderMs = (nowSeconds() - r0) * 1000.0;
    renderedSettings_ = settings_;
    ++stillFrames_;
    profiler_.record(renderer_->timings(), renderMs);
    lastSample_.renderMs = renderMs;
    lastSample_.step = step;
    lastRenderW_ = renderer_->width();
    lastRenderH_ = renderer_->height();
    afterRender();
    drawFrameUi(fbw, fbh);
}

void Viewer::drawFrameUi(int fbw, int fbh) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    applyScriptPointer();
    ImGui::NewFrame();
    routeScriptWheel();
    routeScriptClick();
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
            script_.fail("screenshot " + pendingShot_ + " failed: " + e.what());
        }
        pendingShot_.clear();
    }
    glfwSwapBuffers(window_);
}

void Viewer::drawUi() {
    ImGuiIO& io = ImGui::GetIO();
    const float wh = io.DisplaySize.y;
    headerH_ = ui::drawViewportHeader(view_, *this, vpX0_, vpX1_);
    if (view_.cameraChoice >= 0) {
        useSceneCamera(view_.cameraChoice);
        view_.cameraChoice = -1;
    }
    if (view_.saveRequested) {  // File > Save As
        view_.saveRequested = false;
        saveMessage_ = saveScene(view_.savePath);
        view_.saveMessage = saveMessage_;
        setStatus(saveMessage_);
    }
    drawViewport();
    drawTimeline();

    if (view_.sidebar) drawSidebar(inspX1_, wh);
    if (inspector_.open) {
        ui::drawSplitDivider(vpX1_, 0.0f, wh, vpX0_, inspX1_, view_.inspectorSplit);
        ui::drawInspector(inspector_, *this, nowSeconds(), ImVec2(inspX0_, 0.0f), ImVec2(inspX1_ - inspX0_, wh));
    }

    std::vector<std::string> errors = renderer_->shaders().errors();
    if (!renderError_.empty() && std::find(errors.begin(), errors.end(), renderError_) == errors.end()) errors.push_back(renderError_);
    ui::drawShaderErrors(errors, vpX0_, vpY1_ - 26.0f, vpX1_ - vpX0_);
}

void Viewer::drawSidebar(float x0, float height) {
    ui::SidebarModel m;
    m.scenePath = scene_->sourcePath;
    m.triangles = scene_->triangleCount();
    m.lights = scene_->lights.size();
    m.cameraNames = view_.cameraNames;
    m.shaderDir = renderer_->shaders().directory();
    m.shaderErrors = renderer_->shaders().errors().size();
    m.screenshotDir = opt_.screenshotDir;
    m.lastCapture = lastCapture_;
    m.memory = renderer_->textures().memoryReport();
    m.width = renderer_->width();
    m.height = renderer_->height();
    m.autoTargetFrameMs = softwareGl_ ? 100.0f : 1000.0f / 60.0f;
    pipeline_ = pipelineGraph(*renderer_, settings_);
    m.pipeline = &pipeline_;
    ui::SidebarState& st = sidebar_;
    st.settings = &settings_;
    st.settingsPanel = &settingsPanel_;
    st.profiler = &profiler_;
    st.view = &view_;
    st.inspector = &inspector_;
    st.pipeline = &pipelinePanel_;
    st.captureBuffers = &captureBuffers_;
    st.perspective = ctl_.perspective;
    st.yfov = ctl_.yfov;
    st.itemTab = [this] { drawItemTab(); };
    const ui::SidebarActions a = ui::drawSidebar(m, st, x0, height);

    needRender_ = needRender_ || a.settings.resetHistory || a.settings.convergeFrames > 0 || !a.pipeline.showTexture.empty() ||
                  a.frameAll || a.camera >= 0 || a.projectionChanged || a.fovChanged || a.reloadShaders || a.capture;
    if (a.settings.changed || a.pipeline.settingsChanged) {  // a slider dragged: the render follows like a motion
        lastMotionTime_ = nowSeconds();
        framesStill_ = 0;
    }
    if (a.settings.resetHistory) renderer_->resetHistory();
    if (a.settings.convergeFrames > 0) {
        convergePending_ += a.settings.convergeFrames;
        setStatus("converging over " + std::to_string(a.settings.convergeFrames) + " frames");
    }
    if (a.profiler.exportCsv) {
        const std::string err = writeProfilerCsv(profiler_.csvPath);
        profiler_.message = err.empty() ? std::string("wrote ") + profiler_.csvPath : err;
    }
    if (!a.pipeline.showTexture.empty()) showTexture(a.pipeline.showTexture);
    if (a.frameAll) { ctl_.frame(scene_->bounds); cut(); }
    if (a.camera >= 0) useSceneCamera(a.camera);
    if (a.projectionChanged) { ctl_.perspective = st.perspective; cut(); }
    if (a.fovChanged) ctl_.yfov = st.yfov;
    if (a.reloadShaders) renderer_->shaders().reloadAll();
    if (a.capture) capture();
}

int Viewer::run() {
    try {
        if (!init()) return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deepgi view: error: %s\n", e.what());
        return 1;
    }
    while (!glfwWindowShouldClose(window_) && !quit_) {
        // Minimised, or converged with no script to play: sleep until an event (or the shader poll's next turn).
        if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) glfwWaitEventsTimeout(0.1);
        else if (converged_ && !script_.active()) glfwWaitEventsTimeout(0.25);
        else glfwPollEvents();
        frame();
    }
    saveState();
    return script_.failed() ? 1 : 0;
}

int runViewer(const ViewerOptions& options) {
    Viewer v(options);
    return v.run();
}

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
