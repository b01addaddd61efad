// Each pass proven on a scene built for it.
#include "gl_fixture.h"

#include <map>

#include "renderer/passes/radiosity_gather_pass.h"

#include <glm/gtc/matrix_transform.hpp>

#include <numeric>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

// Camera at the origin looking down -Z; a plane facing it at z = -2 (|x|,|y| < 0.5), a box with its front face at
// z = -3 behind it, and a wall at z = -6.
std::shared_ptr<Scene> layeredScene() {
    auto s = std::make_shared<Scene>();
    int m = addMaterial(*s, glm::vec3(0.5f));
    addQuad(*s, {-0.5f, -0.5f, -2.0f}, {0.5f, -0.5f, -2.0f}, {0.5f, 0.5f, -2.0f}, {-0.5f, 0.5f, -2.0f}, m);
    addBox(*s, {-1.0f, -1.0f, -4.0f}, {1.0f, 1.0f, -3.0f}, m, false);
    addQuad(*s, {-20, -20, -6}, {20, -20, -6}, {20, 20, -6}, {-20, 20, -6}, m);
    addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
    s->computeBounds();
    return s;
}

float centre(const FloatImage& img, int c = 0) { return img.at(img.width / 2, img.height / 2, c); }

void fillTexture(GLuint tex, const glm::vec3& v) { glClearTexImage(tex, 0, GL_RGB, GL_FLOAT, &v.x); }

}  // namespace

// radiosity.min_mip is the finest tap level up to radiosity.min_mip_height rows; each doubling of the height above
// that makes it one level coarser, never past kMaxTapLevel; a height of 0 keeps min_mip at every height.
TEST(FinestTapLevel, OneLevelCoarserPerDoublingAboveTheHeight) {
    EXPECT_EQ(finestTapLevel(2, 180, 90), 2);
    EXPECT_EQ(finestTapLevel(2, 180, 180), 2);
    EXPECT_EQ(finestTapLevel(2, 180, 359), 2);
    EXPECT_EQ(finestTapLevel(2, 180, 360), 3);
    EXPECT_EQ(finestTapLevel(2, 180, 719), 3);
    EXPECT_EQ(finestTapLevel(2, 180, 720), 4);
    EXPECT_EQ(finestTapLevel(2, 180, 1080), 4);
    EXPECT_EQ(finestTapLevel(3, 180, 2880), 5);  // 3 + 4 doublings, held at the coarsest level the gather reads
    EXPECT_EQ(finestTapLevel(0, 1, 1 << 30), kMaxTapLevel);
    EXPECT_EQ(finestTapLevel(2, 0, 100000), 2);
    EXPECT_EQ(finestTapLevel(0, 100000, 4320), 0);
}

// The renderer draws layer 2 and evaluates the taps' radiance at that level of the image's height: a guard band
// (gbuffer.guard_band) makes the frame taller (72 rows here, past 2 x 25) but not the image, and leaves the level alone.
TEST_F(GLTest, TapLevelFollowsTheImageHeight) {
    auto scene = layeredScene();
    struct Case { int minMipHeight; float guard; int level; };
    for (const Case& c : {Case{0, 0.0f, 2}, Case{24, 0.0f, 3}, Case{12, 0.0f, 4}, Case{25, 0.0f, 2}, Case{25, 0.25f, 2}}) {
        auto renderer = rendererFor(scene, 64, 48, "cam");
        Renderer& r = *renderer;
        Settings s;
        s.minMip = 2;
        s.minMipHeight = c.minMipHeight;
        s.guardBand = c.guard;
        s.layer2Prepass = Layer2Prepass::On;  // layer 2 drawn alone, at the tap level
        for (int i = 0; i < 2; ++i) r.render(s);
        EXPECT_EQ(r.config().tapLevel, c.level) << "min_mip_height " << c.minMipHeight << " guard " << c.guard;
        EXPECT_EQ(readLayer2(r, "Depth 2").level, c.level) << "min_mip_height " << c.minMipHeight;
    }
}

