// Half-resolution radiosity (radiosity.resolution): the gather, blur and temporal filter on a grid of a quarter of
// the pixels, upsampled by depth and normal in the composite, checked against the same frames at full resolution.
#include "bench/metrics.h"
#include "renderer/passes/bilateral_blur_pass.h"
#include "renderer/core/image_compare.h"
#include "gl_fixture.h"

#include <cstdio>

namespace deepgi::test {
namespace {

struct RadiosityRun {
    FloatImage indirect;  // final radiance minus the same view without indirect light
    int gridWidth = 0, gridHeight = 0;
    std::string outputSize;
};

RadiosityRun runAt(const std::shared_ptr<Scene>& scene, RadiosityResolution res, int w, int h, int frames) {
    Settings s;
    s.radiosityResolution = res;
    auto r = rendererFor(scene, w, h, "front");
    for (int i = 0; i < frames; ++i) r->render(s);
    RadiosityRun run;
    const FloatImage out = r->readLayer("Output Radiance");
    run.gridWidth = out.width;
    run.gridHeight = out.height;
    const FloatImage fin = r->readFinalRadiance();
    Settings direct = s;
    direct.indirect = false;
    auto d = rendererFor(scene, w, h, "front");
    d->render(direct);
    run.indirect = bench::subtract(fin, d->readFinalRadiance());
    return run;
}

}  // namespace

// The grid is half the screen, rounded up, in every radiosity texture; full keeps the screen's size.
TEST_F(GLTest, HalfResolutionRadiosityGridIsHalfTheScreenRoundedUp) {
    auto scene = cornellScene();
    const RadiosityRun half = runAt(scene, RadiosityResolution::Half, 101, 75, 1);
    EXPECT_EQ(half.gridWidth, 51);
    EXPECT_EQ(half.gridHeight, 38);
    const RadiosityRun full = runAt(scene, RadiosityResolution::Full, 101, 75, 1);
    EXPECT_EQ(full.gridWidth, 101);
    EXPECT_EQ(full.gridHeight, 75);
    ASSERT_TRUE(allFinite(half.indirect));
}

// Against full resolution (the independent answer here): the upsample's weights are normalised, so no energy is made
// or lost (ratio of means of the indirect part within 3 %), and the image follows the full-resolution one within
// 10 % relative L1 on 4x4 blocks, the error issue 13 allows the lower resolution to add. Both converge for 40 frames
// with the default temporal filter; the two differ by the pattern of taps (a quarter of the pixels, each the same
// 14 taps), the wider screen footprint of the blur, and faces 1-2 pixels wide that no grid texel stands for (they
// take a neighbour's light: a share of the image that grows as the image shrinks, hence 320x240, near the bench's
// 320x180). Before the reprojection sampled the history at the grid's own texel positions, the history drifted a
// quarter texel and blurred every frame, and this read 6.9 %; it reads 2.3 %.
TEST_F(GLTest, HalfResolutionRadiosityFollowsFullResolution) {
    auto scene = cornellScene();
    const RadiosityRun half = runAt(scene, RadiosityResolution::Half, 320, 240, 40);
    const RadiosityRun full = runAt(scene, RadiosityResolution::Full, 320, 240, 40);
    dumpIfRequested("radiosity_half_indirect", half.indirect);
    dumpIfRequested("radiosity_full_indirect", full.indirect);
    const ImageFigures f = compareImages(half.indirect, full.indirect);
    std::printf("half vs full resolution radiosity, indirect part: %s\n", f.line().c_str());
    ASSERT_TRUE(f.valid);
    EXPECT_GT(full.indirect.width, 0);
    EXPECT_NEAR(f.ratioOfMeans, 1.0, 0.03);
    EXPECT_LT(f.blockRelL1, 0.10);
}

// blur.radius counts full-resolution pixels: a grid of 1/d takes the fewest of its own taps that reach as far on
// screen (taps * d >= radius, (taps - 1) * d < radius), so half resolution's blur keeps full resolution's footprint
// instead of doubling it (5 -> 3 taps; session 23 of docs/BENCHMARKS.md: hidden_emitter 8.97 -> 8.61 %).
TEST(BlurTaps, ReachTheRadiusInFullResolutionPixels) {
    for (int d = 1; d <= 2; ++d)
        for (int radius = 1; radius <= 6; ++radius) {
            const int taps = blurTaps(radius, d);
            EXPECT_GE(taps * d, radius) << radius << " at 1/" << d;
            EXPECT_LT((taps - 1) * d, radius) << radius << " at 1/" << d;
            EXPECT_EQ(blurKernel(taps).size(), std::size_t(taps + 1));
        }
    EXPECT_EQ(blurTaps(5, 1), 5);
    EXPECT_EQ(blurTaps(5, 2), 3);
    EXPECT_EQ(blurTaps(1, 2), 1);
}

}  // namespace deepgi::test
