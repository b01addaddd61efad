// The world-space irradiance probes (renderer/probes/probe_volume.h) against exact answers and the path tracer.
// One file over 500 lines: the tests share its scenes and helpers and all prove one class.
#include "gl_fixture.h"
#include "probe_glsl_harness.h"

#include "renderer/probes/probe_volume.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/gltf_loader.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <thread>

using namespace deepgi;
using deepgi::test::evaluateAtPoints;
using deepgi::test::probeAtlasTextures;
using deepgi::test::readShaderSource;
using namespace deepgi::procedural;

namespace {

constexpr float kPi = 3.14159265358979323846f;

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Updates until every active probe has been updated `perProbe` times; returns the mean ms per update.
double converge(ProbeVolume& v, const Settings& s, int perProbe, ProbeUpdateStats* last = nullptr) {
    double ms = 0.0;
    int n = 0;
    for (;;) {
        bool done = true;
        for (int i = 0; i < v.probeCount(); ++i)
            if (v.state(i) == ProbeState::Active && v.updatesOf(i) < perProbe) done = false;
        if (done) break;
        const ProbeUpdateStats st = v.update(s);
        if (last) *last = st;
        ms += st.milliseconds;
        ++n;
    }
    return n ? ms / n : 0.0;
}

// A closed box (walls face inward) of side `size` at the origin corner; every surface albedo a, emission e.
Scene furnace(float a, float e, float size) {
    Scene s;
    const int m = addMaterial(s, glm::vec3(a), glm::vec3(e));
    addBox(s, glm::vec3(0.0f), glm::vec3(size), m, true);
    s.computeBounds();
    return s;
}

// Points on each of the six inner walls of the box [0,size]^3 (inset `inset` x size from its edges), with the
// inward normal.
std::vector<std::pair<glm::vec3, glm::vec3>> wallPoints(float size, float inset) {
    std::vector<std::pair<glm::vec3, glm::vec3>> pts;
    const float ts[3] = {inset, 0.5f, 1.0f - inset};
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side)
            for (float u : ts)
                for (float v : ts) {
                    glm::vec3 p, n(0.0f);
                    p[axis] = side ? size : 0.0f;
                    p[(axis + 1) % 3] = u * size;
                    p[(axis + 2) % 3] = v * size;
                    n[axis] = side ? -1.0f : 1.0f;
                    pts.push_back({p, n});
                }
    return pts;
}

Settings noLights() {
    Settings s;
    s.lightScale = 0.0f;  // the scene has no lights: without this the default sun would be added
    return s;
}

}  // namespace

// (a) Closed furnace: radiance is e/(1-a) everywhere, so the irradiance on every wall is pi*e/(1-a). The probes get
// there only through their own multi-bounce feedback. Checked at scale 1 and, with the same relative settings,
// at scales 0.001 and 1000 (every length is relative to the scene).
TEST(ProbeVolume, ClosedFurnaceReachesTheExactIrradiance) {
    const float a = 0.5f, e = 0.1f, exact = kPi * e / (1.0f - a);
    for (float size : {1.0f, 0.001f, 1000.0f}) {
        const Scene scene = furnace(a, e, size);
        Settings s = noLights();
        s.probeRelativeSpacing = 0.25f;  // 4 x 4 x 4 probes
        s.probeRaysPerFrame = 64 * 128;  // all of them every update
        ProbeVolume v(scene, s);
        ASSERT_EQ(v.grid().count(), 64);
        EXPECT_EQ(v.activeProbeCount(), 64) << "no probe of an empty room is inside geometry";
        const double ms = converge(v, s, 60);  // the k/(k+4) ramp leaves ~0.15% of the bounce lag at 60
        float worst = 0.0f;
        for (const auto& [p, n] : wallPoints(size, 0.02f)) {
            const glm::vec3 E = v.irradiance(p, n);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(E[c], exact, 0.03f * exact) << "size " << size << " at " << p.x << "," << p.y << "," << p.z;
                worst = std::max(worst, std::abs(E[c] - exact) / exact);
            }
        }
        std::printf("furnace size %g: worst wall error %.3f%% after 60 updates per probe (%.2f ms per update of "
                    "%d probes x 128 rays)\n",
                    size, 100.0f * worst, ms, v.activeProbeCount());
    }
}

// The default settings in the furnace too (8 x 8 x 8 probes, 16384 rays a frame).
TEST(ProbeVolume, ClosedFurnaceWithDefaultSettings) {
    const float a = 0.5f, e = 0.1f, exact = kPi * e / (1.0f - a);
    const Scene scene = furnace(a, e, 2.0f);
    const Settings s = noLights();
    ProbeVolume v(scene, s);
    EXPECT_EQ(v.grid().counts, glm::ivec3(8));
    ProbeUpdateStats last;
    const double ms = converge(v, s, 60, &last);
    float worst = 0.0f;
    for (const auto& [p, n] : wallPoints(2.0f, 0.01f)) {
        const float E = v.irradiance(p, n).x;
        EXPECT_NEAR(E, exact, 0.03f * exact) << "at " << p.x << "," << p.y << "," << p.z;
        worst = std::max(worst, std::abs(E - exact) / exact);
    }
    std::printf("furnace, default settings: worst wall error %.3f%%; %.2f ms per update of %d probes (%llu rays)\n",
                100.0f * worst, ms, last.probesUpdated, (unsigned long long)last.probeRays);
}

