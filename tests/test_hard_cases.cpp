// Hard cases (issue 5, docs/ROBUSTNESS.md): degenerate geometry, motion, trivial scenes and sizes. Each test
// says what it asserts; the numerical-stability cases are in test_hard_stability.cpp, bad input in
// test_bad_input.cpp.
#include "gl_fixture.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <tuple>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

void expectAllBuffersFinite(const Renderer& r, const std::string& what) {
    for (const auto& name : r.textures().layerNames()) EXPECT_TRUE(allFinite(r.readLayer(name))) << name << " (" << what << ")";
}

double meanRelDiff(const FloatImage& a, const FloatImage& b) {
    double d = 0.0, m = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (b.channels == 4 && i % 4 == 3) continue;
        d += std::abs(double(a.pixels[i]) - b.pixels[i]);
        m += std::abs(double(b.pixels[i]));
    }
    return m > 0.0 ? d / m : d;
}

Camera lookAt(const glm::vec3& eye, const glm::vec3& target, float fovDeg = 70.0f, const glm::vec3& up = {0, 1, 0}) {
    Camera c;
    c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
    c.yfov = glm::radians(fovDeg);
    c.znear = 0.01f;
    c.zfar = 50.0f;
    return c;
}

// One frame of a fresh renderer (no history): what a frame right after a cut must look like.
FloatImage freshFrame(const std::shared_ptr<Scene>& scene, const Camera& cam, const Settings& s, int w, int h,
                      const char* layer = "Final Radiance") {
    Renderer r;
    r.setScene(scene);
    r.resize(w, h);
    r.setCamera(cam);
    r.render(s);
    return r.readLayer(layer);
}

void addTriangle(Scene& s, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n, int material) {
    MeshPart part;
    part.name = "triangle" + std::to_string(s.parts.size());
    part.material = material;
    for (const auto& p : {a, b, c}) part.vertices.push_back({p, n, glm::vec2(0.0f)});
    part.indices = {0, 1, 2};
    s.parts.push_back(std::move(part));
}

}  // namespace

// ------------------------------------------------------------------------------------------ degenerate geometry