// Layer 2 of a box behind a plane has the analytic depth and honours the minimum separation, in both the
// single-pass predicted mode (still camera) and the two-pass depth-peeling oracle, with either layer routing (the
// vertex stage's gl_Layer, or the geometry shader), with and without layer 2's depth prepass.
TEST_F(GLTest, DeepGBufferLayer2DepthAndMinimumSeparation) {
    auto scene = layeredScene();
    for (int minMip : {2, 0})  // layer 2 alone drawn at the tap level, or at full resolution
    for (Layer2Prepass prepass : {Layer2Prepass::Off, Layer2Prepass::On})
    for (LayerRouting routing : {LayerRouting::Vertex, LayerRouting::Geometry})
    for (GBufferGeneration generation : {GBufferGeneration::Predicted, GBufferGeneration::DepthPeel}) {
        for (auto [dz, expected] : {std::pair{0.5f, 3.0f}, std::pair{1.5f, 6.0f}}) {
            auto renderer = rendererFor(scene, 64, 48, "cam");
            Renderer& r = *renderer;
            Settings s;
            s.layerRouting = routing;
            s.layer2Prepass = prepass;
            s.generation = generation;
            s.lengthUnit = 1.0f;  // the lengths below are in scene units
            s.minSeparation = dz;
            s.minMip = minMip;
            for (int i = 0; i < 3; ++i) r.render(s);
            // Layer 2 alone at the tap level is one draw (the prepass only at full resolution).
            const int passes = prepass == Layer2Prepass::Off && generation == GBufferGeneration::Predicted ? 1
                               : prepass == Layer2Prepass::On && minMip == 0                             ? 3
                                                                                                          : 2;
            EXPECT_EQ(r.lastGeometryPasses(), passes) << "min_mip " << minMip;
            // Layer 2 drawn alone (prepass, peeling) is drawn at the gather's finest tap level, its level 0 empty.
            const bool alone = prepass == Layer2Prepass::On || generation == GBufferGeneration::DepthPeel;
            FloatImage d1 = r.readLayer("Depth 1");
            const Layer2Image d2 = readLayer2(r, "Depth 2");
            EXPECT_EQ(d2.level, alone ? r.config().tapLevel : 0);
            EXPECT_EQ(r.config().tapLevel, minMip);
            EXPECT_NEAR(centre(d1), 2.0f, 2e-3f) << "generation " << int(generation);
            EXPECT_NEAR(centre(d2.image), expected, 2e-3f * expected) << "generation " << int(generation) << " dz " << dz;
            // Where nothing is in front, layer 1 is the wall and layer 2 is empty (far plane).
            EXPECT_NEAR(d1.at(2, 2, 0), 6.0f, 2e-3f * 6.0f);
            const glm::ivec2 corner = d2.pixel(0, 0);
            EXPECT_NEAR(d1.at(corner.x, corner.y, 0), 6.0f, 2e-3f * 6.0f);
            EXPECT_GE(d2.image.at(0, 0, 0), r.camera().zfar * 0.999f);
            if (d2.level > 0) {
                const FloatImage base = r.readLayer("Depth 2", 0);
                EXPECT_GE(*std::min_element(base.pixels.begin(), base.pixels.end()), r.camera().zfar * 0.999f);
            }
        }
    }
}

// The two layer routings, with and without layer 2's depth prepass, fill the same deep G-buffer, layer 1 and the
// predicted layer 2, while the camera moves (the prediction reads last frame's depth). On llvmpipe, which has
// GL_ARB_shader_viewport_layer_array, auto takes the vertex route and, on this small scene, the prepass; the
// geometry shader's single draw is the paper's and the independent answer.
TEST_F(GLTest, LayerRoutingsFillTheSameDeepGBuffer) {
    auto scene = cornellScene();
    std::map<std::string, Layer2Image> got[2];
    for (int k : {0, 1}) {
        auto renderer = rendererFor(scene, 80, 60, "front");
        Renderer& r = *renderer;
        Settings s;
        s.layerRouting = k == 0 ? LayerRouting::Auto : LayerRouting::Geometry;
        s.layer2Prepass = k == 0 ? Layer2Prepass::Auto : Layer2Prepass::Off;
        s.lengthUnit = 1.0f;
        s.minSeparation = 0.2f;
        Camera cam = r.camera();
        for (int i = 0; i < 4; ++i) {
            cam.cameraToWorld[3] += glm::vec4(0.03f, 0.0f, 0.0f, 0.0f);
            r.setCamera(cam);
            r.render(s);
        }
        EXPECT_EQ(r.config().layeredVertex, k == 0) << "auto takes the vertex route on llvmpipe";
        EXPECT_EQ(r.config().layer2Prepass, k == 0) << "auto takes the prepass on llvmpipe with few triangles";
        for (const char* name : {"Depth 1", "Normal 1", "Albedo 1"}) {
            FloatImage img = r.readLayer(name);
            got[k][name] = {img, 0, img.height};
        }
        for (const char* name : {"Depth 2", "Normal 2", "Albedo 2"}) got[k][name] = readLayer2(r, name);
        EXPECT_EQ(got[k]["Depth 2"].level, k == 0 ? r.config().tapLevel : 0) << "the prepass draws layer 2 at level L";
    }
    // The prepass's layer 2, drawn at level L, holds the samples of the one draw's full-resolution layer 2 that
    // level L stands for (the same rays), up to the rasteriser's rounding of depth.
    for (const auto& [name, a] : got[0]) {
        const Layer2Image& b = got[1][name];
        ASSERT_EQ(b.level, 0);
        int differ = 0, texels = 0;
        for (int y = 0; y < a.image.height; ++y)
            for (int x = 0; x < a.image.width; ++x) {
                const glm::ivec2 p = a.pixel(x, y);
                for (int c = 0; c < a.image.channels; ++c) {
                    const float va = a.image.at(x, y, c), vb = b.image.at(p.x, p.y, c);
                    if (std::abs(va - vb) > 1e-5f * std::max(1.0f, std::abs(vb))) ++differ;
                }
                ++texels;
            }
        EXPECT_EQ(differ, 0) << name << " (" << texels << " texels)";
    }
}

