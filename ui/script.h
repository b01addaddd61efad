#pragma once
// `deepgi view --script FILE`: timed actions for tests and demos, one per line ('#' starts a comment).
//   wait N                      let N frames render
//   sleep S                     keep rendering for S seconds (e.g. past the twice-a-second shader poll)
//   key NAME [shift] [ctrl] [alt]   press and release a key (GLFW names: KP_1, F12, HOME, N, GRAVE_ACCENT, ...)
//   drag BUTTON X0 Y0 X1 Y1 [shift] [ctrl] [alt]   BUTTON = left|middle|right, window coordinates; from the
//                               viewport it navigates, from any window (the divider, a slider) the UI gets it
//   hover X Y                   move the pointer there (over any window: tooltips, the inspector's readout)
//   click X Y [left|middle|right] [shift] [ctrl] [alt]   press there this frame, release the next (any window:
//                               buttons, tabs, lists; over the viewport where no window is: select, confirm a transform)
//   mousemove X Y               the pointer moves there (over the viewport: what G / R / S follow)
//   scroll N [X Y]              wheel notches (> 0 up) at X Y (default: the viewport centre), given to the window
//                               under that point: the inspector zooms, the viewport dollies
//   set KEY=VALUE               change a setting (see `deepgi settings`)
//   show "BUFFER"               show a buffer in the viewport ("Final Display" to go back)
//   inspect "A" ["B"]           open the inspector on buffer A (and B right of the split)
//   compare MODE                inspector view: a, b, wipe, diff (|A - B|) or relative (|A - B| / B, false colour)
//   reference PATH              load a reference EXR; it is then the buffer "Reference (EXR)"
//   pathtrace off|full|split    "Path trace this view": off, the path tracer full-viewport, or split against the frame
//   camera "NAME"               switch to a glTF camera
//   screenshot PATH             PNG of the whole window (back buffer, before the swap) after this frame
//   panel item|settings|profiler|view|pipeline   bring a sidebar tab to the front (shows the sidebar)
//   resize WxH                  resize the window (window units)
//   capture                     what F12 does (final PNG, buffers if chosen, settings.json, camera.json)
//   profiler_csv PATH           write the profiler's history as CSV (what its "Export CSV" button does)
//   shell COMMAND...            run a shell command (e.g. edit a shader), waits for it
//   dump_errors PATH            write the current shader errors, one per line (empty file if none)
//   dump_figures PATH           write the inspector's and the path tracer's error figures lines
//   reload                      what F5 does
//   converge N                  render N frames at once (anywhere: before the first frame it runs after it)
//   stats PATH                  write JSON: the recent frame times (ms), the render size and scale, the viewport and
//                               window sizes, the target frame time, whether the camera is moving, the keys handled
//   dump_scene PATH             write JSON: every node (name, local TRS, rotation in degrees, world position,
//                               visibility), the lights, the selection, the transform tool, the undo steps, the
//                               default sun's settings, the timeline, the last save's message, the outliner's rows
//   save PATH                   what File > Save As does with that path (its message goes to dump_scene)
//   timeline play|pause|SECONDS play, pause or scrub the scene's animation
//   quit                        exit now (the end of the script also exits)
// Every failure, when parsing or while running, names FILE:LINE and says why; the viewer then exits with 1.
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace deepgi::ui {

struct ScriptAction {
    std::string verb;
    std::vector<std::string> args;  // quotes removed
    int line = 0;
};

// Throws std::runtime_error("FILE:LINE: problem") for unknown verbs, wrong argument counts, bad numbers or keys.
std::vector<ScriptAction> parseViewerScript(const std::string& path);
// GLFW key code for a name like "KP_1", "F12", "A", "HOME"; -1 if unknown.
int glfwKeyFromName(const std::string& name);

// What the script may do to the viewer. Each call may throw std::runtime_error with the reason (no location: the
// runner adds FILE:LINE).
class ScriptHost {
public:
    virtual ~ScriptHost() = default;
    virtual bool scriptReady() = 0;  // false until the first frame has rendered (buffers exist from then on)
    virtual bool scriptBusy() = 0;   // an action spanning frames (a drag over a window) is still being played
    virtual void scriptKey(int glfwKey, int glfwMods) = 0;
    virtual void scriptDrag(int glfwButton, glm::dvec2 from, glm::dvec2 to, int glfwMods) = 0;
    // Pointer for this frame's UI (hover/click): position, and which buttons are down.
    virtual void scriptPointer(glm::dvec2 at, int glfwButton, bool down, int glfwMods = 0) = 0;
    virtual void scriptMouseMove(glm::dvec2 at) = 0;
    virtual void scriptScroll(double notches, const glm::dvec2* at) = 0;
    virtual void scriptSet(const std::string& assignment) = 0;
    virtual void scriptShow(const std::string& buffer) = 0;
    virtual void scriptInspect(const std::string& a, const std::string& b) = 0;
    virtual void scriptCompare(const std::string& mode) = 0;
    virtual void scriptReference(const std::string& path) = 0;
    virtual void scriptPathTrace(const std::string& mode) = 0;
    virtual void scriptCamera(const std::string& name) = 0;
    virtual void scriptScreenshot(const std::string& path) = 0;  // after this frame
    virtual void scriptPanel(const std::string& name) = 0;
    virtual void scriptResize(int w, int h) = 0;
    virtual void scriptCapture() = 0;
    virtual void scriptProfilerCsv(const std::string& path) = 0;
    virtual void scriptDumpErrors(const std::string& path) = 0;
    virtual void scriptDumpFigures(const std::string& path) = 0;
    virtual void scriptReload() = 0;
    virtual void scriptConverge(int frames) = 0;
    virtual void scriptStats(const std::string& path) = 0;
    virtual void scriptDumpScene(const std::string& path) = 0;
    virtual void scriptSave(const std::string& path) = 0;
    virtual void scriptTimeline(const std::string& what) = 0;  // "play", "pause" or seconds (checked by the parser)
};

// Runs a parsed script, a few actions per frame: `wait`, `sleep`, `screenshot` and `click` end a frame's turn.
class ScriptRunner {
public:
    ScriptRunner() = default;
    ScriptRunner(std::string path, std::vector<ScriptAction> actions) : path_(std::move(path)), actions_(std::move(actions)) {}
    bool active() const { return !path_.empty(); }
    // Called once per frame before it renders. Failures are printed as "deepgi view: FILE:LINE: reason".
    void step(ScriptHost& host, double now);
    bool finished() const { return finished_; }
    bool failed() const { return failed_; }
    // A failure found outside step() (e.g. a screenshot that could not be written at the end of the frame).
    void fail(const std::string& why);

private:
    std::string where(const ScriptAction& a) const;
    std::string path_;
    std::vector<ScriptAction> actions_;
    size_t pc_ = 0;
    int waitFrames_ = 0;
    double sleepUntil_ = 0.0;
    bool releasePending_ = false;
    int releaseButton_ = 0, releaseMods_ = 0;
    glm::dvec2 releaseAt_{0.0};
    int lastLine_ = 0;
    bool finished_ = false, failed_ = false;
};

}  // namespace deepgi::ui