// Built in code (bypassing the loader, which would skip or repair them): zero-area and collinear triangles, a
// quad with zero-length normals, a quad with NaN normals, triangles with a NaN and an Inf vertex, all in the
// Cornell room. Asserted: every buffer finite; the quads with broken normals get the geometric normal (within 2
// degrees, generated in the shader); the rest of the image equals the clean room (mean relative difference < 2%).
TEST_F(GLTest, DegenerateTrianglesAndNormalsRenderFinite) {
    auto clean = cornellScene();
    auto bad = cornellScene();
    const int m = addMaterial(*bad, glm::vec3(0.5f));
    addTriangle(*bad, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 1}, m);                    // zero area
    addTriangle(*bad, {-0.5f, 1, 0}, {0, 1, 0}, {0.5f, 1, 0}, {0, 0, 1}, m);             // collinear
    addTriangle(*bad, {0, 0.2f, 0}, {kNaN, 1, 0}, {0.5f, 1, 0}, {0, 0, 1}, m);           // NaN vertex
    addTriangle(*bad, {0, 0.2f, 0}, {kInf, 1, 0}, {0.5f, 1, 0}, {0, 0, 1}, m);           // Inf vertex
    addTriangle(*bad, {0, 0.2f, 0}, {-kInf, -kInf, kInf}, {0.5f, 1, 0}, {0, 0, 1}, m);   // Inf everywhere
    // Two small quads on the back wall (z = -0.99, facing +Z) with broken normals.
    addQuad(*bad, {-0.8f, 1.4f, -0.99f}, {-0.4f, 1.4f, -0.99f}, {-0.4f, 1.8f, -0.99f}, {-0.8f, 1.8f, -0.99f}, m);
    for (auto& v : bad->parts.back().vertices) v.normal = glm::vec3(0.0f);
    addQuad(*bad, {0.4f, 1.4f, -0.99f}, {0.8f, 1.4f, -0.99f}, {0.8f, 1.8f, -0.99f}, {0.4f, 1.8f, -0.99f}, m);
    for (auto& v : bad->parts.back().vertices) v.normal = glm::vec3(kNaN);
    bad->bounds = clean->bounds;  // computeBounds() would take in the Inf vertices: a camera/shadow problem of its own
    const Camera cam = selectCamera(*clean, "front");
    Settings s;
    s.lengthUnit = 1.0f;  // the lengths below are in scene units
    s.radius = 1.5f;
    s.minSeparation = 0.2f;
    Renderer r;
    r.setScene(bad);
    r.resize(96, 72);
    r.setCamera(cam);
    for (int i = 0; i < 6; ++i) r.render(s);
    expectAllBuffersFinite(r, "degenerate");
    // Pixels of the two quads: project their centres.
    const glm::mat4 vp = cam.projection(96.0f / 72.0f) * cam.view();
    for (const glm::vec3 c : {glm::vec3(-0.6f, 1.6f, -0.99f), glm::vec3(0.6f, 1.6f, -0.99f)}) {
        glm::vec4 p = vp * glm::vec4(c, 1.0f);
        const int px = int((p.x / p.w * 0.5f + 0.5f) * 96), py = int((0.5f - p.y / p.w * 0.5f) * 72);
        FloatImage n = r.readLayer("Normal 1");
        const glm::vec3 got(n.at(px, py, 0), n.at(px, py, 1), n.at(px, py, 2));
        EXPECT_GT(glm::dot(got, glm::vec3(0, 0, 1)), std::cos(glm::radians(2.0f))) << "quad at x " << c.x << ": " << got.x << " " << got.y << " " << got.z;
    }
    // Everything else as in the clean room: compare the lower half (the floor, box and walls below the quads).
    Renderer rc;
    rc.setScene(clean);
    rc.resize(96, 72);
    rc.setCamera(cam);
    for (int i = 0; i < 6; ++i) rc.render(s);
    FloatImage a = r.readFinalRadiance(), b = rc.readFinalRadiance();
    a.pixels.erase(a.pixels.begin(), a.pixels.begin() + a.pixels.size() / 2);
    b.pixels.erase(b.pixels.begin(), b.pixels.begin() + b.pixels.size() / 2);
    const double rel = meanRelDiff(a, b);
    std::printf("degenerate vs clean, lower half: mean relative difference %.4f\n", rel);
    EXPECT_LT(rel, 0.02);
}

// Non-finite vertices in the scene bounds (a Scene built in code, no loader to skip them): the framing camera,
// the clip planes and the sun's shadow box all derive from the bounds. Asserted: every buffer finite.
TEST_F(GLTest, NonFiniteBoundsRenderFinite) {
    auto scene = cornellScene();
    const int m = addMaterial(*scene, glm::vec3(0.5f));
    addTriangle(*scene, {0, 0.2f, 0}, {kInf, 1, 0}, {0.5f, 1, 0}, {0, 0, 1}, m);
    addTriangle(*scene, {0, 0.2f, 0}, {kNaN, 1, 0}, {0.5f, 1, 0}, {0, 0, 1}, m);
    scene->computeBounds();
    for (const char* camName : {"front", ""}) {
        Renderer r;
        r.setScene(scene);
        r.resize(48, 36);
        Camera cam = camName[0] ? selectCamera(*scene, camName) : framingCamera(scene->bounds);
        r.setCamera(cam);
        Settings s;
        for (int i = 0; i < 3; ++i) r.render(s);
        expectAllBuffersFinite(r, std::string("camera '") + camName + "'");
        if (camName[0]) EXPECT_GT(meanChannel(r.readFinalRadiance(), 0), 0.01) << "the room stays lit";
    }
}

