// The slow-shader watchdog (issue 11): after a hot reload, a pass whose rebuilt program does not finish within
// debug.shader_watchdog_ms is named in the shader errors (the viewer's overlay lists them) and gets its previous
// program back. llvmpipe cannot be stopped inside a draw (it caps loop iterations instead), so the shader made slow
// here is finite: seconds of work per frame against a limit of a fraction of that.
#include "gl_fixture.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace deepgi;
using namespace deepgi::test;

namespace {

constexpr int kW = 80, kH = 60;

// The limit must exceed what a fast program's first frame costs on llvmpipe (the JIT compiles a new program at its
// first draw: 350 ms measured for composite.frag on a loaded machine) and stay well below the slow program's frame
// (kSlowLoops iterations per pixel: about 1 s per 3000 pixels and 4 trigonometric calls per iteration with one
// llvmpipe thread, so about 5 s here).
constexpr int kSlowLoops = 60000;
constexpr int kLimitMs = 1200;

// A still frame that depends on no earlier frame (no temporal filter, one bounce, fixed taps, no probes, exact
// second layer): the frame after the watchdog's history reset can equal the one before the reload.
Settings independentFrames() {
    Settings s;
    s.probesEnabled = false;
    s.temporal = false;
    s.varyTaps = false;
    s.damping = 1.0f;
    s.generation = GBufferGeneration::DepthPeel;
    return s;
}

class Watchdog : public GLTest {
protected:
    void SetUp() override {
        GLTest::SetUp();
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("deepgi_watchdog_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::copy(DEEPGI_SHADER_DIR, dir_, fs::copy_options::recursive);
    }
    void TearDown() override {
        renderer_.reset();
        GLTest::TearDown();
        fs::remove_all(dir_);
    }
    Renderer& renderer(TimingMode timing) {
        renderer_ = std::make_unique<Renderer>(RendererOptions{dir_.string(), timing});
        auto scene = cornellScene();
        renderer_->setScene(scene);
        renderer_->resize(kW, kH);
        renderer_->setCamera(selectCamera(*scene, "front"));
        return *renderer_;
    }
    // Rewrites composite.frag so that the display output is pure red; with loops > 0 every pixel first runs a loop
    // of that many iterations of eight sines and cosines that the output depends on. llvmpipe caps loop
    // iterations (nested loops of 900^2 and 2000^2 iterations took the same time), so the work per iteration, not
    // the count, makes it slow.
    void editComposite(int loops) {
        const fs::path file = dir_ / "composite.frag";
        std::ifstream in(file);
        std::stringstream ss;
        ss << in.rdbuf();
        std::string src = ss.str();
        const std::string anchor = "    oDisplay = vec4(";
        const size_t at = src.find(anchor);
        ASSERT_NE(at, std::string::npos) << "composite.frag no longer writes `oDisplay = vec4(`";
        std::string slow = "    float slow = 0.0;\n";
        if (loops > 0)
            slow += "    for (int i = 0; i < " + std::to_string(loops) + "; ++i) {\n"
                    "        float t = float(i) * 1e-3 + gl_FragCoord.x;\n"
                    "        slow += sin(t) * cos(1.7 * t) + sin(2.3 * t) * cos(3.1 * t);\n"
                    "        slow += sin(4.1 * t) * cos(5.3 * t) + sin(6.7 * t) * cos(7.9 * t);\n"
                    "    }\n";
        src.replace(at, anchor.size(), slow + "    oDisplay = vec4(1.0, 1e-30 * slow, 0.0, 1.0) + 0.0 * vec4(");
        std::ofstream(file, std::ios::trunc) << src;
    }
    static double meanAbsDiff(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
        if (a.size() != b.size() || a.empty()) return 1e9;
        double sum = 0.0;
        for (size_t i = 0; i < a.size(); ++i) sum += std::abs(int(a[i]) - int(b[i]));
        return sum / double(a.size()) / 255.0;
    }
    // Largest difference of one display byte, in steps of 1/255.
    static int maxByteDiff(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
        if (a.size() != b.size() || a.empty()) return 256;
        int worst = 0;
        for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
        return worst;
    }
    static double redFraction(const std::vector<unsigned char>& px) {
        size_t red = 0;
        for (size_t i = 0; i + 3 < px.size(); i += 4) red += px[i] == 255 && px[i + 1] == 0 && px[i + 2] == 0;
        return double(red) / double(px.size() / 4);
    }
    void checkSlowShaderIsRevertedAndReported(Renderer& r);
    fs::path dir_;
    std::unique_ptr<Renderer> renderer_;
};

void Watchdog::checkSlowShaderIsRevertedAndReported(Renderer& r) {
    Settings s = independentFrames();
    s.shaderWatchdogMs = kLimitMs;
    r.render(s);
    r.render(s);
    const std::vector<unsigned char> before = r.readDisplay();
    // The frames really are independent of the history the watchdog resets, up to the R11F_G11F_B10F stores'
    // dither, which follows the frame number (common.glsl sanitizeR11G11B10): one display step at most.
    r.resetHistory();
    r.render(s);
    const int cutDiff = maxByteDiff(before, r.readDisplay());
    std::printf("a frame after a cut differs from the one before by at most %d/255\n", cutDiff);
    ASSERT_LE(cutDiff, 1) << "a frame after a cut differs: the comparison below means nothing";
    ASSERT_TRUE(r.shaders().errors().empty());

    editComposite(kSlowLoops);
    ASSERT_EQ(r.shaders().reloadChanged(), 1);
    ASSERT_TRUE(r.shaders().errors().empty()) << r.shaders().errors()[0];
    ASSERT_TRUE(r.shaders().anyOnTrial());
    const auto t0 = std::chrono::steady_clock::now();
    r.render(s);
    const double frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const std::vector<unsigned char> slowFrame = r.readDisplay();
    std::printf("slow frame %.0f ms (limit %d ms), red %.3f of it\n", frameMs, kLimitMs, redFraction(slowFrame));
    EXPECT_GT(redFraction(slowFrame), 0.99) << "the reloaded (slow, red) program ran on that frame";
    EXPECT_FALSE(r.shaders().anyOnTrial());

    const auto& errors = r.shaders().errors();
    ASSERT_EQ(errors.size(), 1u);
    std::printf("%s\n", errors[0].c_str());
    EXPECT_NE(errors[0].find("composite.frag"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("pass 'Composite'"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("debug.shader_watchdog_ms = " + std::to_string(kLimitMs)), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find("previous program is restored"), std::string::npos) << errors[0];
    EXPECT_FALSE(r.historyValid()) << "a rejected program's frame must not feed the next";

    r.render(s);
    const std::vector<unsigned char> after = r.readDisplay();
    std::printf("next frame against the pre-reload one: at most %d/255 apart (mean %.2e); the slow frame: mean %.3f\n",
                maxByteDiff(before, after), meanAbsDiff(before, after), meanAbsDiff(before, slowFrame));
    EXPECT_LE(maxByteDiff(before, after), 1) << "the next frame is the pre-reload image";
    // The report stays (as a compile error does) until the file changes again; the unchanged file is not rebuilt.
    EXPECT_EQ(r.shaders().reloadChanged(), 0);
    EXPECT_EQ(r.shaders().errors().size(), 1u);
}


// The fence is waited on with the timeout (no glFinish around the passes).
TEST_F(Watchdog, SlowShaderAfterReloadIsReportedAndThePreviousProgramRestored) {
    Renderer& r = renderer(TimingMode::None);
    checkSlowShaderIsRevertedAndReported(r);
}

// The viewer's and the CLI's default timing: glFinish after each pass (the fence comes before it).
TEST_F(Watchdog, SlowShaderIsCaughtWithWallClockTiming) {
    Renderer& r = renderer(TimingMode::WallClock);
    checkSlowShaderIsRevertedAndReported(r);
}

// A fast edit passes its trial and stays; the watchdog then stops checking.
TEST_F(Watchdog, FastShaderPassesItsTrialAndStays) {
    Renderer& r = renderer(TimingMode::None);
    Settings s = independentFrames();
    s.shaderWatchdogMs = kLimitMs;
    r.render(s);
    editComposite(0);
    ASSERT_EQ(r.shaders().reloadChanged(), 1);
    for (int i = 0; i < gl::ShaderLibrary::kTrialUses; ++i) {
        EXPECT_TRUE(r.shaders().anyOnTrial()) << "frame " << i;
        r.render(s);
    }
    EXPECT_FALSE(r.shaders().anyOnTrial());
    EXPECT_TRUE(r.shaders().errors().empty()) << r.shaders().errors()[0];
    r.render(s);
    EXPECT_GT(redFraction(r.readDisplay()), 0.99) << "the edited program is kept";
}

// debug.shader_watchdog_ms = 0: no check, the slow program stays.
TEST_F(Watchdog, ZeroLimitTurnsTheCheckOff) {
    Renderer& r = renderer(TimingMode::None);
    Settings s = independentFrames();
    s.shaderWatchdogMs = 0;
    r.render(s);
    editComposite(kSlowLoops);
    ASSERT_EQ(r.shaders().reloadChanged(), 1);
    r.render(s);
    EXPECT_TRUE(r.shaders().errors().empty()) << r.shaders().errors()[0];
    EXPECT_GT(redFraction(r.readDisplay()), 0.99);
}

}  // namespace