// gbuffer.layer2_prepass=auto on llvmpipe splits the layers wherever the split costs no more geometry work: layer 2
// drawn alone at a tap level above 0 through the vertex route, at any triangle count; at level 0 (radiosity.min_mip=0,
// the AO alone) or through the geometry shader only while the scene has fewer triangles than twice the pixels.
TEST_F(GLTest, AutoLayer2PrepassSplitsTheLayersWhereItCostsNoMoreGeometryWork) {
    auto scene = cornellScene();
    struct Case {
        const char* what;
        int width, height;
        LayerRouting routing;
        int minMip;
        bool indirect, split;
    };
    const int many = 4, manyRows = 3;  // fewer than half as many pixels as the box has triangles (30)
    ASSERT_GT(scene->triangleCount(), size_t(2 * many * manyRows));
    ASSERT_LT(scene->triangleCount(), size_t(2 * 160 * 120));
    for (const Case& c : {Case{"vertex route, tap level 2", many, manyRows, LayerRouting::Auto, 2, true, true},
                          Case{"geometry shader", many, manyRows, LayerRouting::Geometry, 2, true, false},
                          Case{"tap level 0", many, manyRows, LayerRouting::Auto, 0, true, false},
                          Case{"the AO alone (layer 2 at level 0)", many, manyRows, LayerRouting::Auto, 2, false, false},
                          Case{"geometry shader, few triangles", 160, 120, LayerRouting::Geometry, 2, true, true}}) {
        auto renderer = rendererFor(scene, c.width, c.height, "front");
        Renderer& r = *renderer;
        Settings s;
        s.layerRouting = c.routing;
        s.minMip = c.minMip;
        s.indirect = c.indirect;
        s.aoEnabled = !c.indirect;
        for (int f = 0; f < 2; ++f) r.render(s);  // the second with history: a first frame always peels
        ASSERT_TRUE(r.config().layer2) << c.what;
        EXPECT_EQ(r.config().layer2Prepass, c.split) << c.what;
        if (c.split) EXPECT_EQ(r.lastLayer2Level(), r.config().tapLevel) << c.what << ": layer 2 drawn alone at the tap level";
    }
}