// Two coplanar overlapping quads (red and green, z-fighting) in front of a wall. Asserted: finite; every pixel of
// the overlap has exactly one of the two albedos (no blend, no garbage); layer 2 never holds the coplanar twin
// (it is nearer than the minimum separation): Depth 2 there is the wall behind.
TEST_F(GLTest, CoplanarOverlappingSurfaces) {
    auto s = std::make_shared<Scene>();
    const int red = addMaterial(*s, glm::vec3(0.8f, 0.1f, 0.1f)), green = addMaterial(*s, glm::vec3(0.1f, 0.8f, 0.1f));
    const int grey = addMaterial(*s, glm::vec3(0.5f));
    addQuad(*s, {-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -2}, red);
    addQuad(*s, {-0.5f, -1.5f, -2}, {1.5f, -1.5f, -2}, {1.5f, 0.5f, -2}, {-0.5f, 0.5f, -2}, green);
    addQuad(*s, {-20, -20, -5}, {20, -20, -5}, {20, 20, -5}, {-20, 20, -5}, grey);
    addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
    s->computeBounds();
    auto renderer = rendererFor(s, 64, 64, "cam");
    Renderer& r = *renderer;
    Settings st;
    st.lengthUnit = 1.0f;  // the lengths below are in scene units
    st.minSeparation = 0.5f;
    for (int i = 0; i < 4; ++i) r.render(st);
    expectAllBuffersFinite(r, "coplanar");
    FloatImage albedo = r.readLayer("Albedo 1");
    int overlap = 0, odd = 0, wrongLayer2 = 0, overlap2 = 0;
    // The overlap (x in [-0.5, 1], y in [-1, 0.5] at z = -2) in pixels: tan(30 deg) * 2 = 1.155 half-extent.
    auto inOverlap = [](int x, int y) {
        const float wx = ((x + 0.5f) / 32.0f - 1.0f) * 1.1547f, wy = (1.0f - (y + 0.5f) / 32.0f) * 1.1547f;
        return !(wx < -0.45f || wx > 0.95f || wy < -0.95f || wy > 0.45f);
    };
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            if (!inOverlap(x, y)) continue;
            ++overlap;
            const float rr = albedo.at(x, y, 0), gg = albedo.at(x, y, 1);
            const bool isRed = std::abs(rr - 0.8f) < 0.01f && std::abs(gg - 0.1f) < 0.01f;
            const bool isGreen = std::abs(rr - 0.1f) < 0.01f && std::abs(gg - 0.8f) < 0.01f;
            if (!isRed && !isGreen) ++odd;
        }
    // Layer 2 at the level it is drawn at, each texel judged at the pixel whose ray it sampled.
    const Layer2Image d2 = readLayer2(r, "Depth 2");
    for (int y = 0; y < d2.image.height; ++y)
        for (int x = 0; x < d2.image.width; ++x) {
            const glm::ivec2 p = d2.pixel(x, y);
            if (!inOverlap(p.x, p.y)) continue;
            ++overlap2;
            if (std::abs(d2.image.at(x, y, 0) - 5.0f) > 0.01f) ++wrongLayer2;
        }
    EXPECT_GT(overlap2, 500 >> (2 * d2.level));
    EXPECT_GT(overlap, 500);
    EXPECT_EQ(odd, 0);
    EXPECT_EQ(wrongLayer2, 0);
}

// Back faces: a single-sided quad seen from behind is invisible (the backdrop shows through: Final Radiance =
// light.background exactly), a double-sided one is visible with its normal flipped towards the camera.
TEST_F(GLTest, BackFacesCulledUnlessDoubleSided) {
    for (bool doubleSided : {false, true}) {
        auto s = std::make_shared<Scene>();
        const int m = addMaterial(*s, glm::vec3(0.7f), glm::vec3(0.0f), doubleSided);
        addQuad(*s, {-5, -5, -2}, {-5, 5, -2}, {5, 5, -2}, {5, -5, -2}, m);  // faces -Z, away from the camera
        addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
        s->computeBounds();
        auto renderer = rendererFor(s, 32, 32, "cam");
        Renderer& r = *renderer;
        Settings st;
        st.background = 0.25f;
        st.sunElevation = 10.0f;
        st.sunAzimuth = 0.0f;  // from +Z, behind the camera: lights the back side
        for (int i = 0; i < 3; ++i) r.render(st);
        expectAllBuffersFinite(r, doubleSided ? "double-sided" : "single-sided");
        FloatImage fin = r.readFinalRadiance(), n = r.readLayer("Normal 1");
        if (!doubleSided) {
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) ASSERT_EQ(fin.at(x, y, 0), 0.25f) << x << "," << y;
        } else {
            EXPECT_GT(n.at(16, 16, 2), 0.999f) << "normal faces the camera";
            // Lambert: 0.7 / pi * 3 * cos(10 deg), the sun 10 degrees above the quad's back normal
            EXPECT_NEAR(fin.at(16, 16, 1), 0.7f / float(M_PI) * 3.0f * std::cos(glm::radians(10.0f)), 0.02f);
        }
    }
}