namespace {

// A sunlit floor (4 x 4, albedo 0.5) with a wall along its -X edge (4 wide, 2 high, albedo 0.6): the wall is lit by
// the sun and by the floor, the floor by the sun and by the wall. Open everywhere else.
Scene floorAndWall() {
    Scene s;
    const int floorMat = addMaterial(s, glm::vec3(0.5f));
    const int wallMat = addMaterial(s, glm::vec3(0.6f));
    addQuad(s, {0, 0, 2}, {4, 0, 2}, {4, 0, -2}, {0, 0, -2}, floorMat);  // faces +Y
    addQuad(s, {0, 0, -2}, {0, 2, -2}, {0, 2, 2}, {0, 0, 2}, wallMat);  // faces +X
    addSun(s, glm::vec3(-1.0f, -1.2f, -0.3f), 3.0f);
    s.computeBounds();
    return s;
}

// The path tracer's indirect irradiance at p (normal n, albedo rho): pi / rho x the indirect radiance it sees on a
// 2 cm patch around p through an orthographic camera along -n.
float tracedIndirectIrradiance(const ReferenceTracer& tracer, const glm::vec3& p, const glm::vec3& n, float rho) {
    Camera cam;
    const glm::vec3 up = std::abs(n.y) > 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    cam.cameraToWorld = glm::inverse(glm::lookAt(p + n * 0.5f, p, up));
    cam.perspective = false;
    cam.orthoHalfHeight = 0.01f;
    cam.znear = 0.01f;
    cam.zfar = 2.0f;
    ReferenceOptions o;
    o.width = o.height = 4;
    o.spp = 2048;
    o.maxBounces = 32;
    o.progress = false;
    Settings s;
    const ReferenceResult r = tracer.render(cam, s, o);
    double sum = 0.0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) sum += r.indirect.at(x, y, 0);
    return float(sum / 16.0) * kPi / rho;
}

}  // namespace

// (b) An open scene under a sun: the probes' irradiance on the floor and the wall against the path tracer's
// indirect irradiance there. Tolerance 15% of the value + 2% of the wall's peak: the probes interpolate a field
// that varies over about a probe spacing (0.5 here) near the wall's foot, and store 8 x 8 directions.
TEST(ProbeVolume, OpenSceneMatchesThePathTracersIndirectLight) {
    const Scene scene = floorAndWall();
    Settings s;
    ProbeVolume v(scene, s);
    const double ms = converge(v, s, 60);
    const ReferenceTracer tracer(scene);
    struct Point { glm::vec3 p, n; float rho; };
    const Point points[] = {
        {{0.0f, 0.5f, 0.0f}, {1, 0, 0}, 0.6f}, {{0.0f, 1.0f, 1.0f}, {1, 0, 0}, 0.6f},
        {{0.0f, 1.6f, -0.5f}, {1, 0, 0}, 0.6f}, {{0.4f, 0.0f, 0.0f}, {0, 1, 0}, 0.5f},
        {{1.0f, 0.0f, 1.0f}, {0, 1, 0}, 0.5f},  {{2.5f, 0.0f, -0.5f}, {0, 1, 0}, 0.5f},
    };
    float peak = 0.0f;
    std::vector<float> truth;
    for (const Point& q : points) {
        truth.push_back(tracedIndirectIrradiance(tracer, q.p, q.n, q.rho));
        peak = std::max(peak, truth.back());
    }
    for (size_t i = 0; i < std::size(points); ++i) {
        const float probe = v.irradiance(points[i].p, points[i].n).x;
        std::printf("open scene point (%.1f %.1f %.1f): probes %.4f, path tracer %.4f (%+.1f%%)\n", points[i].p.x,
                    points[i].p.y, points[i].p.z, probe, truth[i], 100.0f * (probe - truth[i]) / truth[i]);
        EXPECT_NEAR(probe, truth[i], 0.15f * truth[i] + 0.02f * peak) << "point " << i;
    }
    std::printf("open scene: %d probes active of %d, %.2f ms per update\n", v.activeProbeCount(), v.probeCount(), ms);
}

// A closed room lit by a point light and a spot light (inverse square, glTF range window, cone): the probes use
// the path tracer's lights and shadow rays. Same tolerance as the open scene.
TEST(ProbeVolume, PointAndSpotLitRoomMatchesThePathTracer) {
    Scene scene;
    const int m = addMaterial(scene, glm::vec3(0.6f, 0.5f, 0.4f));
    addBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 4.0f), m, true);
    addBox(scene, {2.5f, 0.0f, 2.5f}, {3.3f, 1.2f, 3.3f}, m, false);  // a block that casts shadows
    Light point;
    point.type = LightType::Point;
    point.position = {1.2f, 2.2f, 1.5f};
    point.intensity = 6.0f;
    point.range = 8.0f;
    scene.lights.push_back(point);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {3.5f, 2.8f, 0.5f};
    spot.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.4f));
    spot.intensity = 12.0f;
    spot.innerConeAngle = 0.3f;
    spot.outerConeAngle = 0.6f;
    scene.lights.push_back(spot);
    scene.computeBounds();
    const Settings s;
    ProbeVolume v(scene, s);
    converge(v, s, 60);
    const ReferenceTracer tracer(scene);
    struct Point { glm::vec3 p, n; };
    const Point points[] = {
        {{2.0f, 3.0f, 2.0f}, {0, -1, 0}}, {{0.0f, 1.5f, 2.0f}, {1, 0, 0}}, {{2.0f, 0.0f, 1.0f}, {0, 1, 0}},
        {{4.0f, 1.0f, 3.0f}, {-1, 0, 0}}, {{1.0f, 0.0f, 3.5f}, {0, 1, 0}}, {{3.0f, 1.2f, 2.9f}, {0, 1, 0}},
    };
    std::vector<float> truth;
    float peak = 0.0f;
    for (const Point& q : points) {
        truth.push_back(tracedIndirectIrradiance(tracer, q.p, q.n, 0.6f));  // red channel: albedo 0.6
        peak = std::max(peak, truth.back());
    }
    for (size_t i = 0; i < std::size(points); ++i) {
        const float probe = v.irradiance(points[i].p, points[i].n).x;
        std::printf("lit room point (%.1f %.1f %.1f): probes %.4f, path tracer %.4f (%+.1f%%)\n", points[i].p.x,
                    points[i].p.y, points[i].p.z, probe, truth[i], 100.0f * (probe - truth[i]) / truth[i]);
        EXPECT_NEAR(probe, truth[i], 0.15f * truth[i] + 0.02f * peak) << "point " << i;
    }
}

