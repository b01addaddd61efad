#include "app/viewer_script.h"

#include <GLFW/glfw3.h>

#include <cctype>
#include <fstream>
#include <map>
#include <stdexcept>

namespace deepgi {

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
        {"KP_SUBTRACT", GLFW_KEY_KP_SUBTRACT}, {"PERIOD", GLFW_KEY_PERIOD}};
    auto it = named.find(n);
    return it == named.end() ? -1 : it->second;
}

std::vector<ScriptAction> parseViewerScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read script " + path);
    static const std::map<std::string, std::pair<int, int>> arity = {
        {"wait", {1, 1}}, {"sleep", {1, 1}}, {"key", {1, 4}}, {"drag", {5, 8}}, {"scroll", {1, 1}}, {"set", {1, 1}}, {"show", {1, 1}},
        {"inspect", {1, 2}}, {"reference", {1, 1}}, {"camera", {1, 1}}, {"screenshot", {1, 1}}, {"capture", {0, 0}}, {"panel", {1, 1}}, {"resize", {1, 1}}, {"shell", {1, 1000}},
        {"dump_errors", {1, 1}}, {"reload", {0, 0}}, {"converge", {1, 1}}, {"quit", {0, 0}}};
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
            throw std::runtime_error(where + "drag button must be left, middle or right");
        actions.push_back(std::move(a));
    }
    return actions;
}

}  // namespace deepgi