// The camera inside a solid box (outward faces: from inside, all back faces) in the Cornell room, and the camera
// exactly on a surface (eye on the floor plane looking along it, eye on the back wall looking into the room, eye
// on an edge of the box). Asserted: every buffer finite, every depth within the clip range; inside the box its
// faces are culled, so the nearest thing seen is a room wall (Depth 1 > 0.4 everywhere; the box faces are
// 0.1-0.3 away).
TEST_F(GLTest, CameraInsideGeometryOrOnASurface) {
    auto scene = cornellScene();
    Settings s;
    s.lengthUnit = 1.0f;  // the lengths below are in scene units
    s.radius = 1.5f;
    s.minSeparation = 0.2f;
    struct View { const char* name; Camera cam; };
    const View views[] = {
        {"inside the box", lookAt({-0.35f, 0.6f, -0.25f}, {0.5f, 0.8f, -1.0f})},
        {"on the floor plane", lookAt({0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, -1.0f})},
        {"on the back wall", lookAt({0.3f, 1.0f, -1.0f}, {0.3f, 1.0f, 1.0f})},
        {"on a box edge", lookAt({-0.1f, 1.2f, 0.0f}, {0.5f, 0.5f, -1.0f})},
    };
    for (const auto& v : views) {
        Renderer r;
        r.setScene(scene);
        r.resize(48, 36);
        r.setCamera(v.cam);
        for (int i = 0; i < 4; ++i) r.render(s);
        expectAllBuffersFinite(r, v.name);
        const FloatImage d1 = r.readLayer("Depth 1");
        const float nearest = *std::min_element(d1.pixels.begin(), d1.pixels.end());
        std::printf("%s: nearest depth %.4f, mean radiance %.4f\n", v.name, nearest, meanChannel(r.readFinalRadiance(), 1));
        EXPECT_GE(nearest, v.cam.znear * 0.999f) << v.name;
        if (v.name[0] == 'i') EXPECT_GT(nearest, 0.4f) << "the box's own faces must be culled";
    }
}

// ------------------------------------------------------------------------------------------------------ motion

namespace {

// Deterministic settings for history comparisons: one bounce (no feedback) and a fixed tap pattern, so a frame
// without history depends only on the camera; what differs from it is history.
Settings motionSettings() {
    Settings s;
    s.lengthUnit = 1.0f;  // the lengths below are in scene units
    s.radius = 1.5f;
    s.minSeparation = 0.2f;
    s.damping = 1.0f;
    s.varyTaps = false;
    // The screen's history under motion alone: the probe volume keeps converging from frame to frame, which a
    // comparison with a fresh renderer would count as ghosting.
    s.probesEnabled = false;
    return s;
}

}  // namespace

