#pragma once
// The viewer's ImGui panels. They only draw and edit state; anything that touches GL or the renderer goes through
// ViewerServices, which the app implements.
#include "renderer/core/camera.h"
#include "renderer/core/settings.h"
#include "renderer/core/texture_registry.h"
#include "renderer/passes/buffer_view_pass.h"
#include "renderer/renderer.h"

#include <deque>
#include <map>
#include <string>
#include <vector>

namespace deepgi::ui {

constexpr const char* kReferenceName = "Reference (EXR)";

struct BufferStats {
    bool valid = false;
    int channels = 0;
    double min[4] = {0, 0, 0, 0}, max[4] = {0, 0, 0, 0}, mean[4] = {0, 0, 0, 0};  // over finite values
    size_t nan = 0, inf = 0, negative = 0, texels = 0;
};
BufferStats computeStats(const FloatImage& img);

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

// ---- profiler ----------------------------------------------------------------------------------------------
struct ProfilerState {
    static constexpr int kHistory = 120;
    std::deque<float> frameMs, cpuFrameMs;
    std::map<std::string, std::deque<float>> passMs;
    std::vector<std::string> passOrder;
    void record(const std::vector<PassTiming>& timings, double cpuFrameMs);
};
void drawProfilerPanel(const ProfilerState& p, const MemoryReport& mem, int width, int height);

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
    bool sidebar = true;
    std::string status;                    // bottom-left status line
};
// The header bar along the top of the viewport (x0..x1 in window units). Returns its height.
float drawViewportHeader(ViewportState& v, ViewerServices& services, float x0, float x1);
// Shader errors overlay (red), at the bottom of the viewport; nothing if there are none.
void drawShaderErrors(const std::vector<std::string>& errors, float x0, float y1, float width);

// ---- inspector ---------------------------------------------------------------------------------------------
struct InspectorState {
    bool open = false;
    std::string a = "Normal 1", b;   // b empty: no split
    int level = 0;
    BufferViewParams params;
    float zoom = 0.0f;               // output pixels per texel; 0 = fit on next draw
    glm::vec2 center{0.0f};          // texel at the centre of the view
    bool autoStats = false;
    double lastStatsTime = -1e9;
    BufferStats stats;
    std::string statsOf;
    char refPath[512] = "";
    std::string refMessage;
};
void drawInspector(InspectorState& s, ViewerServices& services, double now);

}  // namespace deepgi::ui
