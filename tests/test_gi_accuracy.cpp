// Indirect light against the path tracer on scenes where a screen-space method has what it needs (issue 9, item 1):
// one bounce where every reflecting surface is in view, and the fill of what the screen does not cover.
#include "gl_fixture.h"

#include "bench/gi_figures.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/gltf_loader.h"

#include <cstdio>

using namespace deepgi;
using namespace deepgi::procedural;
using deepgi::test::GLTest;

namespace {

// A 2 x 2 x 2 box open at the front (+Z) seen from outside through the opening: the floor, the back wall, the red
// and green side walls and the ceiling are all on screen. The sun shines through a hole in the ceiling onto the
// floor; everything else is lit by what the floor (and then the walls) reflect. Nothing that reflects light is out
// of view or behind another surface.
std::shared_ptr<Scene> openBoxInView() {
    auto s = std::make_shared<Scene>();
    const int white = addMaterial(*s, glm::vec3(0.75f));
    const int red = addMaterial(*s, glm::vec3(0.75f, 0.15f, 0.1f));
    const int green = addMaterial(*s, glm::vec3(0.15f, 0.75f, 0.1f));
    const float h = 1.0f, a = 0.6f;
    addQuad(*s, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, white);    // floor (+Y)
    addQuad(*s, {-h, 0, -h}, {h, 0, -h}, {h, 2, -h}, {-h, 2, -h}, white);  // back wall (+Z)
    addQuad(*s, {-h, 0, h}, {-h, 0, -h}, {-h, 2, -h}, {-h, 2, h}, red);    // left wall (+X)
    addQuad(*s, {h, 0, -h}, {h, 0, h}, {h, 2, h}, {h, 2, -h}, green);      // right wall (-X)
    // Ceiling (-Y) with a hole |x| < a, -0.9 < z < 0.5: the sun patch covers about a third of the floor.
    addQuad(*s, {-h, 2, -h}, {h, 2, -h}, {h, 2, -0.9f}, {-h, 2, -0.9f}, white);
    addQuad(*s, {-h, 2, 0.5f}, {h, 2, 0.5f}, {h, 2, h}, {-h, 2, h}, white);
    addQuad(*s, {-h, 2, -0.9f}, {-a, 2, -0.9f}, {-a, 2, 0.5f}, {-h, 2, 0.5f}, white);
    addQuad(*s, {a, 2, -0.9f}, {h, 2, -0.9f}, {h, 2, 0.5f}, {a, 2, 0.5f}, white);
    addSun(*s, glm::vec3(0.1f, -1.0f, 0.15f), 3.0f);
    addCamera(*s, "outside", {0.0f, 1.0f, 2.4f}, {0.0f, 1.0f, 0.0f}, 74.0f);
    s->computeBounds();
    return s;
}

struct Figures {
    double relL1, ratio;
};

// deepgi's indirect part (final - direct, both from deepgi) against the reference's (reference final - deepgi
// direct), as ../shared/docs/gi-accuracy.md defines it.
// With refIsIndirect, ref is the path tracer's own indirect part instead (nothing subtracted from it).
Figures indirectFigures(const FloatImage& final, const FloatImage& direct, const FloatImage& refFinal,
                        bool refIsIndirect = false) {
    FloatImage test = final, ref = refFinal;  // the renderer's images are RGBA, the path tracer's RGB
    for (int y = 0; y < test.height; ++y)
        for (int x = 0; x < test.width; ++x)
            for (int c = 0; c < 3; ++c) {
                test.at(x, y, c) -= direct.at(x, y, c);
                if (!refIsIndirect) ref.at(x, y, c) -= direct.at(x, y, c);
            }
    return {bench::relativeL1(test, ref), bench::ratioOfMeans(test, ref)};
}

FloatImage renderDeepgi(const std::shared_ptr<Scene>& scene, Settings s, int w, int h, int frames) {
    Renderer r;
    r.setScene(scene);
    r.resize(w, h);
    r.setCamera(selectCamera(*scene, "outside"));
    for (int f = 0; f < frames; ++f) r.render(s);
    return r.readFinalRadiance();
}

}  // namespace