// Bad queries (NaN position, zero normal) answer 0, never NaN.
TEST(ProbeVolume, BadQueriesAnswerZero) {
    const Scene scene = furnace(0.5f, 0.1f, 1.0f);
    Settings s = noLights();
    s.probeRelativeSpacing = 0.5f;
    ProbeVolume v(scene, s);
    v.update(s);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(v.irradiance({nan, 0.5f, 0.5f}, {0, 1, 0}), glm::vec3(0.0f));
    EXPECT_EQ(v.irradiance({0.5f, 0.5f, 0.5f}, {0, 0, 0}), glm::vec3(0.0f));
    EXPECT_EQ(v.irradiance({0.5f, inf, 0.5f}, {0, 1, 0}), glm::vec3(0.0f));
    const glm::vec3 far = v.irradiance({1e30f, -1e30f, 0.5f}, {0, 1, 0});
    EXPECT_TRUE(std::isfinite(far.x) && std::isfinite(far.y) && std::isfinite(far.z));
}

// (c) Probes inside a solid box are moved out when they are close to its surface, disabled when they are not;
// no active probe is left inside.
TEST(ProbeVolume, ProbesInsideGeometryAreMovedOrDisabled) {
    Scene scene;
    const int m = addMaterial(scene, glm::vec3(0.5f));
    addBox(scene, glm::vec3(0.0f), glm::vec3(4.0f), m, true);             // the room
    const glm::vec3 lo(1.2f), hi(2.8f);
    addBox(scene, lo, hi, m, false);                                      // a solid block in it
    scene.computeBounds();
    Settings s;
    s.probeRelativeSpacing = 0.125f;  // spacing 0.5: probes at 0.25, 0.75, ...; 4^3 of them start in the block
    ProbeVolume v(scene, s);
    int moved = 0, disabled = 0;
    for (int i = 0; i < v.probeCount(); ++i) {
        const glm::vec3 home = v.grid().gridPosition(v.grid().coord(i)), p = v.probePosition(i);
        const bool startedInside = glm::all(glm::greaterThan(home, lo)) && glm::all(glm::lessThan(home, hi));
        const bool isInside = glm::all(glm::greaterThan(p, lo)) && glm::all(glm::lessThan(p, hi));
        if (v.state(i) == ProbeState::Active) {
            EXPECT_FALSE(isInside) << "active probe " << i << " inside the block";
            if (startedInside) ++moved;
        } else if (startedInside) {
            ++disabled;
        } else {
            ADD_FAILURE() << "probe " << i << " outside the block was disabled";
        }
        EXPECT_LE(glm::length(v.probeOffset(i)), 0.45f * 0.5f * std::sqrt(3.0f) + 1e-4f);
    }
    // A probe 0.05 inside a face (a coordinate at 1.25 or 2.75) can leave (0.05 + 0.05 <= 0.225); the 8 with every
    // coordinate at 1.75 or 2.25 are at least 0.55 deep and cannot.
    EXPECT_EQ(moved, 56);
    EXPECT_EQ(disabled, 8);
    std::printf("solid block: %d probes moved out, %d disabled; placement %.1f ms, %llu rays\n", moved, disabled,
                v.placementMilliseconds(), (unsigned long long)v.placementRays());
}

namespace {

// A sunlit room open at the top (x in [-2, 0]) and a closed dark room (x in [0.05, 2.05]), a 5 cm wall between.
Scene thinWall() {
    Scene s;
    const int m = addMaterial(s, glm::vec3(0.7f));
    const float y1 = 2.0f, z0 = -1.0f, z1 = 1.0f;
    // Lit room: floor, four walls (facing inward), no ceiling.
    addQuad(s, {-2, 0, z1}, {0, 0, z1}, {0, 0, z0}, {-2, 0, z0}, m);
    addQuad(s, {-2, 0, z1}, {-2, 0, z0}, {-2, y1, z0}, {-2, y1, z1}, m);  // x = -2, faces +X
    addQuad(s, {0, 0, z0}, {0, 0, z1}, {0, y1, z1}, {0, y1, z0}, m);      // x = 0, faces -X
    addQuad(s, {-2, 0, z0}, {0, 0, z0}, {0, y1, z0}, {-2, y1, z0}, m);    // z = -1, faces +Z
    addQuad(s, {0, 0, z1}, {-2, 0, z1}, {-2, y1, z1}, {0, y1, z1}, m);    // z = +1, faces -Z
    addBox(s, {0.05f, 0.0f, z0}, {2.05f, y1, z1}, m, true);              // the dark room, closed
    addSun(s, glm::vec3(0.5f, -1.0f, 0.2f), 3.0f);
    s.computeBounds();
    return s;
}

}  // namespace

// (d) The dark room's truth is exactly 0; the Chebyshev test must keep the lit probes next door out of it.
TEST(ProbeVolume, ThinWallDoesNotLeakIntoTheDarkRoom) {
    const Scene scene = thinWall();
    const Settings s;
    ProbeVolume v(scene, s);
    converge(v, s, 80);
    // The lit room's indirect level: its floor and walls.
    double litSum = 0.0;
    int litN = 0;
    for (float x : {-1.8f, -1.0f, -0.2f})
        for (float z : {-0.8f, 0.0f, 0.8f}) {
            litSum += luminance(v.irradiance({x, 0.0f, z}, {0, 1, 0}));
            litSum += luminance(v.irradiance({0.0f, 0.3f + 0.7f * (x + 2.0f), z}, {-1, 0, 0}));
            litN += 2;
        }
    const double lit = litSum / litN;
    ASSERT_GT(lit, 0.1);
    // The dark room, with the thin wall's dark side and the surfaces next to it.
    double darkSum = 0.0, darkMax = 0.0;
    int darkN = 0;
    auto dark = [&](const glm::vec3& p, const glm::vec3& n) {
        const double l = luminance(v.irradiance(p, n));
        darkSum += l;
        darkMax = std::max(darkMax, l);
        ++darkN;
    };
    for (float t : {0.1f, 0.5f, 1.0f, 1.5f, 1.9f})
        for (float z : {-0.9f, 0.0f, 0.9f}) {
            dark({0.05f, t, z}, {1, 0, 0});                // the thin wall's dark side
            dark({0.05f + t, 0.0f, z}, {0, 1, 0});         // floor
            dark({0.05f + t, 2.0f, z}, {0, -1, 0});        // ceiling
            dark({0.05f + t, t, -1.0f}, {0, 0, 1});        // side wall
        }
    const double leakMean = darkSum / darkN / lit, leakMax = darkMax / lit;
    std::printf("thin wall: lit room indirect %.4f; dark room leak mean %.4f%%, max %.4f%% of it\n", lit,
                100.0 * leakMean, 100.0 * leakMax);
    EXPECT_LE(leakMean, 0.005) << "the issue's target for the whole pipeline: 0.5 %";
    EXPECT_LE(leakMax, 0.02);
}