// A camera cut: 10 frames from the front, then a jump to a view from the left corner with resetHistory(). The first
// frame after the cut equals a fresh renderer's first frame of that view (mean relative difference < 1%: only the
// per-frame dither of the stores differs) and nothing is reprojected (Reprojected Radiance all 0). Without the reset
// the same jump keeps history from the first view (the test checks it differs, so it can tell).
TEST_F(GLTest, CameraCutLeavesNoGhost) {
    auto scene = cornellScene();
    // Full resolution: at 64x48 the half-resolution grid's 768 texels happen to find no surface within the (tight,
    // 0.3 % of the scene) reprojection distance after this jump, and the control below needs some that do.
    Settings s = motionSettings();
    s.radiosityResolution = RadiosityResolution::Full;
    const Camera a = selectCamera(*scene, "front"), b = lookAt({-0.8f, 1.6f, 0.8f}, {0.3f, 0.6f, -0.6f});
    const FloatImage fresh = freshFrame(scene, b, s, 64, 48);
    for (bool reset : {true, false}) {
        Renderer r;
        r.setScene(scene);
        r.resize(64, 48);
        r.setCamera(a);
        for (int i = 0; i < 10; ++i) r.render(s);
        r.setCamera(b);
        if (reset) r.resetHistory();
        r.render(s);
        expectAllBuffersFinite(r, "cut");
        const double rel = meanRelDiff(r.readFinalRadiance(), fresh);
        const FloatImage reproj = r.readLayer("Reprojected Radiance");
        const double reprojected = meanChannel(reproj, 0) + meanChannel(reproj, 1) + meanChannel(reproj, 2);
        std::printf("cut %s reset: difference to a fresh first frame %.5f, reprojected %.5f\n", reset ? "with" : "without", rel, reprojected);
        if (reset) {
            EXPECT_LT(rel, 0.01);
            EXPECT_EQ(reprojected, 0.0);
        } else {
            EXPECT_GT(reprojected, 0.0) << "without a reset the history is used (this is what the reset must prevent)";
        }
    }
}

// A 180-degree turn every frame (room centre, looking -Z then +Z, 20 frames). The two views share no surface, so
// every frame is a full disocclusion: Reprojected Radiance is 0 everywhere and each frame equals a fresh first
// frame of its view (mean relative difference < 1%); every buffer finite.
TEST_F(GLTest, HalfTurnEveryFrameReprojectsNothing) {
    auto scene = cornellScene();
    const Settings s = motionSettings();
    const Camera views[2] = {lookAt({0, 1, 0}, {0, 1, -1}, 60.0f), lookAt({0, 1, 0}, {0, 1, 1}, 60.0f)};
    const FloatImage fresh[2] = {freshFrame(scene, views[0], s, 48, 36), freshFrame(scene, views[1], s, 48, 36)};
    Renderer r;
    r.setScene(scene);
    r.resize(48, 36);
    double worst = 0.0, reprojected = 0.0;
    for (int f = 0; f < 20; ++f) {
        r.setCamera(views[f & 1]);
        r.render(s);
        if (f == 0) continue;
        const FloatImage reproj = r.readLayer("Reprojected Radiance");
        reprojected = std::max(reprojected, meanChannel(reproj, 0) + meanChannel(reproj, 1) + meanChannel(reproj, 2));
        worst = std::max(worst, meanRelDiff(r.readFinalRadiance(), fresh[f & 1]));
    }
    std::printf("half turns: worst difference to a fresh frame %.5f, reprojected %.5f\n", worst, reprojected);
    EXPECT_EQ(reprojected, 0.0);
    EXPECT_LT(worst, 0.01);
    expectAllBuffersFinite(r, "half turns");
}

