#pragma once
// `deepgi view --script FILE`: timed actions for tests and demos, one per line ('#' starts a comment).
//   wait N                      let N frames render
//   sleep S                     keep rendering for S seconds (e.g. past the twice-a-second shader poll)
//   key NAME [shift] [ctrl] [alt]   press and release a key (GLFW names: KP_1, F12, HOME, N, GRAVE_ACCENT, ...)
//   drag BUTTON X0 Y0 X1 Y1 [shift] [ctrl] [alt]   BUTTON = left|middle|right, window coordinates
//   scroll N                    wheel notches at the viewport centre (> 0 zooms in)
//   set KEY=VALUE               change a setting (see `deepgi settings`)
//   show "BUFFER"               show a buffer in the viewport ("Final Display" to go back)
//   inspect "A" ["B"]           open the inspector on buffer A (and B right of the split)
//   reference PATH              load a reference EXR; it is then the buffer "Reference (EXR)"
//   camera "NAME"               switch to a glTF camera
//   screenshot PATH             PNG of the whole window (back buffer, before the swap) after this frame
//   panel settings|profiler|view   bring a sidebar tab to the front (shows the sidebar)
//   resize WxH                  resize the window (window units)
//   capture                     what F12 does (final PNG, buffers if chosen, settings.json)
//   shell COMMAND...            run a shell command (e.g. edit a shader), waits for it
//   dump_errors PATH            write the current shader errors, one per line (empty file if none)
//   reload                      what F5 does; converge N renders N frames at once
//   quit                        exit now (the end of the script also exits)
#include <string>
#include <vector>

namespace deepgi {

struct ScriptAction {
    std::string verb;
    std::vector<std::string> args;  // quotes removed
    int line = 0;
};

// Throws std::runtime_error("FILE:LINE: problem") for unknown verbs or wrong argument counts.
std::vector<ScriptAction> parseViewerScript(const std::string& path);
// GLFW key code for a name like "KP_1", "F12", "A", "HOME"; -1 if unknown.
int glfwKeyFromName(const std::string& name);

}  // namespace deepgi