// The bench's thin wall (assets/hard/thin_wall, a 5 cm wall between a sunlit and a closed room; tools/gen_scenes.py):
// where the dark room's ceiling and floor meet the wall, the probes of the lit side pass the Chebyshev test (the
// receiver is only 5 cm past what they see) and leaked 20 % of the lit floor's irradiance. Seen from the dark room's
// camera, with the view bias (probes.view_bias) the receiver moves towards the camera: below 0.5 % of the lit level
// (the target), against more than 5 % without it (the check can fail).
TEST(ProbeVolume, ViewBiasKeepsTheLitSidesProbesOutOfTheThinWallsCorners) {
    const Scene scene = loadGltf(std::string(DEEPGI_ASSET_DIR) + "/hard/thin_wall/thin_wall.gltf");
    Settings s;
    ProbeVolume v(scene, s, 1, 2);
    converge(v, s, 80);
    const glm::vec3 camera(-3.6f, 1.5f, 2.1f);  // the bench's "dark" camera
    double lit = 0.0;
    for (float z : {-1.0f, 0.0f, 1.0f}) lit += luminance(v.irradiance({2.0f, 0.0f, z}, {0, 1, 0})) / 3.0;
    ASSERT_GT(lit, 0.05);
    double withBias = 0.0, without = 0.0;
    for (float z = -2.4f; z <= 2.4f; z += 0.1f)
        for (const auto& [y, n] : {std::pair{3.0f, glm::vec3(0, -1, 0)}, std::pair{0.0f, glm::vec3(0, 1, 0)}}) {
            const glm::vec3 x(-0.05f, y, z);
            withBias = std::max(withBias, double(luminance(v.irradiance(x, n, nullptr, glm::normalize(camera - x)))));
            without = std::max(without, double(luminance(v.irradiance(x, n))));
        }
    std::printf("thin wall corners: leak max %.3f%% of the lit floor with the view bias, %.3f%% without\n",
                100.0 * withBias / lit, 100.0 * without / lit);
    EXPECT_LT(withBias / lit, 0.005);
    EXPECT_GT(without / lit, 0.05);
    // The bias is a lookup's parameter: a new value keeps the volume and applies at once (0 = no bias at all).
    Settings noBias = s;
    noBias.probeViewBias = 0.0f;
    EXPECT_FALSE(ProbeVolume::layoutChanged(s, noBias));
    v.setViewBias(noBias);
    const glm::vec3 corner(-0.05f, 0.0f, 2.0f);
    EXPECT_EQ(v.irradiance(corner, {0, 1, 0}, nullptr, glm::normalize(camera - corner)), v.irradiance(corner, {0, 1, 0}));
}

// (e) The rays per update are bounded by probes.rays_per_frame, the probes are visited round-robin, and the result
// does not depend on the thread count.
TEST(ProbeVolume, UpdateCostIsBoundedAndDeterministic) {
    const auto scene = deepgi::test::cornellScene();
    Settings s;
    s.probeRaysPerProbe = 128;
    s.probeRaysPerFrame = 1000;  // 7 probes of 128 rays
    ProbeVolume v(*scene, s, 7, 2);
    const int active = v.activeProbeCount();
    ASSERT_GT(active, 100);
    const int updates = (active + 6) / 7;
    for (int u = 0; u < updates; ++u) {
        const ProbeUpdateStats st = v.update(s);
        EXPECT_EQ(st.probesUpdated, std::min(7, active - 7 * u));
        EXPECT_LE(st.probeRays, uint64_t(s.probeRaysPerFrame));
    }
    for (int i = 0; i < v.probeCount(); ++i)
        if (v.state(i) == ProbeState::Active) EXPECT_EQ(v.updatesOf(i), 1) << "probe " << i;
    // Fewer rays per frame than per probe: one probe, with the frame's rays.
    s.probeRaysPerFrame = 50;
    EXPECT_EQ(v.update(s).probeRays, 50u);

    // The same seed on one thread and on two threads: identical atlases.
    Settings d;
    ProbeVolume one(*scene, d, 3, 1), two(*scene, d, 3, 2);
    for (int u = 0; u < 3; ++u) {
        one.update(d);
        two.update(d);
    }
    EXPECT_TRUE(one.irradianceAtlas() == two.irradianceAtlas());
    EXPECT_TRUE(one.depthAtlas() == two.depthAtlas());
    EXPECT_TRUE(one.probeData() == two.probeData());

    // Timings (figures, not assertions): the default budget on the Cornell box.
    ProbeVolume bench(*scene, d);
    double ms = 0.0, cpu = 0.0;
    uint64_t rays = 0, shadow = 0;
    const int frames = 10;
    for (int f = 0; f < frames; ++f) {
        const ProbeUpdateStats st = bench.update(d);
        ms += st.milliseconds;
        cpu += st.cpuMilliseconds;
        rays += st.probeRays;
        shadow += st.shadowRays;
    }
    std::printf("cornell box: %d of %d probes active, placement %.1f ms; default update: %.2f ms wall, %.2f ms CPU, "
                "for %llu probe rays + %llu shadow rays (%.2f Mrays/s wall, %d threads)\n",
                bench.activeProbeCount(), bench.probeCount(), bench.placementMilliseconds(), ms / frames, cpu / frames,
                (unsigned long long)(rays / frames), (unsigned long long)(shadow / frames),
                double(rays + shadow) / (ms * 1e3), int(std::thread::hardware_concurrency()));
}