// Fast translation: 0.2 m per frame (1/10 of the room) across the room and back, 16 frames. The history is a
// convex blend of earlier gathers, so it may carry light gathered while the sunlit red wall was on screen (a fresh
// frame at the same pose differs by 130% on average: a screen-space gather forgets what leaves the view, the
// history does not), but it must not invent any: asserted, every buffer finite and the brightest Output Radiance
// pixel of any moving frame at most 5% above the brightest pixel of fresh first frames at all the poses.
// The smear itself is asserted against the blend law: a twin renderer on the same path with temporal.enabled =
// false gives this frame's own (history-free) irradiance F, and the temporal blend E = F + w (H - F), w <= alpha
// (H: Reprojected Radiance) bounds every pixel's smear |E - F| by alpha |H - F| (+ three R11G11B10 steps of rounding).
TEST_F(GLTest, FastTranslationBoundedSmearing) {
    auto scene = cornellScene();
    // The law is the temporal blend's over a gather of every pixel: with radiosity.interleave the reusing blocks'
    // own irradiance is the history itself (tests/test_interleaved_gather.cpp checks that path).
    const Settings s = [] {
        Settings m = motionSettings();
        m.interleave = RadiosityInterleave::Off;
        return m;
    }();
    Settings noTemporal = s;
    noTemporal.temporal = false;
    Renderer r, twin;
    for (Renderer* x : {&r, &twin}) {
        x->setScene(scene);
        x->resize(48, 36);
    }
    double sum = 0.0, smear = 0.0, historyGap = 0.0;
    int beyondLaw = 0;
    float brightestMoving = 0.0f, brightestFresh = 0.0f;
    for (int f = 0; f < 16; ++f) {
        const float x = -0.7f + 0.2f * float(f < 8 ? f : 15 - f);
        const Camera cam = lookAt({x, 1.0f, 0.9f}, {x * 0.5f, 0.9f, -1.0f});
        r.setCamera(cam);
        r.render(s);
        twin.setCamera(cam);
        twin.render(noTemporal);
        const FloatImage moving = r.readLayer("Output Radiance"), fresh = freshFrame(scene, cam, s, 48, 36, "Output Radiance");
        const FloatImage own = twin.readLayer("Output Radiance"), history = r.readLayer("Reprojected Radiance");
        for (float v : moving.pixels) brightestMoving = std::max(brightestMoving, v);
        for (float v : fresh.pixels) brightestFresh = std::max(brightestFresh, v);
        sum += meanRelDiff(moving, fresh);
        for (size_t i = 0; i < moving.pixels.size(); ++i) {
            const double E = moving.pixels[i], F = own.pixels[i], H = history.pixels[i];
            const double tol = 3.0 / 32.0 * std::max({std::abs(E), std::abs(F), std::abs(H)}) + 2e-6;
            smear += std::abs(E - F);
            historyGap += std::abs(H - F);
            if (std::abs(E - F) > s.hysteresis * std::abs(H - F) + tol) {
                if (beyondLaw < 5) std::printf("frame %d value %zu: E %g, own F %g, history H %g\n", f, i, E, F, H);
                ++beyondLaw;
            }
        }
    }
    std::printf("fast translation: mean difference to fresh frames %.4f; smear / history gap %.4f (alpha %.2f); "
                "brightest moving %.4f, fresh %.4f\n", sum / 16, smear / historyGap, s.hysteresis, brightestMoving, brightestFresh);
    EXPECT_EQ(beyondLaw, 0) << "a pixel's smear exceeds alpha times its history's difference";
    EXPECT_GT(smear, 0.0) << "the motion must exercise the history";
    EXPECT_LE(smear, s.hysteresis * historyGap);
    EXPECT_LE(brightestMoving, 1.05f * brightestFresh);
    expectAllBuffersFinite(r, "fast translation");
}

// Grazing angle: a large floor seen at 89.9 degrees from its normal (the view 0.1 degrees below the horizon), the
// camera creeping forward 1 cm per frame for 12 frames. Asserted: every buffer finite; the history does not smear
// the grazing floor: Output Radiance within 15% (mean relative difference) of a fresh frame at the last pose.
TEST_F(GLTest, GrazingAngleFiniteWithoutSmearing) {
    auto s = std::make_shared<Scene>();
    const int m = addMaterial(*s, glm::vec3(0.8f));
    addFloor(*s, 200.0f, 0.0f, m);
    addQuad(*s, {-200, 0, -200}, {200, 0, -200}, {200, 20, -200}, {-200, 20, -200}, m);  // a far wall facing +Z
    addSun(*s, {0.3f, -1.0f, -0.5f}, 3.0f);
    s->computeBounds();
    Settings st = motionSettings();
    st.lengthUnit = 1.0f;  // the lengths below are in scene units
    st.radius = 2.0f;
    Renderer r;
    r.setScene(s);
    r.resize(64, 48);
    Camera cam;
    for (int f = 0; f < 12; ++f) {
        const glm::vec3 eye(0.0f, 0.2f, 150.0f - 0.01f * f);
        const glm::vec3 dir(0.0f, -std::sin(glm::radians(0.1f)), -std::cos(glm::radians(0.1f)));
        cam = lookAt(eye, eye + dir, 60.0f);
        cam.zfar = 500.0f;
        r.setCamera(cam);
        r.render(st);
    }
    expectAllBuffersFinite(r, "grazing");
    const double rel = meanRelDiff(r.readLayer("Output Radiance"), freshFrame(s, cam, st, 64, 48, "Output Radiance"));
    std::printf("grazing: difference to a fresh frame %.4f\n", rel);
    EXPECT_LT(rel, 0.15);
}