// One bounce (radiosity.bounce_damping = 1) on the open box against a 1-bounce path trace: the gather's form factors
// and the probes together must converge to the truth as taps grow (issue 9: <= 10 % where everything is in view),
// and more taps must not make it worse.
// Disabled: today 22.9 / 24.6 / 26.5 % at 8 / 14 / 30 taps, ratio of means 1.13 / 1.15 / 1.17 (21.4 / 22.4 / 23.3 %,
// 1.11 / 1.13 / 1.14 before session 8's march fix, whose false occlusion hid part of the excess; 26.6 / 25.1 / 25.0 %
// with the order-2 harmonics); BENCHMARKS.md "Session 5" has the figures: the probes alone are 10 % bright (position
// bias), and inside a sector the probes' sample does not know which part of it the taps covered. Session 13's fill
// (a direction whose light the screen holds is drawn again): 21.6 / 22.7 / 24.1 %, ratio 1.12 / 1.14 / 1.16; session 14's
// line-fit blur: 19.2 / 19.0 / 19.2 %, ratio 1.02 / 1.04 / 1.05; session 16's interleave 4: 20.3 / 19.7 / 19.8 %,
// ratio 0.99 / 1.01 / 1.02. What is left (BENCHMARKS.md "Session 14"): half
// resolution (the probes alone 19.1 % at half, 15.4 % at full) and the wall's foot, whose light comes from a thin band
// above the floor's horizon that 8x8 radiance texels do not resolve (12 x the truth at the foot, 0.92-1.07 above).
TEST_F(GLTest, DISABLED_OneBounceInViewMatchesThePathTracer) {
    const auto scene = openBoxInView();
    const int W = 160, H = 96;
    ReferenceOptions ro;
    ro.width = W;
    ro.height = H;
    ro.spp = 2048;
    ro.maxBounces = 1;
    ro.progress = false;
    const ReferenceResult ref = renderReference(*scene, selectCamera(*scene, "outside"), Settings{}, ro);
    Settings directOnly;
    directOnly.indirect = false;
    const FloatImage direct = renderDeepgi(scene, directOnly, W, H, 2);
    double previous = 1e9;
    for (int taps : {8, 14, 30}) {
        Settings s;
        s.damping = 1.0f;
        s.numSamples = taps;
        const FloatImage final = renderDeepgi(scene, s, W, H, 60);
        test::dumpIfRequested("one_bounce_in_view_" + std::to_string(taps), final);
        // Against the path tracer's own indirect part: on the sunlit floor a 1 % difference in the direct light
        // (shadow-map edges, filtering) is as large as the indirect light there, and is not what is measured here.
        const Figures f = indirectFigures(final, direct, ref.indirect, /*refIsIndirect=*/true);
        std::printf("one bounce in view, %d taps: indirect relL1 %.1f %%, ratio of means %.3f\n", taps, 100.0 * f.relL1,
                    f.ratio);
        EXPECT_LT(f.relL1, 0.10) << taps << " taps";
        EXPECT_NEAR(f.ratio, 1.0, 0.08) << taps << " taps";
        EXPECT_LT(f.relL1, previous + 0.01) << "more taps, larger error: " << taps << " taps";
        previous = f.relL1;
    }
    test::dumpIfRequested("one_bounce_in_view_direct", direct);
    test::dumpIfRequested("one_bounce_in_view_reference", ref.final);
    test::dumpIfRequested("one_bounce_in_view_reference_indirect", ref.indirect);
}

namespace {

std::shared_ptr<Scene> hardScene(const std::string& name) {
    return std::make_shared<Scene>(loadGltf(std::string(DEEPGI_ASSET_DIR) + "/hard/" + name + "/" + name + ".gltf"));
}

FloatImage renderView(const std::shared_ptr<Scene>& scene, const std::string& camera, const Settings& s, int w, int h,
                      int frames) {
    Renderer r;
    r.setScene(scene);
    r.resize(w, h);
    r.setCamera(selectCamera(*scene, camera));
    for (int f = 0; f < frames; ++f) r.render(s);
    return r.readFinalRadiance();
}

// What a view's indirect light is judged against: the path tracer's final image (diffuse, as the bench measures GI:
// deepgi's indirect light has no specular lobe) and deepgi's direct light, both at w x h.
struct ViewTruth {
    Settings diffuse;
    FloatImage referenceFinal, direct;
};
ViewTruth viewTruth(const std::shared_ptr<Scene>& scene, const std::string& camera, int w, int h) {
    ViewTruth t;
    t.diffuse.diffuseOnly = true;
    ReferenceOptions ro;
    ro.width = w;
    ro.height = h;
    ro.spp = 256;
    ro.maxBounces = 128;
    ro.progress = false;
    t.referenceFinal = renderReference(*scene, selectCamera(*scene, camera), t.diffuse, ro).final;
    Settings directOnly = t.diffuse;
    directOnly.indirect = false;
    t.direct = renderView(scene, camera, directOnly, w, h, 2);
    return t;
}

}  // namespace

