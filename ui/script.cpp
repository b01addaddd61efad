// The viewer script: parsing (every argument checked before a window opens) and the per-frame interpreter.
#include "ui/script.h"

#include <GLFW/glfw3.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <algorithm>
#include <map>
#include <cmath>
#include <stdexcept>

namespace deepgi::ui {

namespace {

std::vector<std::string> split(const std::string& line, int lineNo, const std::string& path) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace((unsigned char)line[i])) ++i;
        if (i >= line.size() || line[i] == '#') break;
        std::string tok;
        if (line[i] == '"') {
            const size_t end = line.find('"', i + 1);
            if (end == std::string::npos) throw std::runtime_error(path + ":" + std::to_string(lineNo) + ": unterminated quote");
            tok = line.substr(i + 1, end - i - 1);
            i = end + 1;
        } else {
            while (i < line.size() && !std::isspace((unsigned char)line[i])) tok += line[i++];
        }
        out.push_back(tok);
    }
    return out;
}

}  // namespace

int glfwKeyFromName(const std::string& rawName) {
    std::string n;
    for (char c : rawName) n += char(std::toupper((unsigned char)c));
    if (n.rfind("KEY_", 0) == 0) n = n.substr(4);
    if (n.size() == 1 && n[0] >= 'A' && n[0] <= 'Z') return GLFW_KEY_A + (n[0] - 'A');
    if (n.size() == 1 && n[0] >= '0' && n[0] <= '9') return GLFW_KEY_0 + (n[0] - '0');
    if (n.size() == 4 && n.rfind("KP_", 0) == 0 && std::isdigit((unsigned char)n[3])) return GLFW_KEY_KP_0 + (n[3] - '0');
    if (n.size() >= 2 && n[0] == 'F' && std::isdigit((unsigned char)n[1])) {
        const int f = std::stoi(n.substr(1));
        if (f >= 1 && f <= 25) return GLFW_KEY_F1 + f - 1;
    }
    static const std::map<std::string, int> named = {
        {"HOME", GLFW_KEY_HOME}, {"END", GLFW_KEY_END}, {"ESCAPE", GLFW_KEY_ESCAPE}, {"ESC", GLFW_KEY_ESCAPE},
        {"ENTER", GLFW_KEY_ENTER}, {"SPACE", GLFW_KEY_SPACE}, {"TAB", GLFW_KEY_TAB}, {"GRAVE_ACCENT", GLFW_KEY_GRAVE_ACCENT},
        {"GRAVE", GLFW_KEY_GRAVE_ACCENT}, {"KP_DECIMAL", GLFW_KEY_KP_DECIMAL}, {"KP_ADD", GLFW_KEY_KP_ADD},
        {"KP_SUBTRACT", GLFW_KEY_KP_SUBTRACT}, {"PERIOD", GLFW_KEY_PERIOD}, {"BACKSPACE", GLFW_KEY_BACKSPACE},
        {"MINUS", GLFW_KEY_MINUS}, {"SLASH", GLFW_KEY_SLASH}, {"KP_ENTER", GLFW_KEY_KP_ENTER}, {"DELETE", GLFW_KEY_DELETE},
        {"KP_DIVIDE", GLFW_KEY_KP_DIVIDE}};
    auto it = named.find(n);
    return it == named.end() ? -1 : it->second;
}