// ------------------------------------------------------------------------------------------------ trivial scenes

// Empty scene (no geometry, no lights: the default sun lights nothing) and sky only (the room behind the camera):
// every buffer finite, Final Radiance = light.background exactly everywhere, no indirect light.
TEST_F(GLTest, EmptySceneAndSkyOnlyShowTheBackground) {
    auto room = cornellScene();
    struct Case { const char* name; std::shared_ptr<Scene> scene; Camera cam; };
    const Case cases[] = {
        {"empty", std::make_shared<Scene>(), framingCamera(Aabb{})},
        {"sky only", room, lookAt({0.0f, 1.0f, 5.0f}, {0.0f, 1.0f, 10.0f})},
    };
    for (const auto& c : cases) {
        Renderer r;
        r.setScene(c.scene);
        r.resize(32, 24);
        r.setCamera(c.cam);
        Settings s;
        s.background = 0.375f;
        for (int i = 0; i < 3; ++i) r.render(s);
        expectAllBuffersFinite(r, c.name);
        const FloatImage fin = r.readFinalRadiance(), out = r.readLayer("Output Radiance");
        for (int y = 0; y < fin.height; ++y)
            for (int x = 0; x < fin.width; ++x)
                for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(fin.at(x, y, ch), 0.375f) << c.name << " " << x << "," << y;
        for (int y = 0; y < out.height; ++y)  // the radiosity grid (half the screen on llvmpipe)
            for (int x = 0; x < out.width; ++x)
                for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(out.at(x, y, ch), 0.0f) << c.name;
    }
}

// One triangle, and one surface filling the screen, under a sun at a known angle: finite; the screen-filling
// plane shows exactly Lambert's rho/pi * E * cos (it has no other surface to receive light from, so indirect = 0),
// within 1% on every pixel; the triangle covers the pixels its projection says (centre lit, corners background).
TEST_F(GLTest, OneTriangleAndFullScreenSurface) {
    const float rho = 0.6f, E = 2.0f, elevation = 40.0f;
    {
        auto s = std::make_shared<Scene>();
        const int m = addMaterial(*s, glm::vec3(rho));
        addQuad(*s, {-50, -50, -3}, {50, -50, -3}, {50, 50, -3}, {-50, 50, -3}, m);  // faces +Z
        addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
        s->computeBounds();
        auto renderer = rendererFor(s, 40, 30, "cam");
        Renderer& r = *renderer;
        Settings st;
        st.sunIntensity = E;
        st.sunAzimuth = 0.0f;
        st.sunElevation = elevation;  // toSun = (0, sin 40, cos 40): cos to the +Z normal = cos 40
        for (int i = 0; i < 4; ++i) r.render(st);
        expectAllBuffersFinite(r, "full screen");
        const float expected = rho / float(M_PI) * E * std::cos(glm::radians(elevation));
        const FloatImage fin = r.readFinalRadiance();
        for (int y = 0; y < fin.height; ++y)
            for (int x = 0; x < fin.width; ++x) ASSERT_NEAR(fin.at(x, y, 0), expected, 0.01f * expected) << x << "," << y;
    }
    {
        auto s = std::make_shared<Scene>();
        const int m = addMaterial(*s, glm::vec3(rho));
        addTriangle(*s, {-1, -1, -3}, {1, -1, -3}, {0, 1, -3}, {0, 0, 1}, m);
        addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
        s->computeBounds();
        auto renderer = rendererFor(s, 40, 40, "cam");
        Renderer& r = *renderer;
        Settings st;
        st.sunIntensity = E;
        st.sunAzimuth = 0.0f;
        st.sunElevation = elevation;
        st.background = 0.125f;
        for (int i = 0; i < 4; ++i) r.render(st);
        expectAllBuffersFinite(r, "one triangle");
        const FloatImage fin = r.readFinalRadiance();
        const float expected = rho / float(M_PI) * E * std::cos(glm::radians(elevation));
        EXPECT_NEAR(fin.at(20, 22, 0), expected, 0.01f * expected);
        for (auto [x, y] : {std::pair{0, 0}, std::pair{39, 0}, std::pair{0, 39}, std::pair{39, 39}, std::pair{20, 2}})
            EXPECT_EQ(fin.at(x, y, 0), 0.125f) << x << "," << y;
    }
}

