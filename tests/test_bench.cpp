// deepgi bench: metric functions on known images, the Pareto front, the reference cache and a tiny bench run.
#include "bench/bench.h"
#include "bench/draw.h"
#include "bench/gi_figures.h"
#include "bench/hard_suite.h"
#include "bench/metrics.h"
#include "bench/plot.h"
#include "renderer/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// ---- the GI figures of ../shared/docs/gi-accuracy.md on synthetic images with known answers ----

TEST(GiFigures, LuminanceIsRec709) {
    FloatImage img{3, 1, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    const LumaImage l = luminance(img);
    EXPECT_NEAR(l.v[0], 0.2126, 1e-7);
    EXPECT_NEAR(l.v[1], 0.7152, 1e-7);
    EXPECT_NEAR(l.v[2], 0.0722, 1e-7);
}

TEST(GiFigures, RelativeL1IsOverFourByFourBlockMeans) {
    const FloatImage ref = constant(8, 8, 1.0f);
    // +-0.5 in a checkerboard: every 4x4 block keeps its mean, so per-pixel noise scores 0.
    FloatImage noisy = ref;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) noisy.at(x, y, c) = (x + y) % 2 ? 1.5f : 0.5f;
    EXPECT_NEAR(relativeL1(noisy, ref), 0.0, 1e-12);
    EXPECT_NEAR(relativeL1(noisy, ref, 1), 0.5, 1e-12);  // per pixel it is 50 %
    // One of the four blocks 40 % too bright: sum |diff| / sum ref = 0.4 / 4.
    FloatImage block = ref;
    for (int y = 0; y < 4; ++y)
        for (int x = 4; x < 8; ++x)
            for (int c = 0; c < 3; ++c) block.at(x, y, c) = 1.4f;
    EXPECT_NEAR(relativeL1(block, ref), 0.1, 1e-6);
    EXPECT_NEAR(ratioOfMeans(block, ref), 1.1, 1e-6);
    // A global factor: relL1 = |k - 1|, ratio = k.
    EXPECT_NEAR(relativeL1(constant(8, 8, 2.83f), ref), 1.83, 1e-6);
    EXPECT_NEAR(ratioOfMeans(constant(8, 8, 2.83f), ref), 2.83, 1e-6);
    // Black: relL1 1, ratio 0 (the off-screen case's "1.00 / 0.00").
    EXPECT_NEAR(relativeL1(constant(8, 8, 0.0f), ref), 1.0, 1e-12);
    EXPECT_NEAR(ratioOfMeans(constant(8, 8, 0.0f), ref), 0.0, 1e-12);
}

TEST(GiFigures, RelativeL1WeighsChannelsByLuminanceAndHandlesPartialBlocks) {
    // Reference green 1, test red 1: block means 0.7152 vs 0.2126.
    FloatImage g = constant(4, 4, 0.0f), r = constant(4, 4, 0.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            g.at(x, y, 1) = 1.0f;
            r.at(x, y, 0) = 1.0f;
        }
    EXPECT_NEAR(relativeL1(r, g), (0.7152 - 0.2126) / 0.7152, 1e-6);
    EXPECT_NEAR(ratioOfMeans(r, g), 0.2126 / 0.7152, 1e-6);
    // 6x6: blocks of 4x4, 2x4, 4x2 and 2x2 pixels, each one mean. +0.8 on the 2x2 corner block only: 0.8 / 4.
    const FloatImage ref = constant(6, 6, 1.0f);
    FloatImage t = ref;
    for (int y = 4; y < 6; ++y)
        for (int x = 4; x < 6; ++x)
            for (int c = 0; c < 3; ++c) t.at(x, y, c) = 1.8f;
    EXPECT_NEAR(relativeL1(t, ref), 0.2, 1e-6);
    EXPECT_EQ(blockMeans(luminance(ref)).width, 2);
}

TEST(GiFigures, UndefinedWithoutReferenceLightAndSizeChecked) {
    EXPECT_TRUE(std::isnan(relativeL1(constant(4, 4, 1.0f), constant(4, 4, 0.0f))));
    EXPECT_TRUE(std::isnan(ratioOfMeans(constant(4, 4, 1.0f), constant(4, 4, 0.0f))));
    EXPECT_THROW(relativeL1(constant(4, 4, 1), constant(4, 8, 1)), std::invalid_argument);
}

