// Moving objects done right (issue 14, item 4): a box sliding across a lit floor, away from the camera and sideways.
// The deep G-buffer's predicted layer 2 is compared with depth peeling of the same frame (the exact answer), with
// each surface's own motion (gbuffer.object_motion on) and with the camera's alone (off); the indirect light is
// compared with a still render of the same instant (history reset, then converged). Prints the figures.
#include "gl_fixture.h"

#include <cstdio>
#include <cstdlib>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

constexpr int kW = 96, kH = 72;
const glm::vec3 kStart(-0.5f, 0.0f, 0.4f), kStep(0.04f, 0.0f, -0.08f);  // per frame: 0.09 m, 0.08 m of it away

struct SlidingBox {
    std::shared_ptr<Scene> scene;
    int box = -1;
    void place(int frame) {
        scene->nodes[size_t(box)].local.translation = kStart + float(frame) * kStep;
        scene->updateWorldTransforms();
    }
};

// A white floor with a back wall, a red box (0.5 m) on it, a low sun from the side, a camera looking down at it.
SlidingBox slidingBox() {
    SlidingBox b;
    b.scene = std::make_shared<Scene>();
    Scene& s = *b.scene;
    const int white = addMaterial(s, glm::vec3(0.75f)), red = addMaterial(s, glm::vec3(0.8f, 0.15f, 0.1f));
    addFloor(s, 2.5f, 0.0f, white);
    addQuad(s, {-2.5f, 0.0f, -2.5f}, {2.5f, 0.0f, -2.5f}, {2.5f, 2.0f, -2.5f}, {-2.5f, 2.0f, -2.5f}, white);
    addBox(s, {-0.25f, 0.0f, -0.25f}, {0.25f, 0.5f, 0.25f}, red, false);
    b.box = s.parts.back().node;
    addSun(s, glm::vec3(0.6f, -0.7f, -0.4f), 3.0f);
    addCamera(s, "view", {0.0f, 1.6f, 2.6f}, {0.0f, 0.2f, -0.2f}, 55.0f);
    s.computeBounds();
    return b;
}

Settings settingsFor(const Scene& scene, bool objectMotion, GBufferGeneration g) {
    Settings s;  // lengths "x scene size" (the defaults: the temporal falloff spans a few pixels' footprint here)
    const float size = 2.0f * scene.bounds.radius();
    s.minSeparation = 0.05f / size;  // 5 cm: less than the box's 8 cm per frame away from the camera
    s.objectMotion = objectMotion;
    s.generation = g;
    s.probesEnabled = false;  // the screen-space history alone
    return s;
}

// Fraction of pixels whose predicted layer-2 depth differs from the peeled one by more than 1%.
double layer2Mismatch(const FloatImage& predicted, const FloatImage& peeled) {
    int differ = 0;
    for (size_t i = 0; i < peeled.pixels.size(); ++i)
        if (std::abs(predicted.pixels[i] - peeled.pixels[i]) > 0.01f * peeled.pixels[i]) ++differ;
    return double(differ) / double(peeled.pixels.size());
}

// Runs `frames` frames of the slide; per frame after the first, the layer-2 mismatch against peeling of the same
// frame. Returns the mean and the worst.
void slidePrediction(bool objectMotion, int frames, double& mean, double& worst) {
    SlidingBox b = slidingBox();
    auto predicted = rendererFor(b.scene, kW, kH, "view");
    Settings sp = settingsFor(*b.scene, objectMotion, GBufferGeneration::Predicted),
             sd = settingsFor(*b.scene, objectMotion, GBufferGeneration::DepthPeel);
    sp.indirect = sd.indirect = false;  // the G-buffer alone, with the AO as the reader that makes layer 2 be built
    sp.aoEnabled = sd.aoEnabled = true;
    mean = worst = 0.0;
    for (int f = 0; f < frames; ++f) {
        b.place(f);
        predicted->sceneChanged(SceneChange::Transforms);
        predicted->render(sp);
        if (f == 0) continue;  // no history: peeled anyway
        auto peeled = rendererFor(b.scene, kW, kH, "view");
        peeled->render(sd);
        const double m = layer2Mismatch(predicted->readLayer("Depth 2"), peeled->readLayer("Depth 2"));
        mean += m / double(frames - 1);
        worst = std::max(worst, m);
    }
}

}  // namespace