// gbuffer.view_culling leaves out of the deep G-buffer the parts wholly outside the view, and nothing else: the
// camera looks down -Z (60 degrees, 4:3) at a wall; quads at z = -4, where the image spans |x| < 3.08: A inside,
// D across the right edge, E beyond it but inside a 0.25 guard band (|x| < 4.23), C far to the side, and B behind
// the camera, where it still shadows the wall under a sun from behind (the shadow maps draw every part). The
// independent answers: which parts the frustum's planes exclude, the shadow, and the image without culling.
TEST_F(GLTest, ViewCullingLeavesOutOnlyPartsOutsideTheView) {
    auto scene = std::make_shared<Scene>();
    const int m = addMaterial(*scene, glm::vec3(0.6f));
    auto quadAt = [&](float x0, float x1, float y0, float y1, float z) {
        addQuad(*scene, {x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, m);
        return scene->parts.back().node;
    };
    quadAt(-8.0f, 8.0f, -8.0f, 8.0f, -6.0f);                // the wall
    quadAt(-2.0f, -1.0f, -0.5f, 0.5f, -4.0f);               // A
    quadAt(-1.0f, 1.0f, 0.0f, 1.0f, 3.0f);                  // B, behind the camera
    const int c = quadAt(19.0f, 20.0f, -0.5f, 0.5f, -4.0f);  // C
    quadAt(2.8f, 3.4f, -0.5f, 0.5f, -4.0f);                 // D
    quadAt(3.5f, 4.0f, -0.5f, 0.5f, -4.0f);                 // E
    addSun(*scene, glm::vec3(0.0f, -0.2f, -1.0f), 3.0f);
    addCamera(*scene, "cam", {0, 0, 0}, {0, 0, -1}, 60.0f);
    scene->computeBounds();
    const int W = 64, H = 48;
    for (float band : {0.0f, 0.25f}) {
        std::unique_ptr<Renderer> r[2] = {rendererFor(scene, W, H, "cam"), rendererFor(scene, W, H, "cam")};
        Settings s[2];
        for (int k : {0, 1}) {
            s[k].guardBand = band;
            s[k].viewCulling = k == 0;
        }
        auto renderBoth = [&] {
            for (int k : {0, 1})
                for (int f = 0; f < 3; ++f) r[k]->render(s[k]);
            EXPECT_EQ(r[1]->lastCulledParts(), 0);
            const FloatImage a = r[0]->readFinalRadiance(), b = r[1]->readFinalRadiance();
            float diff = 0.0f;
            for (size_t i = 0; i < a.pixels.size(); ++i) diff = std::max(diff, std::abs(a.pixels[i] - b.pixels[i]));
            EXPECT_EQ(diff, 0.0f) << "band " << band << ": the image without culling";
            for (const char* name : {"Depth 2", "Normal 2"}) {
                const Layer2Image a2 = readLayer2(*r[0], name), b2 = readLayer2(*r[1], name);
                EXPECT_EQ(a2.image.pixels, b2.image.pixels) << name << ", band " << band;
            }
            return a;
        };
        const FloatImage img = renderBoth();
        EXPECT_EQ(r[0]->lastCulledParts(), band > 0.0f ? 2 : 3) << "B and C, and E unless the band holds it";
        // B's shadow on the wall at (0, -1.3, -6), beside the lit wall at (2, -1.3, -6): pixels (32, 33) and (46, 33).
        EXPECT_LT(img.at(32, 33, 1), 0.5f * img.at(46, 33, 1)) << "the shadow of the part behind the camera";

        // C moved into the view: drawn from the frame it arrives in.
        scene->nodes[size_t(c)].local.translation = glm::vec3(-19.0f, 1.0f, 0.0f);
        scene->updateWorldTransforms();
        for (int k : {0, 1}) r[k]->sceneChanged(SceneChange::Transforms);
        renderBoth();
        EXPECT_EQ(r[0]->lastCulledParts(), band > 0.0f ? 1 : 2) << "B, and E unless the band holds it";
        scene->nodes[size_t(c)].local.translation = glm::vec3(0.0f);
        scene->updateWorldTransforms();
    }
}

// The predicted layer 2 equals the depth-peeled oracle for a still camera.
TEST_F(GLTest, PredictedLayer2MatchesPeelingForStillCamera) {
    auto scene = cornellScene();
    FloatImage depth[2];
    for (int g : {0, 1}) {
        auto renderer = rendererFor(scene, 80, 60, "front");
        Renderer& r = *renderer;
        Settings s;
        s.generation = GBufferGeneration(g);
        s.lengthUnit = 1.0f;  // the lengths below are in scene units
        s.minSeparation = 0.2f;
        for (int i = 0; i < 3; ++i) r.render(s);
        const Layer2Image d2 = readLayer2(r, "Depth 2");
        EXPECT_EQ(d2.level, r.config().tapLevel) << "both draw layer 2 alone on llvmpipe (the prepass, peeling)";
        depth[g] = d2.image;
    }
    int differ = 0;
    for (size_t i = 0; i < depth[0].pixels.size(); ++i)
        if (std::abs(depth[0].pixels[i] - depth[1].pixels[i]) > 1e-3f * depth[1].pixels[i]) ++differ;
    EXPECT_EQ(differ, 0);
}

// oct16 normals (RG8_SNORM) round-trip within 1.2 degrees for directions up to 70 degrees from the view axis.
TEST_F(GLTest, Oct16NormalsRoundTrip) {
    auto s = std::make_shared<Scene>();
    int m = addMaterial(*s, glm::vec3(0.5f));
    struct Tile { glm::vec3 n; int px, py; };
    std::vector<Tile> tiles;
    const int grid = 9, cell = 12;
    // A grid of small flat quads at z = -10, each tilted to its own normal (within 80 degrees of the view).
    const float fov = glm::radians(40.0f), half = 10.0f * std::tan(fov / 2);
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            float a = glm::radians(-70.0f + 140.0f * i / (grid - 1)), b = glm::radians(-70.0f + 140.0f * j / (grid - 1));
            glm::vec3 c(-half + (i + 0.5f) * 2 * half / grid, -half + (j + 0.5f) * 2 * half / grid, -10.0f);
            // Tilted by (a, b) away from the direction to the camera, so every tile faces it.
            const glm::vec3 toCam = glm::normalize(-c);
            const glm::vec3 t1 = glm::normalize(glm::cross(glm::vec3(0, 1, 0), toCam)), t2 = glm::cross(toCam, t1);
            glm::vec3 n = glm::normalize(toCam * std::cos(a) * std::cos(b) + t1 * std::sin(a) * std::cos(b) + t2 * std::sin(b));
            glm::vec3 t = glm::normalize(glm::cross(std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), n));
            glm::vec3 u = glm::cross(n, t);
            float e = 0.45f * half / grid * 2;
            addQuad(*s, c - t * e - u * e, c + t * e - u * e, c + t * e + u * e, c - t * e + u * e, m);
            tiles.push_back({n, i * cell + cell / 2, (grid - 1 - j) * cell + cell / 2});
        }
    addCamera(*s, "cam", {0, 0, 0}, {0, 0, -1}, 40.0f);
    s->computeBounds();
    Renderer r;
    r.setScene(s);
    r.resize(grid * cell, grid * cell);
    r.setCamera(selectCamera(*s, "cam"));
    r.render(Settings{});
    FloatImage nimg = r.readLayer("Normal 1");
    float worst = 0.0f;
    for (const auto& t : tiles) {
        glm::vec3 got(nimg.at(t.px, t.py, 0), nimg.at(t.px, t.py, 1), nimg.at(t.px, t.py, 2));
        float err = glm::degrees(std::acos(std::min(1.0f, glm::dot(got, t.n))));
        if (err > 1.2f) std::printf("tile at %d,%d: expected %g %g %g got %g %g %g\n", t.px, t.py, t.n.x, t.n.y, t.n.z, got.x, got.y, got.z);
        worst = std::max(worst, err);
    }
    EXPECT_LT(worst, 1.2f);
    EXPECT_GT(worst, 0.0f);  // 8 bits per component do quantise
}