// After resetHistory() (the lights changed) the volume updates as a new one under the new lights: the same probes
// in the same order with the same rotations, so (one bounce: the old irradiance feeds no bounce) identical atlases.
// A viewer capture re-rendered headless relies on it (tests/test_viewer.cpp).
TEST(ProbeVolume, ResetHistoryUpdatesAsANewVolume) {
    const auto scene = deepgi::test::cornellScene();
    Settings before;
    before.probeRaysPerFrame = 1000;  // 7 probes of 128 rays per update: the round-robin restarts too
    before.damping = 1.0f;
    Settings after = before;
    after.lightScale = 2.5f;
    ProbeVolume changed(*scene, before, 5, 2), fresh(*scene, after, 5, 2);
    for (int u = 0; u < 3; ++u) changed.update(before);
    changed.resetHistory();
    for (int u = 0; u < 3; ++u) {
        changed.update(after);
        fresh.update(after);
    }
    int updated = 0;
    for (int i = 0; i < fresh.probeCount(); ++i) {
        EXPECT_EQ(changed.updatesOf(i), fresh.updatesOf(i)) << "probe " << i;
        updated += fresh.updatesOf(i);
    }
    EXPECT_EQ(updated, 21);
    EXPECT_TRUE(changed.irradianceAtlas() == fresh.irradianceAtlas());
    EXPECT_TRUE(changed.depthAtlas() == fresh.depthAtlas());
    EXPECT_TRUE(changed.probeData() == fresh.probeData());
}

// An update in two halves (startUpdate() with helpers tracing in the background, finishUpdate() joining them) is
// update() to the bit, with multi-bounce (the helpers read the atlases the commit then writes), with a pending
// update finished by resetHistory() and by the next startUpdate(), and with none to finish. A volume destroyed
// while its helpers trace joins them.
TEST(ProbeVolume, UpdateInTwoHalvesIsTheUpdateAtOnce) {
    const auto scene = deepgi::test::cornellScene();
    Settings s;
    s.probeRaysPerFrame = 2000;  // 15 probes of 128 rays per update
    s.damping = 0.0f;            // the probes' own bounce: the traced rays read the committed atlases
    ProbeVolume once(*scene, s, 11, 2), halves(*scene, s, 11, 3);
    for (int u = 0; u < 4; ++u) {
        once.update(s);
        halves.startUpdate(s, 2, true);
        EXPECT_TRUE(halves.updatePending());
        const ProbeUpdateStats st = halves.finishUpdate();
        EXPECT_FALSE(halves.updatePending());
        EXPECT_EQ(st.probesUpdated, 15);
        EXPECT_GT(st.cpuMilliseconds, 0.0) << "the tracing threads' CPU time";
        EXPECT_EQ(halves.lastUpdate().probeRays, st.probeRays);
    }
    EXPECT_EQ(halves.finishUpdate().probesUpdated, 0) << "nothing pending";
    // Finished by the next start, and by a restart of the history: as if each had run at once.
    halves.startUpdate(s, 2, true);
    halves.startUpdate(s, 2, true);
    halves.resetHistory();
    once.update(s);
    once.update(s);
    once.resetHistory();
    for (int u = 0; u < 2; ++u) {
        once.update(s);
        halves.startUpdate(s, u, false);  // no helper: finishUpdate()'s thread traces them all
        halves.finishUpdate();
    }
    EXPECT_EQ(halves.updateCount(), once.updateCount());
    for (int i = 0; i < once.probeCount(); ++i) EXPECT_EQ(halves.updatesOf(i), once.updatesOf(i)) << "probe " << i;
    EXPECT_TRUE(halves.irradianceAtlas() == once.irradianceAtlas());
    EXPECT_TRUE(halves.depthAtlas() == once.depthAtlas());
    EXPECT_TRUE(halves.radianceAtlas() == once.radianceAtlas());
    EXPECT_TRUE(halves.probeData() == once.probeData());

    Settings all = s;
    all.probeRaysPerFrame = 1 << 20;  // every probe: long enough to be cut short
    auto dropped = std::make_unique<ProbeVolume>(*scene, all, 11, 2);
    dropped->startUpdate(all, 1, true);
    dropped.reset();  // joins its helper (a sanitizer build or a hang would say otherwise)
}