// The closed furnace of the hard suite (every surface albedo 0.5, emission 0.1): the radiance is exactly 0.2 on every
// pixel, the screen's borders and the walls seen at grazing angles included (issue 9: within 3 %). Before the gather
// rescaled taps whose patches add up to more than the hemisphere, such pixels (where the sum was kept but the
// probes' share clamped at 0) were 6-7 % too bright.
TEST_F(GLTest, HardFurnaceWithinThreePercentEverywhere) {
    const auto scene = hardScene("furnace");
    const FloatImage final = renderView(scene, "inside", Settings{}, 192, 108, 200);
    test::dumpIfRequested("hard_furnace", final);
    const bench::Deviation d = bench::deviationFromConstant(final, 0.2);
    std::printf("furnace: max %.2f %%, mean %.2f %% off 0.2, ratio %.4f\n", 100.0 * d.maxRel, 100.0 * d.meanRel, d.ratio);
    EXPECT_LT(d.maxRel, 0.03);
    EXPECT_NEAR(d.ratio, 1.0, 0.01);
}

// The only lit surface (a sun patch on the floor) is behind the camera: all the indirect light the camera sees comes
// from directions the screen does not hold. Filling those with the probes' radiance in those directions (not their
// irradiance x the uncovered share, which weighs in the screen's darker directions) matches the path tracer's mean.
TEST_F(GLTest, OffScreenLightFillMatchesThePathTracer) {
    const auto scene = hardScene("offscreen_light");
    const int W = 160, H = 90;
    const ViewTruth truth = viewTruth(scene, "corner", W, H);
    const FloatImage final = renderView(scene, "corner", truth.diffuse, W, H, 200);
    test::dumpIfRequested("offscreen_light", final);
    const Figures f = indirectFigures(final, truth.direct, truth.referenceFinal);
    std::printf("off-screen light: indirect relL1 %.1f %%, ratio of means %.3f\n", 100.0 * f.relL1, f.ratio);
    EXPECT_NEAR(f.ratio, 1.0, 0.05);
    EXPECT_LT(f.relL1, 0.07);
}

// A black parapet between a sunlit floor and a wall, seen from above (assets/hard/occluder): the camera sees over it
// what the floor at its foot cannot, so a gather that counts what the screen holds brings light through it. The
// visibility march must take most of that excess away: at least half of what the gather without the march puts above
// the path tracer. Here 4 march steps alone took 31 % of it away (ratio 1.37 against 1.53); with the test for a segment
// that passes through layer 1 between two samples, 72 % (1.15).
TEST_F(GLTest, VisibilityMarchBlocksLightThroughAParapet) {
    const auto scene = hardScene("occluder");
    const int W = 160, H = 90;
    const ViewTruth truth = viewTruth(scene, "above", W, H);
    Settings noMarch = truth.diffuse;
    noMarch.visibilitySteps = 0;
    const Figures marched =
        indirectFigures(renderView(scene, "above", truth.diffuse, W, H, 120), truth.direct, truth.referenceFinal);
    const Figures unmarched =
        indirectFigures(renderView(scene, "above", noMarch, W, H, 120), truth.direct, truth.referenceFinal);
    std::printf("parapet: indirect ratio of means %.3f marched, %.3f without the march; relL1 %.1f / %.1f %%\n",
                marched.ratio, unmarched.ratio, 100.0 * marched.relL1, 100.0 * unmarched.relL1);
    EXPECT_GT(unmarched.ratio, 1.1);  // the scene does what it is built for
    EXPECT_LT(marched.ratio - 1.0, 0.5 * (unmarched.ratio - 1.0));
    EXPECT_LT(marched.relL1, 0.75 * unmarched.relL1);
}