// With a still camera, Reprojected Radiance is last frame's Output Radiance.
TEST_F(GLTest, ReprojectionWithStillCameraReturnsLastOutput) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 96, 72, "front");
    Renderer& r = *renderer;
    Settings s;
    s.lengthUnit = 1.0f;  // the lengths below are in scene units
    s.radius = 1.5f;
    s.radiosityResolution = RadiosityResolution::Full;  // compared with Depth 1 pixel by pixel
    for (int i = 0; i < 4; ++i) r.render(s);
    FloatImage last = r.readLayer("Output Radiance");
    r.render(s);
    FloatImage reproj = r.readLayer("Reprojected Radiance");
    FloatImage depth = r.readLayer("Depth 1");
    int checked = 0, bad = 0;
    for (int y = 0; y < last.height; ++y)
        for (int x = 0; x < last.width; ++x) {
            if (depth.at(x, y, 0) >= selectCamera(*scene, "front").zfar * 0.99f) continue;
            for (int c = 0; c < 3; ++c) {
                float a = last.at(x, y, c), b = reproj.at(x, y, c);
                ++checked;
                // One R11F_G11F_B10F step: 6-bit mantissa for R and G, 5-bit for B.
                const float step = std::max(std::abs(a), std::abs(b)) * (c == 2 ? 1.0f / 32.0f : 1.0f / 64.0f);
                if (std::abs(a - b) > step + 2e-6f) {  // + one step of the denormal range (2^-20, 2^-19)
                    if (bad < 5) std::printf("reprojection mismatch at %d,%d c%d: last %g reprojected %g\n", x, y, c, a, b);
                    ++bad;
                }
            }
        }
    EXPECT_GT(checked, 1000);
    EXPECT_EQ(bad, 0);
    // After a camera cut nothing is reprojected (defined zeros, not garbage).
    r.resetHistory();
    r.render(s);
    FloatImage cut = r.readLayer("Reprojected Radiance");
    EXPECT_EQ(meanChannel(cut, 0) + meanChannel(cut, 1) + meanChannel(cut, 2), 0.0);
}