// A moved object keeps the probes' history (ProbeVolume::sceneChanged(false)) but starts the settle count again and
// places the probes around it again: a volume settled before the move goes on updating until it agrees with a new
// volume settled on the moved scene. Before this, the settled volume stopped at once and kept the box's light and
// shadow where it had stood (0.83 off), and with the count alone the probes the box now covers stayed disabled and
// its red light next to it was missing (0.27 off).
TEST(ProbeVolume, MovedObjectStartsTheSettleCountAgain) {
    Scene scene;
    const int white = addMaterial(scene, glm::vec3(0.75f)), red = addMaterial(scene, glm::vec3(0.9f, 0.1f, 0.05f));
    addFloor(scene, 2.5f, 0.0f, white);
    addQuad(scene, {-2.5f, 0.0f, -2.5f}, {2.5f, 0.0f, -2.5f}, {2.5f, 2.0f, -2.5f}, {-2.5f, 2.0f, -2.5f}, white);
    addBox(scene, {-0.4f, 0.0f, -0.4f}, {0.4f, 0.8f, 0.4f}, red, false);
    const int box = scene.parts.back().node;
    addSun(scene, glm::vec3(0.3f, -0.8f, -0.5f), 3.0f);
    scene.computeBounds();
    auto place = [&](Scene& s, glm::vec3 at) {
        s.nodes[size_t(box)].local.translation = at;
        s.updateWorldTransforms();
    };
    const glm::vec3 before(-1.2f, 0.0f, 0.0f), after(1.2f, 0.0f, 0.0f);
    Settings s;
    s.probeRaysPerFrame = 1 << 20;  // every probe every update
    s.probeRaysPerProbe = 256;
    s.probeHysteresis = 0.8f;       // 40 updates blend the old state out to 0.8^40 = 1e-4
    s.probeSettleUpdates = 40;
    place(scene, before);
    ProbeVolume moved(scene, s, 5, 2);
    int updates = 0;
    while (!moved.settled(s) && updates < 1000) moved.update(s), ++updates;
    ASSERT_TRUE(moved.settled(s));
    // Floor points along the box's path, facing up.
    std::vector<glm::vec3> pts;
    for (int i = 0; i <= 16; ++i) pts.push_back({-2.0f + 0.25f * float(i), 0.02f, 0.6f});
    std::vector<glm::vec3> stale;
    for (const glm::vec3& p : pts) stale.push_back(moved.irradiance(p, {0, 1, 0}));

    place(scene, after);
    moved.sceneChanged(false);
    EXPECT_FALSE(moved.settled(s)) << "a move starts the count again";
    EXPECT_GT(moved.lastReplacedCount(), 0) << "the probes the box left and now covers are placed again";
    int afterMove = 0;
    while (!moved.settled(s) && afterMove < 1000) moved.update(s), ++afterMove;
    EXPECT_GE(afterMove, s.probeSettleUpdates);
    Scene movedScene = scene;  // a new volume on the scene as it is now
    ProbeVolume fresh(movedScene, s, 9, 2);  // another seed: independent noise
    updates = 0;
    while (!fresh.settled(s) && updates < 1000) fresh.update(s), ++updates;
    double diff = 0.0, moveDiff = 0.0, sum = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
        const glm::vec3 want = fresh.irradiance(pts[i], {0, 1, 0}), got = moved.irradiance(pts[i], {0, 1, 0});
        for (int c = 0; c < 3; ++c) {
            diff += std::abs(double(got[c]) - want[c]);
            moveDiff += std::abs(double(stale[i][c]) - want[c]);
            sum += want[c];
        }
    }
    std::printf("moved box: probes after the move against a new volume %.4f (relative L1), before the move %.4f\n",
                diff / sum, moveDiff / sum);
    // The move matters (the old state is far off), and the kept history converges to the new volume's answer within
    // the probes' noise (two independent volumes of ~9 effective updates of 256 rays).
    EXPECT_GT(moveDiff / sum, 0.15);
    EXPECT_LT(diff / sum, 0.05);
}

using deepgi::test::GLTest;

// The probes' bounce is damped like the screen's (radiosity.bounce_damping): a settled volume whose damping changes
// starts over, and after it the renderer's probe textures are those of a renderer that had that damping from the
// start (a settled one-bounce volume once served the multi-bounce runs after it, 22 % dark in the bench).
TEST_F(GLTest, ProbesStartOverWhenTheBounceDampingChanges) {
    const auto scene = deepgi::test::cornellScene();
    Settings one;
    one.probeRaysPerFrame = 1 << 20;  // every probe every frame
    one.probeSettleUpdates = 8;
    one.damping = 1.0f;
    Settings multi = one;
    multi.damping = 0.0f;
    auto changed = deepgi::test::rendererFor(scene, 32, 24, "front"), fresh = deepgi::test::rendererFor(scene, 32, 24, "front");
    for (int f = 0; f < 10; ++f) changed->render(one);  // settled: one-bounce probes
    const FloatImage oneBounce = changed->readLayer("Probe Irradiance");
    for (int f = 0; f < 10; ++f) {
        changed->render(multi);
        fresh->render(multi);
    }
    const FloatImage a = changed->readLayer("Probe Irradiance"), b = fresh->readLayer("Probe Irradiance");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double sumOne = 0.0, sumMulti = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        ASSERT_EQ(a.pixels[i], b.pixels[i]) << "texel value " << i;
        if (i % 4 == 3) continue;  // rgb only
        sumOne += oneBounce.pixels[i];
        sumMulti += b.pixels[i];
    }
    EXPECT_GT(sumMulti, 1.05 * sumOne) << "multi-bounce probes hold more light than one-bounce ones";
}

// probes.overlap starts the probe rays with the frame, beside the draws of the passes before the probe pass: every
// frame is the one with all of them traced in the probe pass, to the bit, and the probe pass runs after the draws
// that do not need it, before the first pass that reads the probes.
TEST_F(GLTest, ProbeRaysTracedBesideTheDrawsGiveTheSameFrames) {
    const auto scene = deepgi::test::cornellScene();
    Settings on;
    on.probeRaysPerFrame = 4096;
    on.damping = 0.0f;
    Settings off = on;
    off.probeOverlap = false;
    auto a = deepgi::test::rendererFor(scene, 48, 36, "front"), b = deepgi::test::rendererFor(scene, 48, 36, "front");
    for (int f = 0; f < 4; ++f) {
        a->render(on);
        b->render(off);
        const FloatImage ia = a->readFinalRadiance(), ib = b->readFinalRadiance();
        ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
        for (size_t i = 0; i < ia.pixels.size(); ++i) ASSERT_EQ(ia.pixels[i], ib.pixels[i]) << "frame " << f << ", value " << i;
        const FloatImage pa = a->readLayer("Probe Irradiance"), pb = b->readLayer("Probe Irradiance");
        ASSERT_TRUE(pa.pixels == pb.pixels) << "frame " << f;
    }
    EXPECT_FALSE(a->probeVolume()->updatePending());
    std::vector<std::string> order;
    for (const auto& n : a->graph()) order.push_back(n.name);
    auto at = [&](const char* name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
    EXPECT_GT(at("Probe update"), at("Deep G-buffer"));
    EXPECT_GT(at("Probe update"), at("Reproject radiance"));
    EXPECT_LT(at("Probe update"), at("Input radiance"));
}

// Bad input: a scene without geometry is a clear error, never a crash.
TEST(ProbeVolume, SceneWithoutGeometryIsAnError) {
    Scene empty;
    empty.computeBounds();
    try {
        ProbeVolume v(empty, Settings{});
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("no finite geometry"), std::string::npos) << e.what();
    }
}