TEST(GiFigures, LeakMeanAndMax) {
    FloatImage img = constant(10, 10, 0.0f);
    for (int c = 0; c < 3; ++c) {
        img.at(3, 4, c) = 0.5f;
        img.at(9, 9, c) = 0.25f;
    }
    const Leak k = leak(img);
    EXPECT_NEAR(k.max, 0.5, 1e-12);
    EXPECT_NEAR(k.mean, 0.75 / 100.0, 1e-12);
    EXPECT_EQ(leak(constant(5, 5, 0.0f)).max, 0.0);
}

TEST(GiFigures, FurnaceDeviationIsPerPixelIncludingBorders) {
    // Exact 0.2; the top row (a screen border) 5 % dark, one corner pixel 20 % bright.
    FloatImage img = constant(10, 5, 0.2f);
    for (int x = 0; x < 10; ++x)
        for (int c = 0; c < 3; ++c) img.at(x, 0, c) = 0.19f;
    for (int c = 0; c < 3; ++c) img.at(9, 4, c) = 0.24f;
    const Deviation d = deviationFromConstant(img, 0.2);
    EXPECT_NEAR(d.maxRel, 0.2, 1e-6);
    EXPECT_NEAR(d.meanRel, (10 * 0.05 + 0.2) / 50.0, 1e-6);
    EXPECT_NEAR(d.ratio, (10 * 0.19 + 39 * 0.2 + 0.24) / 50.0 / 0.2, 1e-6);
    EXPECT_THROW(deviationFromConstant(img, 0.0), std::invalid_argument);
}

TEST(GiFigures, NoiseFloorIsQuarterSampleDifferenceOverRootFive) {
    const FloatImage a = constant(8, 8, 1.1f), b = constant(8, 8, 1.0f);
    EXPECT_NEAR(noiseFloor(a, b), 0.1 / std::sqrt(5.0), 1e-6);
}

TEST(HardSuite, FloorReferenceIsCachedWithItsFloor) {
    Scene scene = loadGltf(std::string(DEEPGI_ASSET_DIR) + "/hard/furnace/furnace.gltf");
    if (!scene.bounds.valid()) scene.computeBounds();
    const Camera cam = selectCamera(scene, "inside");
    const fs::path dir = tempDir("floor");
    const FloorReference a = floorReference(scene, cam, Settings{}, 16, 8, 8, 8, dir.string(), true);
    EXPECT_FALSE(a.cacheHit);
    EXPECT_GT(a.floorFinal, 0.0);
    // The furnace's truth is 0.2; 8 bounces of albedo 0.5 reach 0.2 * (1 - 0.5^9) and the mean sits near it.
    EXPECT_NEAR(ratioOfMeans(a.final, constantImage(16, 8, 0.2f)), 1.0 - std::pow(0.5, 9), 0.05);
    const FloorReference b = floorReference(scene, cam, Settings{}, 16, 8, 8, 8, dir.string(), true);
    EXPECT_TRUE(b.cacheHit);
    EXPECT_EQ(a.final.pixels, b.final.pixels);
    EXPECT_DOUBLE_EQ(a.floorIndirect, b.floorIndirect);
    EXPECT_THROW(floorReference(scene, cam, Settings{}, 16, 8, 2, 8, dir.string(), true), std::invalid_argument);
    fs::remove_all(dir);
}