// The gather on a floor under a uniformly lit ceiling (radiance B, height H = 1, gather radius r = 2). The
// independent answer: for a grid of floor pixels X, the irradiance from the ceiling points within the radius that
// the camera sees, E(X) = B * integral of cosX * cosY / d^2 dA (= B H^2 / d^4 dA), integrated numerically on a
// fine grid, over the part the camera sees within the gather's screen-space disk; and the covered share of the
// cosine-weighted hemisphere, the same integral / pi without B. The consistent gather (the screen part alone: no
// probes) must match both on average within 5 % (the taps' own noise averages out over the region), converge as
// taps grow, and be exactly linear in B.
TEST_F(GLTest, GatherUnderUniformlyLitCeilingMatchesAnalyticIrradiance) {
    auto s = std::make_shared<Scene>();
    const glm::vec3 B(0.6f, 0.3f, 0.1f);
    int floorM = addMaterial(*s, glm::vec3(0.0f));
    int ceilM = addMaterial(*s, glm::vec3(0.0f), B, false);
    addFloor(*s, 50.0f, 0.0f, floorM);
    addQuad(*s, {-50, 1, -50}, {50, 1, -50}, {50, 1, 50}, {-50, 1, 50}, ceilM);  // facing down
    addCamera(*s, "cam", {0, 0.5f, 0}, {0, 0.5f, -1}, 90.0f);
    s->computeBounds();
    s->lights.clear();
    const int W = 128, Hpx = 128;
    auto renderer = rendererFor(s, W, Hpx, "cam");
    Renderer& r = *renderer;
    double previousError = 1e9;
    for (int taps : {8, 30, 99}) {
        Settings st;
        st.radiosityResolution = RadiosityResolution::Full;  // pixel-exact analytic comparison
        st.numSamples = taps;
        st.sunIntensity = 0.0f;
        st.lengthUnit = 1.0f;  // the lengths below are in scene units
        st.radius = 2.0f;
        st.minMip = 0;
        st.blur = false;
        st.temporal = false;
        st.damping = 1.0f;
        st.varyTaps = false;
        st.probesEnabled = false;  // the screen-space estimator alone
        r.render(st);
        FloatImage E = r.readLayer("Output Radiance");
        FloatImage C = r.readLayer("Gather Coverage");
        const glm::mat4 viewProj = r.camera().projection(float(W) / Hpx) * r.camera().view();
        const glm::mat4 invViewProj = glm::inverse(viewProj);
        const glm::vec3 eye = r.camera().position();
        const double rr = st.radius, H = 1.0, step = 0.01;
        double sum[3] = {0, 0, 0}, cover = 0.0, expectE = 0.0, expectCover = 0.0;
        int n = 0, m = 0;
        for (int y = 80; y < 120; ++y)
            for (int x = 40; x < 88; ++x, ++n) {
                for (int c = 0; c < 3; ++c) sum[c] += E.at(x, y, c);
                cover += C.at(x, y, 0);
                if (x % 4 || y % 4) continue;
                // The floor point the pixel centre sees (image row 0 is the top).
                glm::vec4 ndc(2.0f * (x + 0.5f) / W - 1.0f, 1.0f - 2.0f * (y + 0.5f) / Hpx, 0.0f, 1.0f);
                glm::vec4 w = invViewProj * ndc;
                glm::vec3 dir = glm::normalize(glm::vec3(w) / w.w - eye);
                glm::vec3 X = eye + dir * (-eye.y / dir.y);
                const float zX = glm::dot(X - eye, r.camera().forward());
                const float rss = float(Hpx) / (2.0f * std::tan(0.5f * r.camera().yfov)) * float(rr) / zX;
                double e = 0.0;
                for (double dx = -rr; dx <= rr; dx += step)
                    for (double dz = -rr; dz <= rr; dz += step) {
                        const double d2 = dx * dx + dz * dz + H * H;
                        if (d2 >= rr * rr) continue;
                        glm::vec4 p = viewProj * glm::vec4(X.x + float(dx), 1.0f, X.z + float(dz), 1.0f);
                        if (p.w <= 0.0f || std::abs(p.x) > p.w || std::abs(p.y) > p.w) continue;  // not on screen
                        // ... and within the gather's screen-space disk (radius projScale * r / z_X pixels).
                        const glm::vec2 py((p.x / p.w * 0.5f + 0.5f) * W, (0.5f - p.y / p.w * 0.5f) * Hpx);
                        if (glm::length(py - glm::vec2(x + 0.5f, y + 0.5f)) > rss) continue;
                        e += H * H / (d2 * d2) * step * step;
                    }
                expectE += e;
                expectCover += e / M_PI;
                ++m;
            }
        for (int c = 0; c < 3; ++c) sum[c] /= n;
        cover /= n;
        expectE /= m;
        expectCover /= m;
        // 5 % from 30 taps on; 8 taps may be 8 % off (the coverage of a pixel is clamped to 1 when stored).
        const double tol = taps < 30 ? 0.08 : 0.05;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / (expectE * B[c]), 1.0, tol) << taps << " taps, channel " << c;
        EXPECT_NEAR(cover / expectCover, 1.0, taps < 30 ? 0.25 : 0.05) << taps << " taps";
        // Converges: more taps never move the average away from the answer.
        const double error = std::abs(sum[0] / (expectE * B[0]) - 1.0);
        EXPECT_LE(error, previousError + 0.005) << taps << " taps";
        previousError = error;
        // Colour ratios are preserved exactly up to R11G11B10 rounding (the estimator is linear in B).
        EXPECT_NEAR(sum[1] / sum[0], B[1] / B[0], 0.03);
        EXPECT_NEAR(sum[2] / sum[0], B[2] / B[0], 0.03);
        std::printf("gather under ceiling, %d taps: E/B = %.3f, on-screen analytic %.3f; coverage %.3f, analytic %.3f\n",
                    taps, sum[0] / B[0], expectE, cover, expectCover);
    }
}

