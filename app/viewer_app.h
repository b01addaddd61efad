#pragma once
// The viewer's application object, shared by app/viewer*.cpp (each one job: setup and frame loop, input, captures
// and the state file, the script host). Panels and the script interpreter are in ui/.
#ifdef DEEPGI_HAVE_UI
#include "app/camera_controller.h"
#include "app/dynamic_resolution.h"
#include "app/edit/scene_edit.h"
#include "app/edit/transform_tool.h"
#include "app/edit/undo_history.h"
#include "app/viewer_path_trace.h"
#include "app/viewer.h"
#include "renderer/core/image_io.h"
#include "renderer/passes/buffer_view_pass.h"
#include "renderer/renderer.h"
#include "ui/scene_panel.h"
#include "ui/script.h"
#include "ui/viewer_ui.h"

#include <glad/gl.h>
// glad first: GLFW must not pull in the system GL header.
#include <GLFW/glfw3.h>

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace deepgi {

class Viewer : public ui::ViewerServices, public ui::ScriptHost {
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
    std::string description(const std::string& name) override;
    ui::ErrorView errorView(const std::string& a, const std::string& b, int level, ui::CompareMode mode, float scale) override;
    ui::EmptyMask emptyMask(const std::string& name, int level) override;
    int dataLevel(const std::string& name) override;

    // ScriptHost (ui/script.h)
    bool scriptReady() override { return renderer_ && renderer_->frameIndex() > 0; }
    bool scriptBusy() override { return !uiDrag_.empty(); }
    void scriptKey(int key, int mods) override;
    void scriptDrag(int button, glm::dvec2 from, glm::dvec2 to, int mods) override;
    void scriptPointer(glm::dvec2 at, int button, bool down, int mods) override;
    void scriptMouseMove(glm::dvec2 at) override;
    void scriptScroll(double notches, const glm::dvec2* at) override;
    void scriptSet(const std::string& assignment) override;
    void scriptShow(const std::string& buffer) override;
    void scriptInspect(const std::string& a, const std::string& b) override;
    void scriptCompare(const std::string& mode) override;
    void scriptReference(const std::string& path) override;
    void scriptPathTrace(const std::string& mode) override;
    void scriptCamera(const std::string& name) override;
    void scriptScreenshot(const std::string& path) override { pendingShot_ = path; }
    void scriptPanel(const std::string& name) override;
    void scriptResize(int w, int h) override;
    void scriptCapture() override;
    void scriptProfilerCsv(const std::string& path) override;
    void scriptDumpErrors(const std::string& path) override;
    void scriptDumpFigures(const std::string& path) override;
    void scriptReload() override;
    void scriptConverge(int frames) override { convergePending_ += frames; }
    void scriptStats(const std::string& path) override;
    void scriptDumpScene(const std::string& path) override;
    void scriptSave(const std::string& path) override;
    void scriptTimeline(const std::string& what) override;

    // One input event as GLFW delivered it (or the script made it): queued by the callbacks, handled in order at
    // the start of the next frame, before its render, so that every press of a frame counts.
    struct InputEvent {
        enum class Kind { Button, Cursor, Scroll, Key } kind = Kind::Key;
        int code = 0, action = 0, mods = 0;  // button or key, GLFW_PRESS/RELEASE, modifiers
        double x = 0.0, y = 0.0;             // cursor position, or the wheel's notches in y
        bool fromScript = false;
    };
    void queueInput(const InputEvent& e) { input_.push_back(e); }

    // Input, from GLFW callbacks or the script (fromScript bypasses ImGui's capture flags).
    void onMouseButton(int button, int action, int mods, bool fromScript);
    void onCursor(double x, double y, bool fromScript);
    void onScroll(double dy, bool fromScript);
    void onKey(int key, int action, int mods, bool fromScript);

private:
    enum class Drag { None, Orbit, Pan, Zoom };

    bool init();
    void loadState();
    void saveState();
    void frame();
    void drawUi();
    void drawFrameUi(int fbw, int fbh);  // the UI over the last rendered frame, then the swap
    void drawSidebar(float x0, float height);
    void updateFly(double dt);
    void handleInput();  // the queued events, in arrival order
    double targetFrameMs() const;  // the viewport's setting, or its automatic value (software GL or not)
    void renderFullSize(int frames);  // at the whole viewport's size now (a capture of a moving view)
    void cut() { renderer_->resetHistory(); }
    void useSceneCamera(int index);
    bool inViewport(double x, double y) const {
        return x >= vpX0_ && x < vpX1_ && y >= vpY0_ && y < vpY1_;
    }
    void capture();
    void writeWindowPng(const std::string& path);
    void setStatus(const std::string& s);
    void applyScriptPointer();  // after the GLFW backend's NewFrame, before ImGui's
    void routeScriptWheel();    // after ImGui's NewFrame: the wheel goes to the viewport if no window took it
    void drawViewport();
    void afterRender();         // the path tracer's request and figures, after each frame's render
    ui::PathTraceMode pathTraceMode() const { return ptTex_ ? view_.pathTrace : ui::PathTraceMode::Off; }
    std::string pathTraceFiguresLine() const;
    std::string writeProfilerCsv(const std::string& path);  // "" or the error
    void showTexture(const std::string& textureOrLayer);     // the Pipeline panel's click
    FloatImage readSource(const std::string& name, int level);  // registry layer (decoded), reference or path trace
    // Scene editing (viewer_edit.cpp).
    edit::ToolView toolView() const;                   // the last frame's camera over the viewport (window units)
    void beforeSceneEdit();                            // stops what reads the scene on another thread
    void sceneEdited(unsigned changes);                // Renderer::sceneChanged, and render like a motion
    void recordEdit(const std::string& label, const edit::EditState& before);  // one undo step (before -> now)
    void undoRedo(bool redo);
    void selectAt(double x, double y, bool extend);    // a click in the viewport (window units)
    void selectAll(bool all);
    void hideSelected(bool unhideAll);
    void toggleVisible(int node);
    bool beginTransform(edit::ToolMode mode);
    void applyTransform();
    void confirmTransform();
    void cancelTransform();
    bool editKey(int key, int mods);                   // true: the editor took the key
    bool editButton(int button, int action, int mods, bool captured);
    void editCursor();
    void finishPanelEdit();
    void drawItemTab();
    void updateOutline();
    void drawEditOverlay();
    void advanceAnimation(double dt);
    void applyAnimationNow();
    void drawTimeline();
    std::string saveScene(const std::string& path);    // File > Save As: its message
    void routeScriptClick();                           // after ImGui's NewFrame: a click no window took is the viewport's
    std::vector<uint8_t> surfaceMask(const std::string& name, int level, bool* applies);  // 0 = empty texel

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
    bool lastCaptureFailed_ = false;
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
    float inspX0_ = 1, inspX1_ = 1;
    ui::SidebarState sidebar_;
    ui::PipelineGraph pipeline_;
    ui::PipelinePanelState pipelinePanel_;
    // Inspector caches: the error image and the empty-texel hatch, recomputed when their inputs change or twice a second.
    gl::TextureHandle errTex_, maskTex_;
    std::string errKey_, maskKey_;
    double errTime_ = -1e9, maskTime_ = -1e9;
    ui::ErrorView errLast_;
    ui::EmptyMask maskLast_;
    // "Path trace this view".
    std::unique_ptr<ViewerPathTrace> pathTrace_;
    ViewerPathTrace::Snapshot ptSnap_;
    gl::TextureHandle ptTex_;
    std::string ptFigures_;
    double ptFiguresTime_ = -1e9;
    int ptFiguresSamples_ = -1;
    // Script.
    ui::ScriptRunner script_;
    std::string pendingShot_;
    int convergePending_ = 0;
    bool scriptPointerSet_ = false;     // the script owns the UI pointer (the real one, Xvfb's, is ignored)
    glm::dvec2 scriptPointerAt_{-1e6};
    bool scriptButtons_[3] = {false, false, false};
    std::deque<std::pair<glm::dvec2, bool>> uiDrag_;  // pointer position and left button, one per frame
    double scriptWheel_ = 0.0;          // notches for this frame, given to the window under scriptWheelAt_
    glm::dvec2 scriptWheelAt_{0.0};
    bool quit_ = false;
    double lastFrameTime_ = 0.0;
    // Input queue and the fly keys' state from their events (a tap within one frame still moves).
    std::deque<InputEvent> input_;
    unsigned flyHeld_ = 0, flyPressed_ = 0;
    size_t inputEvents_ = 0, keyPresses_ = 0;
    // Dynamic resolution: the camera's motion, the step chosen, the last frames' times.
    bool softwareGl_ = false;
    DynamicResolution dynres_;
    Camera lastCamera_;
    bool haveLastCamera_ = false;
    double lastMotionTime_ = -1e9;
    int framesStill_ = 1 << 20;
    bool moving_ = false;
    int fullW_ = 0, fullH_ = 0;        // the viewport in framebuffer pixels (times the manual resolution scale)
    FrameSample lastSample_;           // the frame being timed: its render time, step and whether to learn from it
    struct FrameRecord {
        double frameMs, renderMs;
        int width, height;
        bool moving, rendered;
    };
    std::deque<FrameRecord> recentFrames_;
    int lastRenderW_ = 0, lastRenderH_ = 0;
    bool lastMoving_ = false, lastRendered_ = false;
    // UI frames: the panels in use, nothing the render reads changed (see frame()).
    bool uiInput_ = false, needRender_ = false;
    Settings renderedSettings_;
    // What the viewport's view texture was last drawn from (a UI frame reuses it).
    struct ViewportKey {
        BufferViewParams params;
        GLuint source = 0, split = 0;
        int layer = 0, splitLayer = 0, vis = 0, level = 0, sourceW = 0, sourceH = 0, width = 0, height = 0;
        uint64_t frame = 0;
        int pathTraceSamples = -1;
        uint64_t pathTraceGeneration = 0;
        int reference = 0;
    };
    ViewportKey viewportKey_;
    GLuint viewportTex_ = 0;
    int referenceLoads_ = 0;
    size_t uiOnlyFrames_ = 0, idleFrames_ = 0;
    int stillFrames_ = 0;              // rendered frames since anything the render reads changed
    uint64_t lastProbeUpdates_ = 0;
    bool converged_ = false;           // still long enough: frames draw the UI only
    // Scene editing: selection, the transform tool, undo, the N panel's pending edit, the outline, the timeline.
    edit::Selection selection_;
    edit::TransformTool tool_;
    std::vector<int> toolNodes_;       // the nodes the tool moves (the selection's roots); then the default sun
    bool toolSun_ = false;
    edit::EditState toolBefore_;
    edit::UndoHistory<edit::EditState> history_{64};
    std::string lastEditLabel_;
    bool panelEditPending_ = false;    // an N panel drag in progress: one undo step when it ends
    std::string panelEditLabel_;
    edit::EditState panelEditBefore_;
    ui::ScenePanelState scenePanel_;
    int eulerNode_ = -1;
    glm::quat eulerQuat_{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 eulerShown_{0.0f};
    struct OutlineKey {
        uint64_t frame = 0;
        std::vector<int> items;
        int active = -1;
        bool operator==(const OutlineKey& o) const { return frame == o.frame && items == o.items && active == o.active; }
    };
    OutlineKey outlineKey_;
    gl::TextureHandle outlineTex_;
    int outlineW_ = 0, outlineH_ = 0;
    size_t outlinePixels_ = 0;
    bool playing_ = false;
    float animTime_ = 0.0f;
    std::string saveMessage_;
    struct PendingClick {
        bool pending = false;
        glm::dvec2 at{0.0};
        int button = 0, action = 0, mods = 0;
    };
    std::deque<PendingClick> scriptClicks_;
};

double nowSeconds();
// The Pipeline panel's graph from the renderer's passes, their reads/writes and last timings. The one place that
// knows how the renderer exposes its passes (to be re-pointed at Renderer::graph() once it exists).
ui::PipelineGraph pipelineGraph(const Renderer& renderer, const Settings& settings);
// The path tracer renders the view at 1/kPathTraceDivisor of the viewport's width and height (at full resolution).
constexpr int kPathTraceDivisor = 4;

}  // namespace deepgi
#endif  // DEEPGI_HAVE_UI
