// The deepgi binary end to end: outputs of `render`, the buffer report, and clear errors for bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "renderer/core/image_io.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>

namespace fs = std::filesystem;

namespace {

struct RunResult {
    int status;
    std::string output;  // stdout and stderr
};

RunResult run(const std::string& args) {
    const std::string cmd = std::string(DEEPGI_BINARY) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    RunResult r{-1, ""};
    if (!p) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
    int st = pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("deepgi_cli_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(Cli, RenderWritesImagesBuffersTimingsAndSettings) {
    fs::path out = tempDir("render");
    RunResult r = run("render " + std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf --size 64x48 --frames 3 "
                      "--buffers all --set radiosity.samples=8 --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* f : {"final.png", "final.exr", "timings.json", "settings.json", "depth_1.exr", "depth_2.exr",
                          "normal_1.exr", "albedo_2.exr", "input_radiance_1.exr", "output_radiance.exr",
                          "reprojected_radiance.exr", "last_depth.exr", "shadow_map_1.exr"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    nlohmann::json t = nlohmann::json::parse(std::ifstream(out / "timings.json"));
    EXPECT_EQ(t["frames"], 3);
    EXPECT_GE(t["passes"].size(), 6u);
    for (const auto& p : t["passes"]) EXPECT_GE(p["median_ms"].get<double>(), 0.0);
    nlohmann::json s = nlohmann::json::parse(std::ifstream(out / "settings.json"));
    EXPECT_EQ(s["radiosity.samples"], 8);
    fs::remove_all(out);
}

// --warmup: frames rendered before the timed ones are ordinary frames (the image is that of rendering them all timed),
// only the timed ones are in timings.json, and it says whether the probes had settled.
TEST(Cli, RenderWarmupFramesAreRenderedButNotTimed) {
    const std::string box = std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf";
    // Every probe updated each frame, settled after 2 updates.
    const std::string common = " --size 32x24 --set probes.settle_updates=2 --set probes.rays_per_frame=1048576 --out ";
    fs::path dir = tempDir("warmup");
    RunResult early = run("render " + box + " --frames 1" + common + (dir / "early").string());
    ASSERT_EQ(early.status, 0) << early.output;
    EXPECT_NE(early.output.find("(probes still updating)"), std::string::npos) << early.output;
    RunResult warm = run("render " + box + " --warmup 3 --frames 2" + common + (dir / "warm").string());
    ASSERT_EQ(warm.status, 0) << warm.output;
    EXPECT_NE(warm.output.find("after 3 warm-up frames"), std::string::npos) << warm.output;
    EXPECT_NE(warm.output.find("(probes settled)"), std::string::npos) << warm.output;
    RunResult all = run("render " + box + " --frames 5" + common + (dir / "all").string());
    ASSERT_EQ(all.status, 0) << all.output;

    nlohmann::json early_t = nlohmann::json::parse(std::ifstream(dir / "early" / "timings.json"));
    nlohmann::json warm_t = nlohmann::json::parse(std::ifstream(dir / "warm" / "timings.json"));
    EXPECT_EQ(early_t["probes_settled"], false);
    EXPECT_EQ(warm_t["probes_settled"], true);
    // The probe update's own cost: the frame that updated them reports it, settled frames none.
    EXPECT_EQ(early_t["probe_update_frames"], 1);
    EXPECT_GT(early_t["probe_update_cpu_ms"].get<double>(), 0.0);
    EXPECT_GT(early_t["probe_update_span_ms"].get<double>(), 0.0);
    EXPECT_EQ(warm_t["probe_update_frames"], 0);
    EXPECT_EQ(warm_t["probe_update_cpu_ms"].get<double>(), 0.0);
    EXPECT_EQ(warm_t["frames"], 2);
    EXPECT_EQ(warm_t["warmup_frames"], 3);
    ASSERT_EQ(warm_t["frames_ms"].size(), 2u);
    for (const auto& ms : warm_t["frames_ms"]) EXPECT_GT(ms.get<double>(), 0.0);

    auto pixels = [&](const char* run) { return deepgi::readImage((dir / run / "final.exr").string()).pixels; };
    const std::vector<float> warmPixels = pixels("warm");
    ASSERT_FALSE(warmPixels.empty());
    EXPECT_TRUE(warmPixels == pixels("all")) << "3 warm-up + 2 timed frames differ from 5 frames";
    EXPECT_FALSE(warmPixels == pixels("early")) << "the frame count changes nothing: the check is blind";
    fs::remove_all(dir);
}

TEST(Cli, BuffersReportsSeedLayoutTotals) {
    RunResult r = run("buffers " + std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf --size 320x180 --set radiosity.resolution=full");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("G-buffer:  176 bits per pixel"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("radiosity: 128 bits per pixel"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("scene load peak: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("load.memory_budget of 4096 MiB"), std::string::npos) << r.output;
}

TEST(Cli, MalformedGltfIsAClearErrorNamingTheFile) {
    fs::path dir = tempDir("bad");
    fs::path bad = dir / "broken.gltf";
    std::ofstream(bad) << "{ \"asset\": {\"version\": \"2.0\"}, \"meshes\": [ ";
    RunResult r = run("render " + bad.string() + " --size 32x32 --frames 1 --out " + (dir / "out").string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("broken.gltf"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    RunResult missing = run("render " + (dir / "nope.glb").string() + " --frames 1");
    EXPECT_NE(missing.status, 0);
    EXPECT_NE(missing.output.find("nope.glb"), std::string::npos) << missing.output;
    fs::remove_all(dir);
}

TEST(Cli, BadOptionsAreClearErrors) {
    RunResult size = run("render --size 0x10 --frames 1");
    EXPECT_NE(size.status, 0);
    EXPECT_NE(size.output.find("--size"), std::string::npos) << size.output;
    RunResult set = run("render --set radiosity.samples=lots --frames 1");
    EXPECT_NE(set.status, 0);
    EXPECT_NE(set.output.find("radiosity.samples"), std::string::npos) << set.output;
    RunResult cam = run("render " + std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf --camera nosuch --frames 1 --size 16x16");
    EXPECT_NE(cam.status, 0);
    EXPECT_NE(cam.output.find("front"), std::string::npos) << "lists the available cameras: " << cam.output;
}

TEST(Cli, ShaderThatFailsToCompileIsAClearErrorWithFileAndLine) {
    fs::path dir = tempDir("shaders");
    fs::copy(fs::path(DEEPGI_SHADER_DIR), dir / "shaders");
    {
        std::ofstream f(dir / "shaders" / "composite.frag", std::ios::app);
        f << "\nthis is not glsl;\n";
    }
    RunResult r = run("render " + std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf --size 16x16 --frames 1 --shaders " +
                      (dir / "shaders").string() + " --out " + (dir / "out").string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("composite.frag:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("failed to compile"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find((dir / "shaders").string() + "/composite.frag"), std::string::npos)
        << "names the --shaders folder: " << r.output;
    fs::remove_all(dir);
}

// unclear messages (issue 11): the size error reads the same in every sub-command and says what is wrong with
// the number; an unknown sub-command is named; out-of-range settings name key, value and range; a FIFO is no
// "File not found".
TEST(Cli, MessagesNameWhatIsWrong) {
    const std::string box = std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf";
    RunResult render = run("render " + box + " --size 99999999x1 --frames 1");
    RunResult reference = run("reference " + box + " --size 99999999x1 --spp 1");
    for (const RunResult* r : {&render, &reference}) {
        EXPECT_NE(r->status, 0);
        EXPECT_NE(r->output.find("--size: invalid size '99999999x1': width '99999999' is not a positive integer"),
                  std::string::npos) << r->output;
    }
    RunResult big = run("render " + box + " --size 70000x1 --frames 1");
    EXPECT_NE(big.output.find("width must be between 1 and 65536"), std::string::npos) << big.output;

    RunResult sub = run("rendr " + box);
    EXPECT_NE(sub.status, 0);
    EXPECT_NE(sub.output.find("unknown subcommand 'rendr'"), std::string::npos) << sub.output;
    EXPECT_NE(sub.output.find("render"), std::string::npos) << "lists the sub-commands: " << sub.output;

    RunResult set = run("render " + box + " --size 16x16 --frames 1 --set light.sun_intensity=-1");
    EXPECT_NE(set.status, 0);
    EXPECT_NE(set.output.find("'light.sun_intensity' = -1 is out of range [0, 1e+06] W/m^2"), std::string::npos)
        << set.output;
    fs::path dir = tempDir("messages");
    std::ofstream(dir / "s.json") << "{\"temporal.alpha\": 1}";
    RunResult file = run("render " + box + " --size 16x16 --frames 1 --settings " + (dir / "s.json").string());
    EXPECT_NE(file.status, 0);
    EXPECT_NE(file.output.find("s.json: setting 'temporal.alpha' = 1 is out of range"), std::string::npos) << file.output;

    ASSERT_EQ(mkfifo((dir / "pipe.gltf").c_str(), 0600), 0);
    RunResult fifo = run("render " + (dir / "pipe.gltf").string() + " --size 16x16 --frames 1");
    EXPECT_NE(fifo.status, 0);
    EXPECT_NE(fifo.output.find("pipe.gltf: is a FIFO (named pipe), not a regular file"), std::string::npos)
        << fifo.output;
    fs::remove_all(dir);
}