// executePass runs only a pass of this frame: one that is off (AO by default) is refused with a message that says so,
// not with a texture error from inside the pass; a name that is no pass is refused too.
TEST_F(GLTest, ExecutePassRefusesAPassThatIsOff) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 32, 24, "front");
    Settings s;
    renderer->render(s);
    try {
        renderer->executePass("Ambient occlusion", s);
        FAIL() << "an AO pass ran with ao.enabled=false";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("does not run with these settings"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("Radiosity gather"), std::string::npos) << e.what();
    }
    EXPECT_THROW(renderer->executePass("No such pass", s), std::runtime_error);
    s.aoEnabled = true;
    EXPECT_NO_THROW(renderer->executePass("Ambient occlusion", s));
}

// The bilateral blur preserves a constant field.
TEST_F(GLTest, BilateralBlurPreservesConstant) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 96, 72, "front");
    Renderer& r = *renderer;
    Settings s;
    r.render(s);
    const glm::vec3 k(0.25f, 0.5f, 1.0f);
    fillTexture(r.textures().id("Output Radiance"), k);
    r.executePass("Bilateral blur", s);
    FloatImage out = r.readLayer("Output Radiance");
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(out.at(x, y, c), k[c], 1e-6f) << x << "," << y;
}

// The blur keeps a linear gradient where an edge or the screen border cuts its kernel: it reads the value off a
// weighted line fit along each axis, so a one-sided kernel keeps the centre's value (the weighted mean moved a
// corner's value towards the interior's by about 2.5 pixels of the slope: 0.094 here, over the tolerance; the
// concave corners of one bounce 10-100 % too bright).
TEST_F(GLTest, BilateralBlurKeepsALinearGradientAtEdges) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 96, 72, "front");
    Renderer& r = *renderer;
    Settings s;
    s.radiosityResolution = RadiosityResolution::Full;
    r.render(s);
    const GLuint tex = r.textures().id("Output Radiance");
    const FloatImage before = r.readLayer("Output Radiance");
    const int w = before.width, h = before.height;
    std::vector<float> ramp(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) ramp[(size_t(y) * w + x) * 3 + c] = 1.0f + 4.0f * float(x + y) / float(w);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, ramp.data());
    const FloatImage in = r.readLayer("Output Radiance");  // the ramp as R11G11B10 holds it
    r.executePass("Bilateral blur", s);
    const FloatImage out = r.readLayer("Output Radiance");
    int edged = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = in.at(x, y, 0);
            // One step of R11G11B10's 6-bit mantissa at the value: the input's rounding and the output's.
            ASSERT_NEAR(out.at(x, y, 0), v, v / 64.0f) << x << "," << y;
            const bool cut = x < 5 || y < 5 || x >= w - 5 || y >= h - 5;
            edged += cut ? 1 : 0;
        }
    EXPECT_GT(edged, 1000);  // the border's band, where the old one-sided kernel was biased
}

namespace {
// Renders two still frames of the Cornell box, fills this frame's irradiance with cur and the reprojected history
// with prev, runs the temporal blend alone and checks every surface pixel against historyWeight * prev + (1 -
// historyWeight) * cur, within `tolerance` of the value (R11G11B10 rounding).
void expectTemporalBlend(Renderer& r, const Settings& s, float historyWeight, float tolerance) {
    r.render(s);
    r.render(s);
    const glm::vec3 cur(1.0f, 2.0f, 4.0f), prev(3.0f, 0.5f, 8.0f);
    fillTexture(r.textures().id("Output Radiance"), cur);
    fillTexture(r.textures().id("Reprojected Radiance"), prev);
    r.executePass("Temporal blend", s);
    const FloatImage out = r.readLayer("Output Radiance"), depth = r.readLayer("Depth 1");
    const glm::vec3 expect = historyWeight * prev + (1.0f - historyWeight) * cur;
    int checked = 0;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            if (depth.at(x, y, 0) >= r.camera().zfar * 0.99f) continue;
            ++checked;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(out.at(x, y, c), expect[c], tolerance * expect[c]) << x << "," << y;
        }
    EXPECT_GT(checked, 1000);
}
}  // namespace

