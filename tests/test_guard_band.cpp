// The guard band (gbuffer.guard_band, issue 9 item 3): the G-buffer and the radiosity are rendered larger than the
// screen with the view widened by whole pixels, and the image is their centre.
#include "gl_fixture.h"

#include "bench/gi_figures.h"
#include "renderer/reference/path_tracer.h"

#include <cmath>
#include <cstdio>

using namespace deepgi;
using namespace deepgi::procedural;
using deepgi::test::GLTest;

namespace {

// A wall lit only by a sunlit strip of floor (albedo 0.8, 0.7 m deep, in front of the wall's 0.3 m shadow; the rest
// of the floor is black); the sun cannot see the wall's face. The camera "wall" looks at the wall with its foot on
// the bottom row: the strip, the only surface that reflects light, is just below the view (inside a band of 0.3).
std::shared_ptr<Scene> stripBelowTheView() {
    auto s = std::make_shared<Scene>();
    const int white = addMaterial(*s, glm::vec3(0.8f)), black = addMaterial(*s, glm::vec3(0.0f));
    addQuad(*s, {-3, 0, -1.7f}, {3, 0, -1.7f}, {3, 0, -2}, {-3, 0, -2}, black);  // floor (+Y): in the wall's shadow
    addQuad(*s, {-3, 0, -1}, {3, 0, -1}, {3, 0, -1.7f}, {-3, 0, -1.7f}, white);  // the lit strip
    addQuad(*s, {-3, 0, 2}, {3, 0, 2}, {3, 0, -1}, {-3, 0, -1}, black);
    addQuad(*s, {-3, 0, -2}, {3, 0, -2}, {3, 3, -2}, {-3, 3, -2}, white);  // wall (+Z)
    addSun(*s, glm::vec3(0.0f, -1.0f, 0.1f), 3.0f);  // towards +Z: the wall is unlit, its shadow on the floor 0.3 deep
    // From (0, 1, 1) the wall's foot is atan(1/3) = 18.43 deg below the horizon: the bottom edge of a 50 deg view
    // pitched up 6.57 deg. A band of 0.3 reaches 30 deg below the horizon: the floor up to z = -0.73.
    const float pitch = glm::radians(25.0f) - std::atan(1.0f / 3.0f);
    addCamera(*s, "wall", {0.0f, 1.0f, 1.0f}, {0.0f, 1.0f + 3.0f * std::tan(pitch), -2.0f}, 50.0f);
    s->computeBounds();
    return s;
}

// Mean luminance of rows [y0, y1) (row 0 at the top).
double rowsMean(const FloatImage& img, int y0, int y1) {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < img.width; ++x)
            sum += 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
    return sum / double(img.width * (y1 - y0));
}

}  // namespace

// The image with a guard band is, pixel for pixel, the centre of the same frame rendered larger without one: the view
// is widened by whole pixels of the same size. Checked on the full pipeline (G-buffer, gather, blur, temporal filter,
// composite) at full, half, quarter and eighth radiosity resolution, and for every read-back of the image (readLayer, readDisplay,
// objectAt).
TEST_F(GLTest, GuardBandImageIsTheCentreOfAWiderFrame) {
    auto scene = test::cornellScene();
    const int W = 64, H = 48;
    // Each grid, its divisor d and the band in pixels: 0.25 x 48 = 12 on each side, a multiple of 4, so the
    // quarter grid's texels stay the image's; the eighth grid rounds it up to 16, a multiple of 8.
    struct Grid {
        const char* resolution;
        int d, band;
    };
    for (const Grid grid : {Grid{"full", 1, 12}, Grid{"half", 2, 12}, Grid{"quarter", 4, 12}, Grid{"eighth", 8, 16}}) {
        const char* resolution = grid.resolution;
        const int d = grid.d;
        Settings s;
        applySetting(s, "radiosity.resolution", resolution);
        s.guardBand = 0.25f;
        Renderer banded(test::sceneEditing());
        banded.setScene(scene);
        banded.resize(W, H);
        const Camera cam = selectCamera(*scene, "front");
        banded.setCamera(cam);
        for (int f = 0; f < 4; ++f) banded.render(s);
        const int g = banded.guardPixels();
        ASSERT_EQ(g, grid.band) << resolution;
        EXPECT_EQ(banded.textures().entry("Depth").width, W + 2 * g);
        EXPECT_EQ(banded.frameCamera().yfov > cam.yfov, true);

        // The wider frame: no band, (W + 2g) x (H + 2g), the banded renderer's own frame camera.
        Settings wideSettings = s;
        wideSettings.guardBand = 0.0f;
        Renderer wide(test::sceneEditing());
        wide.setScene(scene);
        wide.resize(W + 2 * g, H + 2 * g);
        wide.setCamera(banded.frameCamera());
        for (int f = 0; f < 4; ++f) wide.render(wideSettings);
        ASSERT_EQ(wide.guardPixels(), 0);

        const FloatImage a = banded.readFinalRadiance(), b = wide.readFinalRadiance();
        ASSERT_EQ(a.width, W);
        ASSERT_EQ(a.height, H);
        double maxDiff = 0.0, maxValue = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c) {
                    maxDiff = std::max(maxDiff, double(std::abs(a.at(x, y, c) - b.at(x + g, y + g, c))));
                    maxValue = std::max(maxValue, double(b.at(x + g, y + g, c)));
                }
        std::printf("guard band, %s radiosity: largest difference from the wider frame's centre %.2e (of %.3f)\n",
                    resolution, maxDiff, maxValue);
        EXPECT_LT(maxDiff, 1e-3 * maxValue) << resolution;  // the same computation but for float rounding

        // Reduced-resolution buffers crop by the band over the grid's divisor.
        const FloatImage ra = banded.readLayer("Output Radiance"), rb = wide.readLayer("Output Radiance");
        EXPECT_EQ(ra.width, (W + d - 1) / d);
        double rd = 0.0;
        for (int y = 0; y < ra.height; ++y)
            for (int x = 0; x < ra.width; ++x) rd = std::max(rd, double(std::abs(ra.at(x, y, 1) - rb.at(x + g / d, y + g / d, 1))));
        EXPECT_LT(rd, 1e-3 * maxValue) << resolution;

        const std::vector<unsigned char> da = banded.readDisplay(), db = wide.readDisplay();
        ASSERT_EQ(da.size(), size_t(W) * H * 4);
        int differing = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                differing += std::abs(int(da[(size_t(y) * W + x) * 4 + 1]) - int(db[(size_t(y + g) * (W + 2 * g) + x + g) * 4 + 1])) > 1;
        EXPECT_EQ(differing, 0) << resolution;
        for (int y = 0; y < H; y += 7)
            for (int x = 0; x < W; x += 5) EXPECT_EQ(banded.objectAt(x, y), wide.objectAt(x + g, y + g)) << x << "," << y;
        EXPECT_EQ(banded.objectAt(W, 0), -1);  // past the image: the band is not part of it
    }
}