TEST(HardSuite, FurnaceRunWritesItsFiguresAndBadScalesAreErrors) {
    // The furnace needs no reference (its answer is exact), so the suite's wiring runs in seconds.
    const fs::path dir = tempDir("hard");
    const std::string base = std::string(DEEPGI_BINARY) + " bench --suite hard --hard-scenes furnace --size 32x18 --frames 4"
                             " --timed-frames 2 --one-bounce-frames 2 --quiet --out " + dir.string();
    const std::string cmd = base + " --scales 1,1000 > " + (dir / "log.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const char* f : {"results_hard.md", "results_hard.csv", "grid_furnace_inside.png", "grid_furnace_inside_s1000.png"})
        EXPECT_TRUE(fs::exists(dir / f)) << f;
    std::ifstream csv(dir / "results_hard.csv");
    std::string header, line;
    std::getline(csv, header);
    for (const char* col : {"ind_rel_l1", "ind_ratio", "one_rel_l1", "one_ratio", "leak_mean_rel", "furnace_max_dev", "vs_scale1", "frame_ms"})
        EXPECT_NE(header.find(col), std::string::npos) << col;
    std::vector<std::string> rows;
    while (std::getline(csv, line))
        if (!line.empty()) rows.push_back(line);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].rfind("furnace,inside,default,1,", 0), 0u) << rows[0];
    EXPECT_EQ(rows[1].rfind("furnace,inside,default,1000,", 0), 0u) << rows[1];
    // A scale the generator does not write is refused with a message naming the option.
    const std::string bad = base + " --scales 2 > " + (dir / "bad.txt").string() + " 2>&1";
    EXPECT_NE(std::system(bad.c_str()), 0);
    std::ifstream b(dir / "bad.txt");
    const std::string msg((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    EXPECT_NE(msg.find("--scales"), std::string::npos) << msg;
    fs::remove_all(dir);
}

TEST(BenchDraw, TextHeatAndAxes) {
    // Text (DejaVu Sans through OIIO) darkens pixels of a white canvas, and only near where it is drawn.
    OIIO::ImageBuf c = draw::canvas(60, 20);
    draw::text(c, 2, 2, "A1", {0, 0, 0}, 12);
    float minLeft = 1.0f, minRight = 1.0f;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 60; ++x) {
            float px[3];
            c.getpixel(x, y, px, 3);
            (x < 25 ? minLeft : minRight) = std::min(x < 25 ? minLeft : minRight, px[0]);
        }
    EXPECT_LT(minLeft, 0.5f);
    EXPECT_EQ(minRight, 1.0f);
    // The heat map is OIIO's inferno: 0 is near black, 1 a bright yellow, values clamped.
    const OIIO::ImageBuf h = draw::heat({0.0f, 1.0f, 7.0f}, 3, 1);
    float lo[3], hi[3], over[3];
    h.getpixel(0, 0, lo, 3);
    h.getpixel(1, 0, hi, 3);
    h.getpixel(2, 0, over, 3);
    EXPECT_LT(lo[0] + lo[1] + lo[2], 0.1f);
    EXPECT_GT(hi[0], 0.9f);
    EXPECT_GT(hi[1], 0.9f);
    EXPECT_EQ(over[1], hi[1]);
    // Axis maxima round up to 1, 2, 2.5, 5 x a power of ten, five ticks.
    double mx, step;
    niceAxis(0.31, mx, step);
    EXPECT_DOUBLE_EQ(mx, 0.5);
    EXPECT_DOUBLE_EQ(step, 0.1);
    niceAxis(2.1, mx, step);
    EXPECT_DOUBLE_EQ(mx, 2.5);
    niceAxis(0.0, mx, step);
    EXPECT_DOUBLE_EQ(mx, 1.0);
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
    std::vector<std::string> names = {"Shadow maps", "Environment", "Deep G-buffer", "Reproject radiance", "Probe update", "Input radiance", "Gather select", "Radiosity gather",
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

// A user's --set wins over a configuration's preset (preset_quality with radiosity.min_mip=0 runs min_mip 0), but not
// over the assignment that makes the configuration what it is (direct_only stays direct only).
TEST(BenchConfigs, UserSettingsWinOverAPresetNotOverTheConfiguration) {
    const std::vector<std::string> user = {"radiosity.min_mip=0", "radiosity.enabled=true"};
    Settings base;
    for (const auto& a : user) applyAssignment(base, a);
    const BenchConfig quality{"preset_quality", "quality", {}, ""}, direct{"direct_only", "", {"radiosity.enabled=false"}, ""};
    const Settings q = configSettings(base, quality, user);
    EXPECT_EQ(q.minMip, 0);
    Settings presetOnly;
    applyPreset(presetOnly, "quality");
    EXPECT_EQ(q.numSamples, presetOnly.numSamples);  // the rest of the preset stays
    EXPECT_EQ(configSettings(base, quality).minMip, presetOnly.minMip);  // without the user's list: the preset's
    EXPECT_FALSE(configSettings(base, direct, user).indirect);
}