// The temporal blend follows E = a*w*E_reprojected + (1 - a*w)*E_current, w = 1 for a still camera.
TEST_F(GLTest, TemporalBlendFollowsFormula) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 96, 72, "front");
    Renderer& r = *renderer;
    Settings s;
    s.hysteresis = 0.75f;
    s.radiosityResolution = RadiosityResolution::Full;  // compared with Depth 1 pixel by pixel
    s.interleave = RadiosityInterleave::Off;  // the plain blend (the interleaved one: the test below)
    expectTemporalBlend(r, s, 0.75f, 0.02f);
    // Without history the current value passes through (the reprojection pass rejects every pixel's history).
    const glm::vec3 cur(1.0f, 2.0f, 4.0f);
    r.resetHistory();
    r.executePass("Reproject radiance", s);
    fillTexture(r.textures().id("Output Radiance"), cur);
    r.executePass("Temporal blend", s);
    FloatImage fresh = r.readLayer("Output Radiance");
    EXPECT_NEAR(fresh.at(48, 36, 1), cur[1], 0.02f);
}

// With the interleaved gather about 1 in N of the blurred values is new each frame, so the blend weighs the history
// 1 - N (1 - alpha): 0.5 at N = 2 and alpha = 0.75, which keeps alpha's response (test_interleaved_gather.cpp).
// Within one R11G11B10 step of blue (0.125 at 6: 2.1 %; the uncompensated weight 0.75 would give 7).
TEST_F(GLTest, InterleavedTemporalBlendWeighsTheHistoryOneMinusNTimesOneMinusAlpha) {
    auto scene = cornellScene();
    auto renderer = rendererFor(scene, 96, 72, "front");
    Settings s;
    s.hysteresis = 0.75f;
    s.radiosityResolution = RadiosityResolution::Full;
    s.interleave = RadiosityInterleave::Two;
    expectTemporalBlend(*renderer, s, 0.5f, 0.03f);
}

// The memory report of the seed layout: 176 bits per pixel of G-buffer, 128 of radiosity (at full resolution; a
// half-resolution grid holds a quarter of them per screen pixel).
TEST_F(GLTest, BufferReportGivesSeedLayout) {
    auto scene = cornellScene();
    Renderer r;
    r.setScene(scene);
    r.resize(320, 180);
    Settings half;
    half.radiosityResolution = RadiosityResolution::Half;
    r.prepare(half);
    EXPECT_EQ(r.textures().memoryReport().radiosityBitsPerPixel, 2 * 32 + 2 * 8);  // input radiance stays full
    Settings seed;
    seed.radiosityResolution = RadiosityResolution::Full;
    r.prepare(seed);
    MemoryReport m = r.textures().memoryReport();
    EXPECT_EQ(m.gbufferBitsPerPixel, 176);
    EXPECT_EQ(m.radiosityBitsPerPixel, 128);
    EXPECT_EQ(m.gbufferBytes, uint64_t(320) * 180 * 176 / 8);
    EXPECT_EQ(m.radiosityBytes, uint64_t(320) * 180 * 128 / 8);
    // Extras are listed on their own lines: mips, shadow map, final images.
    bool mips = false, shadow = false;
    for (const auto& l : m.lines) {
        if (l.name.find("mips") != std::string::npos) { mips = true; EXPECT_EQ(l.group, "extra"); }
        if (l.name == "Shadow Map 1") { shadow = true; EXPECT_EQ(l.group, "extra"); }
    }
    EXPECT_TRUE(mips);
    EXPECT_TRUE(shadow);
    // temporal_first adds exactly one 32-bit history buffer, counted as extra.
    Settings tf;
    tf.filterOrder = FilterOrder::TemporalFirst;
    tf.radiosityResolution = RadiosityResolution::Full;
    r.prepare(tf);
    MemoryReport m2 = r.textures().memoryReport();
    EXPECT_EQ(m2.radiosityBitsPerPixel, 128);
    EXPECT_EQ(m2.extraBitsPerPixel, m.extraBitsPerPixel + 32);
}

TEST(SpiralTurns, MatchesPaperTable) {
    EXPECT_EQ(spiralTurns(13), 5);
    EXPECT_EQ(spiralTurns(14), 3);
    EXPECT_EQ(spiralTurns(19), 7);
    EXPECT_EQ(spiralTurns(30), 11);
    EXPECT_EQ(spiralTurns(50), 19);
}

// Tap i of N lies at angle 2 pi * turns * (i + 0.5) / N. For every N (the table's 1..99 and the fallback beyond):
// turns coprime with N, so all N tap directions differ; and consecutive taps at least 1/6 of a turn apart in angle
// (the table's worst case, N = 6), so the spiral never degenerates into taps lined up along a few rays.
TEST(SpiralTurns, EveryTapCountGetsDistinctWellSpreadDirections) {
    for (int n = 2; n < 4000; ++n) {
        const int t = spiralTurns(n);
        EXPECT_EQ(std::gcd(t, n), 1) << "N = " << n << ", turns " << t;
        const double step = std::fmod(double(t) / n, 1.0);
        EXPECT_GE(std::min(step, 1.0 - step), 1.0 / 6.0 - 1e-9) << "N = " << n << ", turns " << t;
    }
}
