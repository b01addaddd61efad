#pragma once
// The viewer's ImGui panels. They only draw and edit state; anything that touches GL or the renderer goes through
// ViewerServices, which the app implements.
#include "renderer/core/camera.h"
#include "renderer/core/settings.h"
#include "renderer/core/texture_registry.h"
#include "renderer/passes/buffer_view_pass.h"
#include "renderer/renderer.h"

#include <imgui.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace deepgi::ui {

constexpr const char* kReferenceName = "Reference (EXR)";
constexpr const char* kPathTraceName = "Path Trace (live)";

struct BufferStats {
    bool valid = false;
    int channels = 0;
    double min[4] = {0, 0, 0, 0}, max[4] = {0, 0, 0, 0}, mean[4] = {0, 0, 0, 0};  // over finite, non-empty values
    size_t nan = 0, inf = 0, negative = 0, texels = 0;
    size_t empty = 0;          // texels with no surface (sky, no layer-2 surface): left out of everything above
    bool vectors = false;      // normals: channels are x, y, z of unit vectors (negative components are not flagged)
    double meanLength = 0.0;   // vectors: mean length before normalisation (1 for well-formed normals)
};
// mask: width*height, 0 = empty texel (left out), or empty = every texel counts. vectors: the image holds decoded
// normals (xyz): min/mean/max per axis, no "negative" count.
BufferStats computeStats(const FloatImage& img, const std::vector<uint8_t>& mask = {}, bool vectors = false);

enum class CompareMode { A = 0, B, Wipe, Diff, Relative };
// The inspector's difference and relative-error images and their figures, computed by the app.
struct ErrorView {
    BufferSource source;         // invalid if it cannot be computed (then `message` says why)
    std::string figures;         // "rel L1 (4x4) ...": the same figures as `deepgi compare`
    std::string message;
};
// The hatch drawn over empty texels of a buffer (no surface at that layer), for the inspector.
struct EmptyMask {
    GLuint texture = 0;          // RGBA8, buffer-sized, rows bottom-up; 0 = the buffer has no empty texels / no mask
    size_t empty = 0, texels = 0;
};

// What the panels may ask of the app.
class ViewerServices {
public:
    virtual ~ViewerServices() = default;
    virtual std::vector<std::string> bufferNames() = 0;  // every registered layer, plus the reference if loaded
    virtual BufferSource source(const std::string& name, int level) = 0;
    // Draws into the view `slot`'s texture (0 = main viewport, 1 = inspector) and returns the GL texture.
    virtual GLuint drawView(int slot, const BufferSource& a, const BufferSource* b, const BufferViewParams& p, int w,
                            int h) = 0;
    virtual TexelBlock readTexels(const BufferSource& s, int x, int y, int w, int h) = 0;
    virtual BufferStats stats(const std::string& name, int level) = 0;  // reads the whole level: on demand only
    virtual std::string loadReference(const std::string& path) = 0;    // "" or the error
    virtual const Camera& camera() const = 0;
    virtual std::string description(const std::string& name) = 0;      // the registry's TextureDecl.description
    virtual ErrorView errorView(const std::string& a, const std::string& b, int level, CompareMode mode, float scale) = 0;
    virtual EmptyMask emptyMask(const std::string& name, int level) = 0;
    // The finest mip level that holds the buffer's data, shown first when it is picked: the gather's finest tap
    // level for Input Radiance and a layer 2 drawn there, else 0.
    virtual int dataLevel(const std::string& name) = 0;
};

// ---- settings ----------------------------------------------------------------------------------------------
struct SettingsActions {
    bool changed = false;         // a value changed (keep rendering; history stays)
    bool resetHistory = false;
    int convergeFrames = 0;       // > 0: render that many frames now
    std::string message;          // shown under the buttons (saved/loaded/errors)
};
struct SettingsPanelState {
    char path[512] = "settings.json";
    int convergeFrames = 16;
    std::string message;
};
// Every declared setting, grouped, generated from settingTable(); presets; history; save/load.
SettingsActions drawSettingsPanel(Settings& s, SettingsPanelState& state);
// One setting's widget (slider, checkbox, combo) with its tooltip; true if the value changed.
bool drawSettingWidget(Settings& s, const SettingInfo& info);

// ---- profiler ----------------------------------------------------------------------------------------------
struct ProfilerState {
    static constexpr int kHistory = 240;
    std::deque<float> frameMs, cpuFrameMs;
    std::map<std::string, std::deque<float>> passMs;
    std::vector<std::string> passOrder;
    std::string timingNote = "wall clock, glFinish around each pass";
    char csvPath[512] = "profiler.csv";
    std::string message;
    void record(const std::vector<PassTiming>& timings, double cpuFrameMs);
    // Frame, passes (ms) per recorded frame, oldest first: "frame,cpu_frame_ms,renderer_ms,<pass>..." header.
    std::string csv() const;
};
struct ProfilerActions {
    bool exportCsv = false;  // write csv() to csvPath
};
ProfilerActions drawProfilerPanel(ProfilerState& p, const MemoryReport& mem, int width, int height);
// A history plot with its scale: the y axis from 0 to a rounded maximum, labelled, and the last value.
void drawHistoryPlot(const char* id, const std::deque<float>& values, float height, const char* unit);