// Layout: cell-centred probes cover the bounds, a flat scene gets 2 layers, and the count stays within
// probes.max_count.
TEST(ProbeVolume, GridFitsTheBoundsWithinTheCount) {
    Aabb b;
    b.extend({-2, 0, -2});
    b.extend({2, 0, 2});
    Settings s;
    ProbeGrid g = fitProbeGrid(b, s);
    EXPECT_EQ(g.counts, glm::ivec3(8, 2, 8));
    EXPECT_NEAR(g.spacing.x, 0.5f, 1e-6f);
    EXPECT_NEAR(g.gridPosition({0, 0, 0}).y, -0.125f, 1e-6f);  // 2 layers 0.25 apart around y = 0
    s.probeSpacing = 0.01f;  // absolute: 400 x 2 x 400 would be far too many
    g = fitProbeGrid(b, s);
    EXPECT_TRUE(g.coarsened);
    EXPECT_LE(g.count(), s.probeMaxCount);
    EXPECT_GE(g.count(), s.probeMaxCount / 2);
}


// The probes' radiance per direction (the directional fill's "Probe Radiance") inside a closed box whose six walls
// emit six different colours and reflect nothing: along each axis, every probe near the centre sees the one wall
// that axis points at (from the farthest probe, 1.5 away, the nearest edge of the wall is 18 degrees off the
// axis), so radiance(x, n, axis) is exactly that wall's emission; and it is the same whatever the receiver's normal.
TEST(ProbeVolume, RadiancePerDirectionIsTheEmissionOfTheWallSeen) {
    Scene scene;
    const float L = 2.0f;
    addBox(scene, glm::vec3(0.0f), glm::vec3(L), addMaterial(scene, glm::vec3(0.0f)), true);
    const glm::vec3 emission[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};  // +X -X +Y -Y +Z -Z
    for (int f = 0; f < 6; ++f)
        scene.parts[scene.parts.size() - 6 + size_t(f)].material = addMaterial(scene, glm::vec3(0.0f), 2.0f * emission[f]);
    scene.computeBounds();
    Settings s = noLights();
    s.probeRelativeSpacing = 0.5f;  // 2 x 2 x 2 probes, each 0.5 from three walls: all active (one near every wall)
    s.probeRadianceTexels = 16;     // texels of about 11 degrees: rays in those around an axis all hit its wall
    ProbeVolume v(scene, s);
    converge(v, s, 40);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int checked = 0;
    for (const glm::vec3& x : {glm::vec3(1.0f), glm::vec3(0.85f, 1.1f, 0.95f), glm::vec3(1.12f, 0.9f, 1.05f)})
        for (const glm::vec3& n : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, -1, 2))})
            for (int f = 0; f < 6; ++f) {
                const glm::vec3 r = v.radiance(x, n, axes[f]);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(r[c], 2.0f * emission[f][c], 0.01f) << "wall " << f << " channel " << c << " at " << x.x;
                ++checked;
            }
    EXPECT_EQ(checked, 36);
}

// The GLSL probeIrradiance() equals ProbeVolume::irradiance() (within llvmpipe's 8-bit filtering weights).
TEST_F(GLTest, ProbeVolumeShaderMatchesTheCpp) {
    const auto scene = deepgi::test::cornellScene();
    Settings s;
    ProbeVolume v(*scene, s);
    converge(v, s, 4);
    // Points on the floor, walls, ceiling and the block, and some in the air.
    std::vector<glm::vec3> ps, ns;
    for (int i = 0; i < 8; ++i) {
        const float t = -0.9f + 1.8f * float(i) / 7.0f;
        ps.push_back({t, 0.0f, 0.3f * t}); ns.push_back({0, 1, 0});
        ps.push_back({-1.0f, 1.0f + 0.5f * t, t}); ns.push_back({1, 0, 0});
        ps.push_back({1.0f, 0.2f + t * t, -t}); ns.push_back({-1, 0, 0});
        ps.push_back({0.5f * t, 1.99f, 0.7f}); ns.push_back({0, -1, 0});
        ps.push_back({-0.1f, 0.6f + 0.5f * t, -0.25f}); ns.push_back({1, 0, 0});
        ps.push_back({0.3f * t, 1.0f, t}); ns.push_back(glm::normalize(glm::vec3(t, 1.0f, -0.5f)));
    }
    const int N = int(ps.size());

    std::vector<gl::TextureHandle> tex = probeAtlasTextures(v.textures());
    v.uploadTextures(tex[0].id(), tex[1].id(), tex[2].id(), tex[3].id(), false);
    gl::BufferHandle ubo = gl::createBuffer("probe uniforms");
    glNamedBufferStorage(ubo.id(), sizeof(ProbeVolumeUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    v.uploadUniforms(ubo.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, ubo.id());
    glBindTextureUnit(2, tex[0].id());
    glBindTextureUnit(3, tex[1].id());
    glBindTextureUnit(5, tex[2].id());

    const std::string lib = readShaderSource("probe_volume.glsl");
    ASSERT_FALSE(lib.empty());
    // Seen from a direction per point: the view bias (probes.view_bias) moves the receiver alike on both sides.
    auto viewOf = [](const glm::vec3& n) { return glm::normalize(n + glm::vec3(0.2f, 0.5f, -0.3f)); };
    const std::vector<float> out = evaluateAtPoints(
        "#version 450 core\n#define PROBE_VOLUME_FIXED_UNITS\n" + lib +
            "\nvec3 testView(vec3 n) { return normalize(n + vec3(0.2, 0.5, -0.3)); }\n",
        "probeAtlasWeighted(uProbeIrradiance, uPoints[i], uNormals[i], testView(uNormals[i]))", ps, ns);
    ASSERT_EQ(out.size(), size_t(N) * 4);

    float worst = 0.0f;
    int lit = 0;
    for (int i = 0; i < N; ++i) {
        float w = 0.0f;
        const glm::vec3 E = v.irradiance(ps[i], ns[i], &w, viewOf(ns[i]));
        const glm::vec3 G(out[4 * i], out[4 * i + 1], out[4 * i + 2]);
        const float scale = std::max({E.x, E.y, E.z, 1e-3f});
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(G[c], E[c], 0.02f * scale + 1e-4f) << "point " << i << " channel " << c;
            worst = std::max(worst, std::abs(G[c] - E[c]) / scale);
        }
        EXPECT_NEAR(out[4 * i + 3], w, 0.02f * w + 1e-5f) << "weight at point " << i;
        lit += E.x > 0.01f;
    }
    EXPECT_GT(lit, N / 2) << "most points receive some indirect light";

    // probeRadianceAt() equals ProbeVolume::radiance() (the directional fill's lookup), in a direction per point.
    glBindTextureUnit(6, tex[3].id());
    const std::string radianceLib = lib + "\nvec3 testDirection(vec3 n) { return normalize(n + vec3(0.3, -0.2, 0.1)); }\n"
                                          "vec4 testRadiance(vec3 X, vec3 n) { ivec2 p[8]; float w[8]; vec3 c; probeSetAt(X, n, vec3(0.0), p, w, c);\n"
                                          "  return vec4(probeRadianceAt(p, w, testDirection(n)), 1.0); }\n";
    const std::vector<float> rad = evaluateAtPoints("#version 450 core\n#define PROBE_VOLUME_FIXED_UNITS\n" + radianceLib,
                                                    "testRadiance(uPoints[i], uNormals[i])", ps, ns);
    ASSERT_EQ(rad.size(), size_t(N) * 4);
    for (int i = 0; i < N; ++i) {
        const glm::vec3 L = v.radiance(ps[i], ns[i], glm::normalize(ns[i] + glm::vec3(0.3f, -0.2f, 0.1f)));
        const float scale = std::max({L.x, L.y, L.z, 1e-3f});
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rad[4 * i + c], L[c], 0.02f * scale + 1e-4f) << "radiance, point " << i;
    }

    // Later uploads send only the tile rows the updates changed; the textures still equal the CPU arrays.
    s.probeRaysPerFrame = 5 * 128;
    v.update(s);
    v.uploadTextures(tex[0].id(), tex[1].id(), tex[2].id(), tex[3].id(), false);
    const std::vector<ProbeTextureDesc> descs = v.textures();
    for (size_t t = 0; t < descs.size(); ++t) {
        const ProbeTextureDesc& d = descs[t];
        std::vector<float> back(size_t(d.width) * d.height * d.channels);
        glGetTextureImage(tex[t].id(), 0, d.uploadFormat, GL_FLOAT, GLsizei(back.size() * sizeof(float)), back.data());
        EXPECT_TRUE(std::equal(back.begin(), back.end(), d.data)) << d.name;
    }
    std::printf("GLSL vs C++: worst difference %.3f%% over %d points\n", 100.0f * worst, N);
}