std::vector<ScriptAction> parseViewerScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read script " + path);
    static const std::map<std::string, std::pair<int, int>> arity = {
        {"wait", {1, 1}}, {"sleep", {1, 1}}, {"key", {1, 4}}, {"drag", {5, 8}}, {"hover", {2, 2}}, {"click", {2, 6}}, {"mousemove", {2, 2}},
        {"scroll", {1, 3}}, {"set", {1, 1}}, {"show", {1, 1}}, {"inspect", {1, 2}}, {"compare", {1, 1}},
        {"reference", {1, 1}}, {"pathtrace", {1, 1}}, {"camera", {1, 1}}, {"screenshot", {1, 1}}, {"capture", {0, 0}},
        {"panel", {1, 1}}, {"resize", {1, 1}}, {"shell", {1, 1000}}, {"profiler_csv", {1, 1}}, {"dump_errors", {1, 1}},
        {"dump_figures", {1, 1}}, {"reload", {0, 0}}, {"converge", {1, 1}}, {"stats", {1, 1}}, {"quit", {0, 0}},
        {"dump_scene", {1, 1}}, {"save", {1, 1}}, {"timeline", {1, 1}}};
    std::vector<ScriptAction> actions;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const std::string where = path + ":" + std::to_string(lineNo) + ": ";
        std::vector<std::string> tok;
        const size_t first = line.find_first_not_of(" \t");
        // `shell` keeps the rest of the line verbatim.
        if (first != std::string::npos && line.compare(first, 6, "shell ") == 0) {
            actions.push_back({"shell", {line.substr(first + 6)}, lineNo});
            continue;
        }
        tok = split(line, lineNo, path);
        if (tok.empty()) continue;
        ScriptAction a{tok[0], {tok.begin() + 1, tok.end()}, lineNo};
        auto it = arity.find(a.verb);
        if (it == arity.end()) throw std::runtime_error(where + "unknown action '" + a.verb + "'");
        if (int(a.args.size()) < it->second.first || int(a.args.size()) > it->second.second)
            throw std::runtime_error(where + "wrong number of arguments for '" + a.verb + "'");
        if (a.verb == "key" && glfwKeyFromName(a.args[0]) < 0) throw std::runtime_error(where + "unknown key '" + a.args[0] + "'");
        if (a.verb == "drag" && a.args[0] != "left" && a.args[0] != "middle" && a.args[0] != "right")
            throw std::runtime_error(where + "drag button must be left, middle or right, got '" + a.args[0] + "'");
        if (a.verb == "click")
            for (size_t i = 2; i < a.args.size(); ++i)
                if (a.args[i] != "left" && a.args[i] != "middle" && a.args[i] != "right" && a.args[i] != "shift" &&
                    a.args[i] != "ctrl" && a.args[i] != "alt")
                    throw std::runtime_error(where + "click takes a button (left, middle, right) and modifiers (shift, ctrl, alt), got '" +
                                             a.args[i] + "'");
        if (a.verb == "scroll" && a.args.size() == 2)
            throw std::runtime_error(where + "scroll takes N, or N X Y (a position needs both coordinates)");
        // Numbers are checked here, so that a typo fails before the window opens, with its line.
        auto number = [&](size_t i, bool integer, double lo) {
            const std::string& t = a.args[i];
            char* end = nullptr;
            const double v = std::strtod(t.c_str(), &end);
            if (t.empty() || *end != '\0' || !std::isfinite(v) || (integer && v != double(long(v))))
                throw std::runtime_error(where + a.verb + ": '" + t + "' is not " + (integer ? "an integer" : "a number"));
            if (v < lo) throw std::runtime_error(where + a.verb + ": " + t + " must be at least " + std::to_string(int(lo)));
        };
        const double any = -1e300;
        if (a.verb == "wait" || a.verb == "converge") number(0, true, a.verb == "wait" ? 0 : 1);
        if (a.verb == "sleep") number(0, false, 0);
        if (a.verb == "scroll") for (size_t i = 0; i < a.args.size(); ++i) number(i, false, any);
        if (a.verb == "hover" || a.verb == "click" || a.verb == "mousemove") { number(0, false, any); number(1, false, any); }
        if (a.verb == "timeline" && a.args[0] != "play" && a.args[0] != "pause") {
            char* end = nullptr;
            const double t = std::strtod(a.args[0].c_str(), &end);
            if (a.args[0].empty() || *end != '\0' || !std::isfinite(t) || t < 0.0)
                throw std::runtime_error(where + "timeline takes play, pause or a time in seconds (>= 0), got '" + a.args[0] + "'");
        }
        if (a.verb == "drag") for (size_t i = 1; i <= 4; ++i) number(i, false, any);
        if (a.verb == "key" || a.verb == "drag")
            for (size_t i = a.verb == "key" ? 1 : 5; i < a.args.size(); ++i)
                if (a.args[i] != "shift" && a.args[i] != "ctrl" && a.args[i] != "alt")
                    throw std::runtime_error(where + a.verb + ": modifier must be shift, ctrl or alt, got '" + a.args[i] + "'");
        if (a.verb == "compare" && a.args[0] != "a" && a.args[0] != "b" && a.args[0] != "wipe" && a.args[0] != "diff" &&
            a.args[0] != "relative")
            throw std::runtime_error(where + "compare mode must be a, b, wipe, diff or relative, got '" + a.args[0] + "'");
        if (a.verb == "pathtrace" && a.args[0] != "off" && a.args[0] != "full" && a.args[0] != "split")
            throw std::runtime_error(where + "pathtrace must be off, full or split, got '" + a.args[0] + "'");
        if (a.verb == "panel" && a.args[0] != "settings" && a.args[0] != "profiler" && a.args[0] != "view" &&
            a.args[0] != "pipeline" && a.args[0] != "item")
            throw std::runtime_error(where + "panel must be item, settings, profiler, view or pipeline, got '" + a.args[0] + "'");
        if (a.verb == "resize") {
            int w = 0, h = 0;
            char x = 0, extra = 0;
            if (std::sscanf(a.args[0].c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 64 ||
                h < 64 || w > 16384 || h > 16384)
                throw std::runtime_error(where + "resize expects WxH between 64x64 and 16384x16384, got '" + a.args[0] + "'");
        }
        actions.push_back(std::move(a));
    }
    return actions;
}

// ---- interpreter -------------------------------------------------------------------------------------------

std::string ScriptRunner::where(const ScriptAction& a) const { return path_ + ":" + std::to_string(a.line) + ": "; }

void ScriptRunner::fail(const std::string& why) {
    std::fprintf(stderr, "deepgi view: %s:%d: %s\n", path_.c_str(), lastLine_, why.c_str());
    failed_ = finished_ = true;
}

