// The deepgi binary end to end: outputs of `render`, the buffer report, and clear errors for bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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

TEST(Cli, BuffersReportsSeedLayoutTotals) {
    RunResult r = run("buffers " + std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf --size 320x180");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("G-buffer:  176 bits per pixel"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("radiosity: 128 bits per pixel"), std::string::npos) << r.output;
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
    fs::remove_all(dir);
}