// ---- pipeline ----------------------------------------------------------------------------------------------
// The pass graph as the panel sees it: plain data, filled by the app (ui knows no pass classes).
struct PipelineNode {
    std::string name;
    std::vector<std::string> reads, writes;  // texture names, as in the registry
    bool enabled = true;
    double ms = -1.0;                        // last frame's time; < 0 unknown
    std::vector<std::string> settingKeys;    // settings that shape this pass (settings.def keys)
};
struct PipelineGraph {
    std::vector<PipelineNode> passes;  // in execution order
};
struct PipelinePanelState {
    std::string selectedPass;
    std::map<std::string, glm::vec4> itemRects;  // pass and texture name -> x0 y0 x1 y1 of its first item (for scripts)
};
struct PipelineActions {
    std::string showTexture;  // a texture was clicked: show it in the viewport (and the inspector)
    bool settingsChanged = false;
};
PipelineActions drawPipelinePanel(const PipelineGraph& g, PipelinePanelState& st, Settings& settings);

enum class PathTraceMode { Off = 0, Full, Split };

// ---- viewport header, overlays -----------------------------------------------------------------------------
struct ViewportState {
    std::string buffer = "Final Display";  // what the viewport shows
    BufferViewParams params;               // channel, exposure, range (the window is the fit)
    std::string viewName = "User Perspective";
    std::vector<std::string> cameraNames;  // glTF cameras
    int cameraChoice = -1;                 // set by the header when the user picks a camera
    bool emulate3Button = false;
    bool flyMode = false;
    float resolutionScale = 1.0f;
    float targetFrameMs = -1.0f;           // dynamic resolution's target while moving: 0 off, < 0 automatic
    bool sidebar = true;
    std::string status;                    // bottom-left status line
    float inspectorSplit = 0.5f;           // the viewport's share of the width left of the sidebar (inspector open)
    float pathTraceSplit = 0.5f;           // "Path trace this view", split: real time left of it, path traced right
    PathTraceMode pathTrace = PathTraceMode::Off;
    char savePath[512] = "scene_edited.gltf";  // File > Save As
    bool saveRequested = false;            // set by the header's Save button, cleared by the app
    std::string saveMessage;               // the last save's result or error
};

// ---- layout ------------------------------------------------------------------------------------------------
constexpr float kDividerWidth = 6.0f;
constexpr float kMinSplit = 0.15f, kMaxSplit = 0.85f;
// The movable divider between the viewport (x0..x) and the inspector (x..x1): drags `split` (fraction of x0..x1).
void drawSplitDivider(float x, float y0, float y1, float x0, float x1, float& split);
// The header bar along the top of the viewport (x0..x1 in window units). Returns its height.
float drawViewportHeader(ViewportState& v, ViewerServices& services, float x0, float x1);
// Shader errors overlay (red), at the bottom of the viewport; nothing if there are none.
void drawShaderErrors(const std::vector<std::string>& errors, float x0, float y1, float width);

// ---- sidebar -----------------------------------------------------------------------------------------------
struct InspectorState;
// What the sidebar shows, filled by the app each frame.
struct SidebarModel {
    std::string scenePath;
    size_t triangles = 0, lights = 0;
    std::vector<std::string> cameraNames;
    std::string shaderDir, screenshotDir, lastCapture;
    size_t shaderErrors = 0;
    MemoryReport memory;
    int width = 0, height = 0;
    float autoTargetFrameMs = 100.0f;      // what "automatic" means on this GL (software or not)
    const PipelineGraph* pipeline = nullptr;
};
// What it edits (pointers into the app's state) and its own state.
struct SidebarState {
    Settings* settings = nullptr;
    SettingsPanelState* settingsPanel = nullptr;
    ProfilerState* profiler = nullptr;
    ViewportState* view = nullptr;
    InspectorState* inspector = nullptr;
    PipelinePanelState* pipeline = nullptr;
    bool* captureBuffers = nullptr;
    bool perspective = true;  // the camera's projection and field of view, copied in and out by the app
    float yfov = 0.87f;
    std::string selectTab;    // tab to bring to the front this frame
    std::function<void()> itemTab;  // draws the Item tab (outliner and N panel: the app owns the scene)
};
struct SidebarActions {
    SettingsActions settings;
    ProfilerActions profiler;
    PipelineActions pipeline;
    bool frameAll = false;
    int camera = -1;
    bool projectionChanged = false, fovChanged = false;
    bool reloadShaders = false;
    bool capture = false;
};
SidebarActions drawSidebar(const SidebarModel& m, SidebarState& st, float x0, float height);

// ---- inspector ---------------------------------------------------------------------------------------------
struct InspectorState {
    bool open = false;
    std::string a = "Normal 1", b;   // b empty: no second image
    int level = 0;
    BufferViewParams params;
    CompareMode compare = CompareMode::Wipe;
    float relativeScale = 1.0f;      // relative error at the top of the false-colour scale (1 = 100 %)
    bool hatchEmpty = true;          // hatch texels with no surface
    float zoom = 0.0f;               // output pixels per texel; 0 = fit on next draw
    glm::vec2 center{0.0f};          // texel at the centre of the view
    bool autoStats = false;
    double lastStatsTime = -1e9;
    BufferStats stats;
    std::string statsOf;
    std::string depthLikeRangeOf;    // a depth-like buffer whose display range was set from its values
    char refPath[512] = "";
    std::string refMessage;
    std::string figures;             // the error figures line of the current A/B (empty: none)
    std::string readout;             // the last texel readout under the pointer (also for scripts)
    glm::vec4 imageRect{0.0f}, statsButtonRect{0.0f};  // x0 y0 x1 y1 in window units, last frame (for scripts)
};
// The inspector as a fixed pane at pos/size (window units).
void drawInspector(InspectorState& s, ViewerServices& services, double now, ImVec2 pos, ImVec2 size);
// The false-colour legend of the relative-error view: colour bar, ticks, labels (0 .. scale).
void drawHeatLegend(float scale, float width);

}  // namespace deepgi::ui