// The band's purpose: light from a surface just outside the view. The floor's lit strip, the only surface that
// reflects light, is below the bottom edge and inside the band; with the probes off, the screen alone lights the wall
// only when the band holds the strip. The answer is a one-bounce path trace. Asserted, at two band sizes that both
// hold the strip: nothing without the band, and at least half of the truth with it. Issue 9's targets are not met:
// ratio 0.91 / 0.66 at bands 0.3 / 0.45 (relL1 27 % / 39 %) because the strip is about 9 pixels tall and a tap reads
// at least mip 2 (radiosity.min_mip), so which of its pixels the mips keep depends on where the frame's edge falls
// (0.80 / 0.83 with min_mip 0); docs/BENCHMARKS.md, "Session 8".
TEST_F(GLTest, GuardBandLightsTheWallFromTheFloorBelowTheView) {
    const auto scene = stripBelowTheView();
    const int W = 128, H = 72;
    const Camera cam = selectCamera(*scene, "wall");
    ReferenceOptions ro;
    ro.width = W;
    ro.height = H;
    ro.spp = 512;
    ro.maxBounces = 1;
    ro.progress = false;
    const ReferenceResult ref = renderReference(*scene, cam, Settings{}, ro);
    ASSERT_GT(rowsMean(ref.indirect, 0, H), 0.01);

    auto render = [&](float band) {
        Settings s;
        s.probesEnabled = false;
        s.damping = 1.0f;  // one bounce
        s.guardBand = band;
        Renderer r;
        r.setScene(scene);
        r.resize(W, H);
        r.setCamera(cam);
        for (int f = 0; f < 30; ++f) r.render(s);
        return r.readFinalRadiance();  // the wall is not lit directly: all of it is indirect
    };
    const FloatImage without = render(0.0f);
    test::dumpIfRequested("guard_band_wall_without", without);
    test::dumpIfRequested("guard_band_wall_reference", ref.indirect);
    std::printf("wall lit from below the view, one bounce: no band: ratio %.3f\n",
                bench::ratioOfMeans(without, ref.indirect));
    EXPECT_LT(bench::ratioOfMeans(without, ref.indirect), 0.05);  // the screen alone has nothing of the strip
    for (float band : {0.3f, 0.45f}) {
        const FloatImage with = render(band);
        test::dumpIfRequested(band < 0.4f ? "guard_band_wall_with_0.3" : "guard_band_wall_with_0.45", with);
        const double l1 = bench::relativeL1(with, ref.indirect), ratio = bench::ratioOfMeans(with, ref.indirect);
        std::printf("  band %.2f: relL1 %.1f %%, ratio %.3f\n", band, 100.0 * l1, ratio);
        EXPECT_GT(ratio, 0.5) << band;
        EXPECT_LT(ratio, 1.2) << band;
    }
}

// Nothing stands between any two points of a floor and a wall that meet in a concave corner, so the visibility march
// must not remove light there: the same frame with radiosity.visibility_steps=0 is the answer (within 3 %). It failed
// (0.53-0.55; 0.33-0.41 at the foot) while a coarse tap took its x, y at full resolution and its depth from the mip:
// that put the tap and the march's samples off a grazing floor, and the floor blocked its own light.
TEST_F(GLTest, VisibilityMarchBlocksNothingInAnOpenCorner) {
    const auto scene = stripBelowTheView();
    const int W = 128, H = 72;
    for (const char* resolution : {"half", "full"}) {
        auto render = [&](int steps) {
            Settings s;
            applySetting(s, "radiosity.resolution", resolution);
            s.probesEnabled = false;
            s.damping = 1.0f;
            s.guardBand = 0.3f;
            s.visibilitySteps = steps;
            Renderer r;
            r.setScene(scene);
            r.resize(W, H);
            r.setCamera(selectCamera(*scene, "wall"));
            for (int f = 0; f < 20; ++f) r.render(s);
            return r.readFinalRadiance();
        };
        const FloatImage marched = render(8), open = render(0);
        const double all = rowsMean(marched, 0, H) / rowsMean(open, 0, H);
        const double foot = rowsMean(marched, H - H / 6, H) / rowsMean(open, H - H / 6, H);  // the wall's foot rows
        std::printf("open corner, %s radiosity: marched / no march = %.3f (the foot's sixth of the rows %.3f)\n",
                    resolution, all, foot);
        EXPECT_GT(all, 0.97) << resolution;
        EXPECT_GT(foot, 0.97) << resolution;
    }
}