// ----------------------------------------------------------------------------------------------------- sizes

// 1x1 renders finite images; 0x0 makes render() a no-op (no frame counted, no timings) and resizing back works.
TEST_F(GLTest, TinyAndZeroSizes) {
    auto scene = cornellScene();
    Renderer r;
    r.setScene(scene);
    r.setCamera(selectCamera(*scene, "front"));
    Settings s;
    r.resize(1, 1);
    for (int i = 0; i < 3; ++i) r.render(s);
    expectAllBuffersFinite(r, "1x1");
    EXPECT_EQ(r.readFinalRadiance().pixels.size(), 4u);
    const uint64_t frames = r.frameIndex();
    r.resize(0, 0);
    EXPECT_NO_THROW(r.render(s));
    EXPECT_EQ(r.frameIndex(), frames);
    EXPECT_TRUE(r.timings().empty());
    r.resize(64, 48);
    for (int i = 0; i < 2; ++i) r.render(s);
    expectAllBuffersFinite(r, "back to 64x48");
    EXPECT_EQ(r.readFinalRadiance().width, 64);
    EXPECT_GT(meanChannel(r.readFinalRadiance(), 0), 0.0);
    EXPECT_THROW(r.resize(-1, 10), std::runtime_error);
}

// A size too large is a clear std::runtime_error before anything is allocated, and the renderer keeps working:
// 100000 x 100000 exceeds GL_MAX_TEXTURE_SIZE (16384 on llvmpipe); 16384 x 16384 is within it but needs ~17 GiB of
// textures, more than the budget (set to 4 GiB here so the test does not depend on this machine's memory). Also
// checked: what llvmpipe itself does with a 100000 x 100000 texture (an error, not a crash or a huge allocation).
TEST_F(GLTest, SizeTooLargeIsAClearError) {
    {
        GLuint t = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &t);
        while (glGetError() != GL_NO_ERROR) {}
        glTextureStorage2D(t, 1, GL_R11F_G11F_B10F, 100000, 100000);
        const GLenum err = glGetError();
        std::printf("llvmpipe, glTextureStorage2D 100000x100000: GL error 0x%x\n", err);
        EXPECT_NE(err, GLenum(GL_NO_ERROR));
        glDeleteTextures(1, &t);
    }
    auto scene = cornellScene();
    Renderer r;
    r.setScene(scene);
    r.setCamera(selectCamera(*scene, "front"));
    r.textures().setMemoryBudget(uint64_t(4) << 30);
    Settings s;
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    for (auto [w, h, word] : {std::tuple{100000, 100000, "GL_MAX_TEXTURE_SIZE"}, std::tuple{maxSize, maxSize, "memory budget"}}) {
        r.resize(w, h);
        try {
            r.render(s);
            ADD_FAILURE() << w << "x" << h << " rendered";
        } catch (const std::runtime_error& e) {
            std::printf("%dx%d: %s\n", w, h, e.what());
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::to_string(w)), std::string::npos) << e.what();
        }
    }
    r.resize(32, 24);
    r.render(s);
    expectAllBuffersFinite(r, "after the refusals");
}
