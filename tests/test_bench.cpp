// deepgi bench: metric functions on known images, the Pareto front, the reference cache and a tiny bench run.
#include "renderer/bench/bench.h"
#include "renderer/bench/canvas.h"
#include "renderer/bench/metrics.h"
#include "renderer/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace deepgi;
using namespace deepgi::bench;
namespace fs = std::filesystem;

namespace {

FloatImage ramp(int w, int h) {
    FloatImage img{w, h, 3, std::vector<float>(size_t(w) * h * 3)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = 0.1f + 0.05f * float(x + y + c);
    return img;
}

FloatImage constant(int w, int h, float v) { return FloatImage{w, h, 3, std::vector<float>(size_t(w) * h * 3, v)}; }

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("deepgi_bench_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(BenchMetrics, IdenticalImages) {
    const FloatImage a = ramp(17, 11);
    EXPECT_DOUBLE_EQ(relativeMse(a, a), 0.0);
    EXPECT_DOUBLE_EQ(meanRelativeError(a, a), 0.0);
    EXPECT_NEAR(ssimDisplay(a, a), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(relativeChange(a, a), 0.0);
}

TEST(BenchMetrics, KnownPerturbation) {
    // Reference 0.5 everywhere, image 10 % brighter: analytic values with eps = 0.01.
    const FloatImage r = constant(8, 6, 0.5f), a = constant(8, 6, 0.55f);
    const double d = double(0.55f) - double(0.5f);
    EXPECT_NEAR(relativeMse(a, r), d * d / (0.25 + 0.01), 1e-9);
    EXPECT_NEAR(meanRelativeError(a, r), d / (0.5 + 0.01), 1e-9);
    EXPECT_NEAR(relativeChange(a, r), d / 0.5, 1e-6);
    // SSIM of two constant images is its luminance term (2ab + C1) / (a^2 + b^2 + C1).
    const double ya = linearToSrgb(0.55f), yb = linearToSrgb(0.5f), C1 = 1e-4;
    EXPECT_NEAR(ssimDisplay(a, r), (2 * ya * yb + C1) / (ya * ya + yb * yb + C1), 1e-5);
    // Values above 1 are clamped before the SSIM: 2 and 3 look the same.
    EXPECT_NEAR(ssimDisplay(constant(4, 4, 2.0f), constant(4, 4, 3.0f)), 1.0, 1e-9);
    // Half the pixels off by +0.1 and half exact: the mean relative error halves.
    FloatImage h = r;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) h.at(x, y, c) = 0.6f;
    EXPECT_NEAR(meanRelativeError(h, r), 0.5 * (double(0.6f) - 0.5) / 0.51, 1e-7);
}

TEST(BenchMetrics, SizeMismatchThrows) {
    EXPECT_THROW(relativeMse(constant(4, 4, 1), constant(4, 5, 1)), std::invalid_argument);
}

TEST(BenchMetrics, ParetoFront) {
    // (time, error): 0 and 2 and 4 are on the front; 1 is dominated by 0, 3 by 2, 5 duplicates 4's x with more error.
    const std::vector<Point2> p = {{1, 5}, {2, 6}, {3, 3}, {4, 3}, {5, 1}, {5, 2}, {0.5, NAN}};
    EXPECT_EQ(paretoFront(p), (std::vector<int>{0, 2, 4}));
    EXPECT_TRUE(paretoFront({}).empty());
    EXPECT_EQ(paretoFront({{1, 1}, {1, 1}}), (std::vector<int>{0}));
}

TEST(BenchCanvas, TextAndHeat) {
    Canvas c(40, 10, {255, 255, 255});
    EXPECT_EQ(c.text(0, 0, "A1", {0, 0, 0}), 12);
    // 'A' has its top row 01110: column 0 blank, column 1 set.
    EXPECT_EQ(c.get(0, 0).r, 255);
    EXPECT_EQ(c.get(1, 0).r, 0);
    EXPECT_EQ(heat(0.0).r, 0);
    EXPECT_GT(heat(1.0).g, 200);
}

TEST(BenchReference, SecondCallHitsTheCache) {
    Scene scene = loadGltf(std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf");
    if (!scene.bounds.valid()) scene.computeBounds();
    const Camera cam = selectCamera(scene, "front");
    const Settings s;
    const fs::path dir = tempDir("cache");
    const CachedReference a = cachedReference(scene, cam, s, 16, 9, 2, 2, dir.string());
    EXPECT_FALSE(a.cacheHit);
    EXPECT_TRUE(fs::exists(a.path));
    const CachedReference b = cachedReference(scene, cam, s, 16, 9, 2, 2, dir.string());
    EXPECT_TRUE(b.cacheHit);
    EXPECT_EQ(a.path, b.path);
    EXPECT_EQ(a.final.pixels, b.final.pixels);
    EXPECT_EQ(a.indirect.pixels, b.indirect.pixels);
    // Anything in the key changes the file: spp, light settings, camera.
    Settings brighter = s;
    brighter.lightScale = 2.0f;
    EXPECT_NE(referenceKey(scene, cam, s, 16, 9, 2, 2, 1), referenceKey(scene, cam, s, 16, 9, 3, 2, 1));
    EXPECT_NE(referenceKey(scene, cam, s, 16, 9, 2, 2, 1), referenceKey(scene, cam, brighter, 16, 9, 2, 2, 1));
    Camera moved = cam;
    moved.cameraToWorld[3].x += 0.1f;
    EXPECT_NE(referenceKey(scene, cam, s, 16, 9, 2, 2, 1), referenceKey(scene, moved, s, 16, 9, 2, 2, 1));
    fs::remove_all(dir);
}

TEST(BenchCli, TinyRunWritesResults) {
    const fs::path dir = tempDir("cli");
    const std::string cmd = std::string(DEEPGI_BINARY) + " bench --scene " + DEEPGI_ASSET_DIR +
                            "/cornell_box/cornell_box.gltf --camera front --size 48x27 --frames 4 --timed-frames 2 --spp 8"
                            " --path-frames 2 --path-spp 2 --configs default,layer1 --whole-frame-size 0x0 --quiet --out " +
                            dir.string() + " > " + (dir / "log.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const char* f : {"results.csv", "results.md", "speed_error.png", "speed_error_indirect.png", "grid_cornell_box_front.png"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    std::ifstream csv(dir / "results.csv");
    std::string header, line;
    std::getline(csv, header);
    std::vector<std::string> names = {"Shadow maps", "Deep G-buffer", "Reproject radiance", "Input radiance", "Radiosity gather",
                                      "Ambient occlusion", "Bilateral blur", "Temporal blend", "Composite"};
    std::string expected;
    for (const auto& c : csvColumns(names)) expected += (expected.empty() ? "" : ",") + c;
    EXPECT_EQ(header, expected);
    for (const char* col : {"total_ms", "memory_bytes", "rel_mse", "mean_rel_err", "ssim", "ind_rel_mse", "ind_mean_rel_err",
                            "stability", "path_mean_rel_err", "ms_radiosity_gather"})
        EXPECT_NE(header.find(col), std::string::npos) << col;
    int rows = 0;
    while (std::getline(csv, line))
        if (!line.empty()) {
            ++rows;
            EXPECT_EQ(line.rfind("cornell_box,front,", 0), 0u) << line;
        }
    EXPECT_EQ(rows, 2);
    fs::remove_all(dir);
}

#include "renderer/gl/offscreen_context.h"
#include "renderer/renderer.h"
#include "renderer/scene/procedural.h"

// The EGL context (Mesa's surfaceless platform here) renders the same pipeline; skipped where EGL cannot start.
TEST(OffscreenContext, EglRendersAFrame) {
    if (!gl::OffscreenContext::eglAvailable()) GTEST_SKIP() << "built without EGL";
    std::unique_ptr<gl::OffscreenContext> ctx;
    try {
        ctx = std::make_unique<gl::OffscreenContext>("egl");
    } catch (const std::exception& e) {
        GTEST_SKIP() << e.what();
    }
    EXPECT_NE(ctx->description().find("egl"), std::string::npos);
    auto s = std::make_shared<Scene>();
    procedural::addFloor(*s, 10.0f, 0.0f, procedural::addMaterial(*s, glm::vec3(0.5f)));
    procedural::addCamera(*s, "cam", {0, 1, 2}, {0, 0, 0});
    s->computeBounds();
    Renderer r;
    r.setScene(s);
    r.resize(32, 18);
    r.setCamera(selectCamera(*s, "cam"));
    r.render(Settings{});
    const FloatImage img = r.readFinalRadiance();
    double sum = 0.0;
    for (float v : img.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
    EXPECT_THROW(gl::OffscreenContext("vulkan"), std::runtime_error);
}
