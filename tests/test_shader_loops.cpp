// Every loop of the project's shaders has a compile-time bound (issue 11, the slow-shader watchdog): a loop counts
// up to a constant (an integer literal or an upper-case `const int` / #define of the shaders) and breaks at a
// uniform count, so no uniform value can make a pass run unbounded. The constants are at least the maxima of the
// settings that feed the counts, so the break, not the bound, ends every loop a setting allows.
#include "renderer/core/settings.h"
#include "renderer/passes/bilateral_blur_pass.h"
#include "renderer/scene/lighting.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The source without // and /* */ comments.
std::string stripComments(const std::string& src) {
    std::string out;
    for (size_t i = 0; i < src.size();) {
        if (src.compare(i, 2, "//") == 0) {
            while (i < src.size() && src[i] != '\n') ++i;
        } else if (src.compare(i, 2, "/*") == 0) {
            const size_t end = src.find("*/", i + 2);
            i = end == std::string::npos ? src.size() : end + 2;
        } else {
            out += src[i++];
        }
    }
    return out;
}

// Upper-case integer constants the sources define: `const int NAME = 6;` and `#define NAME 6`.
std::map<std::string, long> integerConstants(const std::string& src) {
    std::map<std::string, long> c;
    static const std::regex constRe(R"(const\s+int\s+([A-Z][A-Z0-9_]*)\s*=\s*(\d+)\s*;)");
    static const std::regex defineRe(R"(#\s*define\s+([A-Z][A-Z0-9_]*)\s+(\d+)\b)");
    for (const auto* re : {&constRe, &defineRe})
        for (auto it = std::sregex_iterator(src.begin(), src.end(), *re); it != std::sregex_iterator(); ++it)
            c[(*it)[1]] = std::stol((*it)[2]);
    return c;
}

struct Loop {
    std::string header;  // what is inside for ( ... ), or "while" / "do"
    std::string problem; // "" when the loop has a constant bound
};

// Checks every loop of src against the rule, with `constants` the names a bound may use.
std::vector<Loop> loops(const std::string& src, const std::map<std::string, long>& constants) {
    std::vector<Loop> out;
    static const std::regex loopRe(R"(\b(for|while|do)\b)");
    for (auto it = std::sregex_iterator(src.begin(), src.end(), loopRe); it != std::sregex_iterator(); ++it) {
        const std::string kind = (*it)[1];
        if (kind != "for") {
            out.push_back({kind, "a " + kind + " loop has no counted bound (write a for loop up to a constant)"});
            continue;
        }
        size_t open = src.find('(', size_t(it->position()));
        int depth = 0;
        size_t close = open;
        for (; close < src.size(); ++close) {
            if (src[close] == '(') ++depth;
            if (src[close] == ')' && --depth == 0) break;
        }
        const std::string header = src.substr(open + 1, close - open - 1);
        std::vector<std::string> parts;
        std::stringstream ss(header);
        for (std::string part; std::getline(ss, part, ';');) parts.push_back(part);
        Loop loop{std::regex_replace(header, std::regex(R"(\s+)"), " "), ""};
        std::smatch m;
        static const std::regex condRe(R"(^\s*([A-Za-z_]\w*)\s*(<=|<)\s*(.+?)\s*$)");
        if (parts.size() != 3 || !std::regex_match(parts[1], m, condRe)) {
            loop.problem = "the condition is not `variable < bound` or `variable <= bound`";
        } else {
            const std::string var = m[1], bound = m[3];
            static const std::regex stepRe(R"(^\s*(\+\+\s*(\w+)|(\w+)\s*\+\+|(\w+)\s*\+=\s*\d+)\s*$)");
            std::smatch sm;
            const bool stepOk = std::regex_match(parts[2], sm, stepRe) &&
                                (sm[2] == var || sm[3] == var || sm[4] == var);
            if (!stepOk) loop.problem = "the step does not count " + var + " up";
            static const std::regex tokenRe(R"([A-Za-z_]\w*)");
            for (auto t = std::sregex_iterator(bound.begin(), bound.end(), tokenRe); t != std::sregex_iterator(); ++t)
                if (!constants.count(t->str())) loop.problem = "the bound uses '" + t->str() + "', not a constant";
            if (bound.find_first_not_of("0123456789+-*/() ABCDEFGHIJKLMNOPQRSTUVWXYZ_") != std::string::npos &&
                loop.problem.empty())
                loop.problem = "the bound '" + bound + "' is not a constant expression";
        }
        out.push_back(loop);
    }
    return out;
}