// Benchmark, not run by ctest (figures, no assertion on time):
//   build/tests/deepgi_tests --gtest_also_run_disabled_tests --gtest_filter='*ProbeVolumeBench*'
TEST(ProbeVolumeBench, DISABLED_AtriumDefaultSettings) {
    const Scene scene = loadGltf(std::string(DEEPGI_ASSET_DIR) + "/atrium/atrium.gltf");
    const Settings s;
    for (int threads : {1, 2}) {
        ProbeVolume v(scene, s, 1, threads);
        double wall = 0.0, cpu = 0.0;
        uint64_t rays = 0, shadow = 0;
        const int frames = 20;
        for (int f = 0; f < frames; ++f) {
            const ProbeUpdateStats st = v.update(s);
            wall += st.milliseconds;
            cpu += st.cpuMilliseconds;
            rays += st.probeRays;
            shadow += st.shadowRays;
        }
        size_t bytes = 0;
        for (const ProbeTextureDesc& d : v.textures()) bytes += size_t(d.width) * d.height * d.channels * 4;
        std::printf("atrium, %d thread(s): grid %dx%dx%d, %d active, placement %.0f ms (%llu rays); per update "
                    "%.1f ms wall, %.1f ms CPU for %llu probe + %llu shadow rays; textures %.1f MiB\n",
                    threads, v.grid().counts.x, v.grid().counts.y, v.grid().counts.z, v.activeProbeCount(),
                    v.placementMilliseconds(), (unsigned long long)v.placementRays(), wall / frames, cpu / frames,
                    (unsigned long long)(rays / frames), (unsigned long long)(shadow / frames),
                    double(bytes) / (1024.0 * 1024.0));
    }
}

// probes.view_bias changes on a settled volume without a new one or a restart, and the next frame uses it.
TEST_F(GLTest, ViewBiasChangesWithoutRestartingTheProbes) {
    const auto scene = deepgi::test::cornellScene();
    Settings s;
    s.probeRaysPerFrame = 1 << 20;  // every probe every frame
    s.probeSettleUpdates = 8;
    s.varyTaps = false;             // the same taps every frame: a still frame repeats itself
    s.temporal = false;
    auto r = deepgi::test::rendererFor(scene, 48, 32, "front");
    for (int f = 0; f < 30; ++f) r->render(s);
    const ProbeVolume* volume = r->probeVolume();
    ASSERT_NE(volume, nullptr);
    const uint64_t updates = volume->updateCount();
    const FloatImage before = r->readLayer("Output Radiance");
    r->render(s);
    const FloatImage again = r->readLayer("Output Radiance");
    Settings other = s;
    other.probeViewBias = 0.6f;
    r->render(other);
    const FloatImage after = r->readLayer("Output Radiance");
    EXPECT_EQ(r->probeVolume(), volume) << "a new view bias built a new probe volume";
    EXPECT_EQ(r->probeVolume()->updateCount(), updates) << "a new view bias restarted the settled probes";
    double still = 0.0, changed = 0.0;
    for (size_t i = 0; i < before.pixels.size(); ++i) {
        still += std::abs(again.pixels[i] - before.pixels[i]);
        changed += std::abs(after.pixels[i] - again.pixels[i]);
    }
    std::printf("view bias 0.15 -> 0.6 on settled probes: L1 change %.4g (a repeated frame: %.4g)\n", changed, still);
    // A repeated frame still moves (the stores' dither, the feedback settling); a bias that never reaches the shaders
    // moves the next frame by as much (1.1 x), the new bias by about 9 x.
    EXPECT_GT(changed, 4.0 * still + 1e-3) << "the new bias did not reach the shaders";
}