// Predicted layer 2 = depth-peeled layer 2 within 2% of the pixels per frame when each object's motion is used
// (what remains: strips the box uncovers and covers each frame, where last frame's layer 1 cannot say); with the
// camera's motion alone the box's own front faces are kept as layer 2 (they moved away from last frame's depth by
// more than the minimum separation) and the mismatch is over twice as large (measured: 0.84% vs 2.58% mean, 96x72).
TEST_F(GLTest, SlidingBoxPredictedLayer2MatchesPeelingWithObjectMotion) {
    const int frames = 10;
    double meanOn, worstOn, meanOff, worstOff;
    slidePrediction(true, frames, meanOn, worstOn);
    slidePrediction(false, frames, meanOff, worstOff);
    std::printf("sliding box, %dx%d, %d frames, 0.09 m/frame: predicted layer 2 vs depth peeling, pixels over 1%% depth error:\n"
                "  object motion on : mean %.2f%%, worst %.2f%%\n  object motion off: mean %.2f%%, worst %.2f%%\n",
                kW, kH, frames, 100 * meanOn, 100 * worstOn, 100 * meanOff, 100 * worstOff);
    EXPECT_LT(worstOn, 0.02);
    EXPECT_GT(meanOff, 2.0 * meanOn);
    EXPECT_GT(meanOff, 0.02);
}

// The indirect light of the sliding box against a still render of the same instant (a fresh renderer: no history,
// converged). Both first converge (multi-bounce feedback) for kWarm frames at the start, so the difference is the
// motion's. While sliding, the difference is the temporal filter's lag (alpha 0.92 averages ~12 frames); once the box
// stops, no ghost of its old positions may remain: after kHold frames the difference must be within 1% of the
// indirect light of the difference between two still renders (the measure's noise floor). The box's own pixels
// keep their history (reprojected with their motion) instead of being rejected every frame as with the camera's
// motion alone.
TEST_F(GLTest, SlidingBoxIndirectLightHasNoGhost) {
    const int frames = 12, kWarm = 40, kHold = 30;
    for (bool objectMotion : {true, false}) {
        SlidingBox b = slidingBox();
        auto moving = rendererFor(b.scene, kW, kH, "view", sceneEditing());
        const Settings s = settingsFor(*b.scene, objectMotion, GBufferGeneration::Predicted);
        double boxKept = 0.0;
        b.place(0);
        moving->sceneChanged(SceneChange::Transforms);
        for (int f = 0; f < kWarm; ++f) moving->render(s);
        for (int f = 1; f < frames; ++f) {
            b.place(f);
            moving->sceneChanged(SceneChange::Transforms);
            moving->render(s);
        }
        {
            // Box pixels (layer 1) whose reprojected history was accepted (Reprojected Radiance is 0 where rejected).
            const FloatImage ids = moving->readLayer("Object ID 1"), rep = moving->readLayer("Reprojected Radiance");
            int box = 0, kept = 0;
            const int d = ids.width / rep.width;
            for (int y = 0; y < rep.height; ++y)
                for (int x = 0; x < rep.width; ++x) {
                    const int px = std::min(x * d + d / 2, ids.width - 1), py = std::min(y * d + d / 2, ids.height - 1);
                    if (int(ids.at(px, py, 0)) != b.box + 1) continue;
                    ++box;
                    kept += rep.at(x, y, 0) + rep.at(x, y, 1) + rep.at(x, y, 2) > 0.0f;
                }
            boxKept = box ? double(kept) / box : 0.0;
        }
        auto still = rendererFor(b.scene, kW, kH, "view");
        for (int f = 0; f < kWarm; ++f) still->render(s);
        const FloatImage stillE = still->readLayer("Output Radiance");
        auto ghost = [&](const FloatImage& e) {
            double diff = 0.0, total = 0.0;
            for (size_t i = 0; i < stillE.pixels.size(); ++i) {
                diff += std::abs(double(e.pixels[i]) - stillE.pixels[i]);
                total += stillE.pixels[i];
            }
            return total > 0 ? diff / total : 1.0;
        };
        const double atStop = ghost(moving->readLayer("Output Radiance"));
        for (int f = 0; f < kHold; ++f) moving->render(s);
        const double after = ghost(moving->readLayer("Output Radiance"));
        // The floor of this measure: two still renders of the same instant differ by the stochastic rounding of the
        // R11G11B10 stores (dithered by frame index) that the temporal history carries.
        auto still2 = rendererFor(b.scene, kW, kH, "view");
        for (int f = 0; f < kWarm + frames + kHold; ++f) still2->render(s);
        const double floor = ghost(still2->readLayer("Output Radiance"));
        std::printf("sliding box, object motion %s: indirect |moving - still| / still = %.2f%% when it stops after %d frames, "
                    "%.2f%% %d frames later (two still renders: %.2f%%); box pixels keeping their history while sliding %.0f%%\n",
                    objectMotion ? "on " : "off", 100 * atStop, frames, 100 * after, kHold, 100 * floor, 100 * boxKept);
        EXPECT_LT(after, floor + 0.01);
        if (objectMotion) EXPECT_GT(boxKept, 0.5);
        else EXPECT_LT(boxKept, 0.5);
    }
}