void ScriptRunner::step(ScriptHost& host, double now) {
    if (!active() || finished_) return;
    if (releasePending_) {  // the second frame of a click
        host.scriptPointer(releaseAt_, releaseButton_, false, releaseMods_);
        releasePending_ = false;
        return;
    }
    if (host.scriptBusy()) return;
    if (waitFrames_ > 0) { --waitFrames_; return; }
    if (now < sleepUntil_) return;
    // Nothing is registered before the first frame: every verb waits for it (so `converge` or `inspect` may come first).
    if (!host.scriptReady()) return;
    while (pc_ < actions_.size()) {
        const ScriptAction& a = actions_[pc_++];
        lastLine_ = a.line;
        auto mods = [&](size_t from) {
            int m = 0;
            for (size_t i = from; i < a.args.size(); ++i) {
                if (a.args[i] == "shift") m |= GLFW_MOD_SHIFT;
                else if (a.args[i] == "ctrl") m |= GLFW_MOD_CONTROL;
                else if (a.args[i] == "alt") m |= GLFW_MOD_ALT;
            }
            return m;
        };
        auto button = [](const std::string& b) {
            return b == "left" ? GLFW_MOUSE_BUTTON_LEFT : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE : GLFW_MOUSE_BUTTON_RIGHT;
        };
        auto num = [&](size_t i) { return std::stod(a.args[i]); };  // checked by the parser
        try {
            const std::string& v = a.verb;
            if (v == "wait") { waitFrames_ = std::max(0, std::stoi(a.args[0]) - 1); return; }
            if (v == "sleep") { sleepUntil_ = now + num(0); return; }
            if (v == "key") host.scriptKey(glfwKeyFromName(a.args[0]), mods(1));
            else if (v == "drag") host.scriptDrag(button(a.args[0]), {num(1), num(2)}, {num(3), num(4)}, mods(5));
            else if (v == "hover") host.scriptPointer({num(0), num(1)}, -1, false);
            else if (v == "mousemove") host.scriptMouseMove({num(0), num(1)});
            else if (v == "click") {
                releaseAt_ = {num(0), num(1)};
                releaseButton_ = GLFW_MOUSE_BUTTON_LEFT;
                for (size_t i = 2; i < a.args.size(); ++i)
                    if (a.args[i] == "left" || a.args[i] == "middle" || a.args[i] == "right") releaseButton_ = button(a.args[i]);
                releaseMods_ = mods(2);
                host.scriptPointer(releaseAt_, releaseButton_, true, releaseMods_);
                releasePending_ = true;
                return;  // released on the next frame: the UI must see the button down for one frame
            } else if (v == "scroll") {
                const glm::dvec2 at = a.args.size() == 3 ? glm::dvec2(num(1), num(2)) : glm::dvec2(0.0);
                host.scriptScroll(num(0), a.args.size() == 3 ? &at : nullptr);
                return;  // the UI takes the wheel during this frame
            } else if (v == "set") host.scriptSet(a.args[0]);
            else if (v == "show") host.scriptShow(a.args[0]);
            else if (v == "inspect") host.scriptInspect(a.args[0], a.args.size() > 1 ? a.args[1] : std::string());
            else if (v == "compare") host.scriptCompare(a.args[0]);
            else if (v == "reference") host.scriptReference(a.args[0]);
            else if (v == "pathtrace") host.scriptPathTrace(a.args[0]);
            else if (v == "camera") host.scriptCamera(a.args[0]);
            else if (v == "screenshot") { host.scriptScreenshot(a.args[0]); return; }
            else if (v == "panel") host.scriptPanel(a.args[0]);
            else if (v == "resize") {
                int w = 0, h = 0;
                std::sscanf(a.args[0].c_str(), "%d%*c%d", &w, &h);
                host.scriptResize(w, h);
            } else if (v == "capture") host.scriptCapture();
            else if (v == "profiler_csv") host.scriptProfilerCsv(a.args[0]);
            else if (v == "shell") {
                const int rc = std::system(a.args[0].c_str());
                if (rc != 0) std::fprintf(stderr, "deepgi view: %sshell command returned %d (continuing)\n", where(a).c_str(), rc);
            } else if (v == "dump_errors") host.scriptDumpErrors(a.args[0]);
            else if (v == "dump_figures") host.scriptDumpFigures(a.args[0]);
            else if (v == "reload") host.scriptReload();
            else if (v == "stats") host.scriptStats(a.args[0]);
            else if (v == "dump_scene") host.scriptDumpScene(a.args[0]);
            else if (v == "save") host.scriptSave(a.args[0]);
            else if (v == "timeline") host.scriptTimeline(a.args[0]);
            else if (v == "converge") { host.scriptConverge(std::stoi(a.args[0])); return; }
            else if (v == "quit") { finished_ = true; return; }
        } catch (const std::exception& e) {
            fail(std::string(a.verb) + ": " + e.what());
            return;
        }
    }
    finished_ = true;  // end of the script
}

}  // namespace deepgi::ui