TEST(ShaderLoops, CheckerTellsConstantBoundsFromUniformOnes) {
    const std::map<std::string, long> k{{"MAX_TAPS", 99}};
    auto check = [&](const std::string& src) { return loops(src, k).at(0).problem; };
    EXPECT_EQ(check("for (int i = 0; i < MAX_TAPS; ++i) { if (i >= uTaps) break; }"), "");
    EXPECT_EQ(check("for (int side = -1; side <= 1; side += 2) {}"), "");
    EXPECT_EQ(check("for (int r = 1; r <= MAX_TAPS + 1; r++) {}"), "");
    EXPECT_NE(check("for (int i = 0; i < uTaps; ++i) {}"), "");
    EXPECT_NE(check("for (int i = 0; i < MAX_OTHER; ++i) {}"), "") << "an undefined upper-case name is no constant";
    EXPECT_NE(check("for (int k = m; k > 0; --k) {}"), "");
    EXPECT_NE(check("for (int i = 0; i < 8; i += uStep) {}"), "");
    EXPECT_NE(check("for (;;) {}"), "");
    EXPECT_NE(check("while (x < 3) {}"), "");
}

// Loops allowed to count up to a uniform (none now: the gather's two loops have their bounds too). Kept so that a
// file under rewrite can be listed here, by file and loop text, rather than its loop fixed in two places.
const std::set<std::pair<std::string, std::string>> kPendingLoops = {};

TEST(ShaderLoops, EveryLoopOfTheShadersHasAConstantBound) {
    std::map<std::string, std::string> sources;
    std::map<std::string, long> constants;
    for (const auto& f : fs::directory_iterator(DEEPGI_SHADER_DIR)) {
        const std::string ext = f.path().extension().string();
        if (ext != ".frag" && ext != ".vert" && ext != ".geom" && ext != ".glsl" && ext != ".comp") continue;
        sources[f.path().filename().string()] = stripComments(readText(f.path()));
    }
    ASSERT_GT(sources.size(), 10u) << DEEPGI_SHADER_DIR;
    // The constants of the included files are visible everywhere (a bound naming one a file does not see would
    // not compile, which the GL tests catch).
    for (const auto& [file, src] : sources)
        for (const auto& [name, value] : integerConstants(src)) constants[name] = value;
    int checked = 0, pending = 0;
    for (const auto& [file, src] : sources)
        for (const Loop& loop : loops(src, constants)) {
            ++checked;
            if (kPendingLoops.count({file, loop.header})) {
                ++pending;
                continue;
            }
            EXPECT_EQ(loop.problem, "") << "shaders/" << file << ": for (" << loop.header << ")";
        }
    std::printf("%d loops in %zu shader files, %d of them pending in files being rewritten\n", checked, sources.size(), pending);
    EXPECT_GT(checked, 5);
}

// The bounds hold every count the settings allow: a smaller bound would clamp a setting silently.
TEST(ShaderLoops, BoundsCoverTheSettingsRanges) {
    std::map<std::string, long> constants;
    for (const auto& f : fs::directory_iterator(DEEPGI_SHADER_DIR))
        for (const auto& [name, value] : integerConstants(stripComments(readText(f.path())))) constants[name] = value;
    ASSERT_TRUE(constants.count("MAX_SPIRAL_TAPS") && constants.count("MAX_BLUR_RADIUS") && constants.count("MAX_LIGHTS") &&
                constants.count("MAX_VISIBILITY_STEPS"));
    EXPECT_GE(double(constants["MAX_SPIRAL_TAPS"]), deepgi::findSetting("radiosity.samples")->max);
    EXPECT_GE(double(constants["MAX_BLUR_RADIUS"]), deepgi::findSetting("blur.radius")->max);
    // The taps the blur pass asks for and the weights it uploads (kMaxBlurTaps + 1 of them for uKernel[MAX_BLUR_RADIUS + 1]).
    EXPECT_EQ(constants["MAX_BLUR_RADIUS"], deepgi::kMaxBlurTaps);
    EXPECT_GE(double(constants["MAX_VISIBILITY_STEPS"]), deepgi::findSetting("radiosity.visibility_steps")->max);
    EXPECT_EQ(constants["MAX_LIGHTS"], deepgi::kMaxGpuLights);
    // The unrolled light loop's length: a smaller one would drop the lights past it.
    EXPECT_EQ(constants["MAX_UNROLLED_LIGHTS"], deepgi::kUnrolledLights);
    // Mip levels: a texture of GL's largest size has log2(size) + 1 levels.
    EXPECT_GE(constants["MAX_MIP_LEVELS"], 15);
}

}  // namespace
