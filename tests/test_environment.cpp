// The environment light (renderer/scene/environment_map.h): the map's convention and checks, its importance
// sampling, the path tracer under a sky against analytic answers, and the real-time renderer against those.
// One file over 500 lines: the tests share the scenes and helpers and prove one feature end to end.
#include "gl_fixture.h"
#include "probe_glsl_harness.h"

#include "renderer/core/image_io.h"
#include "renderer/probes/probe_volume.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene_loader.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using namespace deepgi;
using deepgi::test::evaluateAtPoints;
using deepgi::test::probeAtlasTextures;
using deepgi::test::readShaderSource;
using namespace deepgi::procedural;
using deepgi::test::GLTest;
namespace fs = std::filesystem;

namespace {

constexpr float kPi = 3.14159265358979323846f;
const std::string kAssets = std::string(DEEPGI_ASSET_DIR) + "/test/open_sky";
// Two latitude-longitude maps of OpenEXR's sample images (assets/public/openexr_envmaps, BSD-3-Clause, ILM 2005).
const std::string kPublicMaps = std::string(DEEPGI_ASSET_DIR) + "/public/openexr_envmaps";

// The sky alone: no default sun.
Settings skyOnly(float skyRadiance) {
    Settings s;
    s.sunIntensity = 0.0f;
    s.skyRadiance = skyRadiance;
    return s;
}

// A map of w x h with radiance `base` everywhere and `bright` on the texels [x0, x1) x [y0, y1).
std::shared_ptr<EnvironmentMap> blockMap(int w, int h, float base, float bright, int x0, int x1, int y0, int y1) {
    std::vector<float> rgb(size_t(w) * h * 3, base);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c) rgb[(size_t(y) * w + x) * 3 + c] = bright;
    return std::make_shared<EnvironmentMap>(makeEnvironmentMap(w, h, std::move(rgb), "block map"));
}

// Irradiance on an upward surface from the environment, by a fine midpoint quadrature over (u, t).
double upwardIrradiance(const EnvironmentLight& env, int n = 1024) {
    double e = 0.0;
    for (int j = 0; j < n / 2; ++j)  // the upper hemisphere: t in [0, 1/2]
        for (int i = 0; i < n; ++i) {
            const float u = (float(i) + 0.5f) / float(n), t = (float(j) + 0.5f) / float(n);
            const glm::vec3 d = directionFromEquirect(u, t);
            const double dOmega = (2.0 * kPi / n) * (kPi / n) * std::sin(double(t) * kPi);
            e += double(env.radiance(d).x) * d.y * dOmega;
        }
    return e;
}

Camera lookAt(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfovDeg = 60.0f) {
    Camera cam;
    cam.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
    cam.yfov = glm::radians(yfovDeg);
    return cam;
}

ReferenceOptions refOptions(int size, int spp, int bounces) {
    ReferenceOptions o;
    o.width = o.height = size;
    o.spp = spp;
    o.maxBounces = bounces;
    o.progress = false;
    return o;
}

// A sphere of flat facets (each vertex carries its face's normal) with outward faces: convex facet by facet, so a
// ray leaving a facet never meets the sphere again.
void addFacetedSphere(Scene& s, glm::vec3 centre, float radius, int material, int rings = 12, int segments = 24) {
    MeshPart part;
    part.name = "sphere";
    part.material = material;
    auto p = [&](int r, int k) {
        const float theta = kPi * float(r) / float(rings), phi = 2.0f * kPi * float(k) / float(segments);
        return centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    auto tri = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const glm::vec3 n = glm::cross(b - a, c - a);
        if (!(glm::length(n) > 1e-9f)) return;
        const uint32_t base = uint32_t(part.vertices.size());
        for (const glm::vec3& q : {a, b, c}) part.vertices.push_back({q, glm::normalize(n), glm::vec2(0.0f)});
        part.indices.insert(part.indices.end(), {base, base + 1, base + 2});
    };
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < segments; ++k) {
            // Seen from outside, (r, k+1) lies left of (r, k) and (r+1, k) below it: counter-clockwise.
            if (r > 0) tri(p(r, k), p(r, k + 1), p(r + 1, k + 1));
            if (r < rings - 1) tri(p(r, k), p(r + 1, k + 1), p(r + 1, k));
        }
    s.parts.push_back(std::move(part));
    s.computeBounds();
}

// Pixel statistics of one channel over a centred square of half size `half` (fraction of the image).
double centreMean(const FloatImage& img, float half = 0.25f, int c = 0) {
    const int x0 = int(img.width * (0.5f - half)), x1 = int(img.width * (0.5f + half));
    const int y0 = int(img.height * (0.5f - half)), y1 = int(img.height * (0.5f + half));
    return test::meanChannel(img, c, x0, y0, x1, y1);
}

}  // namespace

// ---- The map ------------------------------------------------------------------------------------------------

// The convention of environment_map.h: u = 0.5 along +X, 0.75 along +Z, 0.25 along -Z, 0 along -X; t = 0 up.
TEST(EnvironmentMap, ConventionMapsTheAxes) {
    auto near = [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(equirectFromDirection({1, 0, 0}), {0.5f, 0.5f}));
    EXPECT_TRUE(near(equirectFromDirection({0, 0, 1}), {0.75f, 0.5f}));
    EXPECT_TRUE(near(equirectFromDirection({0, 0, -1}), {0.25f, 0.5f}));
    EXPECT_NEAR(equirectFromDirection({-1, 0, 0}).x, 0.0f, 1e-5f);
    EXPECT_NEAR(equirectFromDirection({0, 1, 0}).y, 0.0f, 1e-5f);
    EXPECT_NEAR(equirectFromDirection({0, -1, 0}).y, 1.0f, 1e-5f);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        const float u = U(rng), t = 0.01f + 0.98f * U(rng);
        const glm::vec2 back = equirectFromDirection(directionFromEquirect(u, t));
        EXPECT_NEAR(back.y, t, 1e-4f);
        EXPECT_NEAR(std::fmod(back.x - u + 1.5f, 1.0f) - 0.5f, 0.0f, 1e-4f);
    }
}

// Non-finite and negative radiance is refused with the file, the first bad pixel and the count; never clamped.
TEST(EnvironmentMap, BadTexelsAreRefusedNamingTheMap) {
    for (float bad : {std::nanf(""), INFINITY, -0.5f}) {
        std::vector<float> rgb(4 * 2 * 3, 1.0f);
        rgb[(1 * 4 + 2) * 3 + 1] = bad;  // pixel (2, 1)
        try {
            makeEnvironmentMap(4, 2, rgb, "sky.exr");
            ADD_FAILURE() << "accepted " << bad;
        } catch (const std::runtime_error& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("sky.exr"), std::string::npos) << m;
            EXPECT_NE(m.find("pixel 2, 1"), std::string::npos) << m;
            EXPECT_NE(m.find("1 non-finite or negative"), std::string::npos) << m;
        }
    }
    EXPECT_THROW(makeEnvironmentMap(0, 0, {}, "empty"), std::runtime_error);
}

TEST(EnvironmentMap, UnreadableFilesAreNamed) {
    const fs::path dir = fs::temp_directory_path() / ("deepgi_env_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const std::string& name : {std::string("missing.exr"), std::string("garbage.exr"), std::string("garbage.hdr")}) {
        const fs::path p = dir / name;
        if (name != "missing.exr") std::ofstream(p) << "not an image at all";
        try {
            loadEnvironmentMap(p.string());
            ADD_FAILURE() << name << " loaded";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
        }
    }
    // An 8-bit PNG is decoded from sRGB, with a warning that it has no high dynamic range.
    writePng8((dir / "ldr.png").string(), 2, 1, 3, {128, 128, 128, 255, 255, 255});
    const EnvironmentMap m = loadEnvironmentMap((dir / "ldr.png").string());
    EXPECT_NEAR(m.rgb[0], 0.21586f, 1e-4f);
    EXPECT_NEAR(m.rgb[3], 1.0f, 1e-6f);
    ASSERT_FALSE(m.warnings.empty());
    EXPECT_NE(m.warnings[0].find("8-bit"), std::string::npos) << m.warnings[0];
    // A NaN in an EXR file: refused, naming the file.
    writeExr((dir / "nan.exr").string(), FloatImage{2, 1, 3, {1, 1, 1, std::nanf(""), 1, 1}});
    EXPECT_THROW(loadEnvironmentMap((dir / "nan.exr").string()), std::runtime_error);
    fs::remove_all(dir);
}

// The test asset (tools/gen_environment_assets.py): each compass quadrant has its colour, the sun its radiance.
TEST(EnvironmentMap, TestAssetIsReadInItsOrientation) {
    const EnvironmentMap m = loadEnvironmentMap(kAssets + "/sky_test.hdr");
    ASSERT_EQ(m.width, 64);
    ASSERT_EQ(m.height, 32);
    Settings s;
    const EnvironmentLight env(&m, s);
    const float up = std::sin(0.3f), across = std::cos(0.3f);
    const glm::vec3 east = env.radiance({across, up, 0}), south = env.radiance({0, up, across});
    const glm::vec3 west = env.radiance({-across, up, 0}), north = env.radiance({0, up, -across});
    EXPECT_GT(east.x, 2.0f * east.y) << "+X is red";
    EXPECT_GT(south.y, 2.0f * south.x) << "+Z is green";
    EXPECT_GT(west.z, 2.0f * west.x) << "-X is blue";
    EXPECT_GT(north.x, 2.0f * north.z) << "-Z is yellow";
    EXPECT_GT(north.y, 2.0f * north.z);
    EXPECT_NEAR(env.radiance({0, -1, 0}).x, 0.2f, 0.002f) << "the ground below";
    // The sun: 2 x 2 texels around u = 0.625, t = 0.25 (45 degrees up towards +X+Z).
    EXPECT_NEAR(env.radiance(directionFromEquirect(0.625f, 0.25f)).x, 200.0f, 1.0f);
}

// environment.rotation turns the map about +Y: what the map holds towards m appears towards R_y(angle) m.
TEST(EnvironmentMap, RotationTurnsTheMapAboutUp) {
    const EnvironmentMap m = loadEnvironmentMap(kAssets + "/sky_test.hdr");
    Settings s;
    const EnvironmentLight still(&m, s, true);
    s.environmentRotation = 90.0f;
    const EnvironmentLight turned(&m, s, true);
    // R_y(90 deg) takes +X to -Z and +Z to +X: the red east of the map is now towards -Z.
    const float up = std::sin(0.3f), across = std::cos(0.3f);
    const glm::vec3 red = turned.radiance({0, up, -across});
    EXPECT_GT(red.x, 2.0f * red.y) << "+X's red now towards -Z";
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (float angle : {90.0f, -37.0f, 250.0f}) {
        s.environmentRotation = angle;
        const EnvironmentLight env(&m, s, true);
        const float c = std::cos(glm::radians(angle)), sn = std::sin(glm::radians(angle));
        for (int i = 0; i < 100; ++i) {
            const glm::vec3 d = directionFromEquirect(U(rng), 0.02f + 0.96f * U(rng));
            const glm::vec3 rd(d.x * c + d.z * sn, d.y, -d.x * sn + d.z * c);  // R_y(angle) d
            const glm::vec3 a = env.radiance(rd), b = still.radiance(d);
            for (int k = 0; k < 3; ++k) ASSERT_NEAR(a[k], b[k], 1e-4f * (1.0f + b[k])) << angle;
            ASSERT_NEAR(env.pdf(rd), still.pdf(d), 1e-4f * (1.0f + still.pdf(d))) << angle;
            // A sample's direction is where its radiance is, and pdf() agrees with it.
            const EnvironmentLight::Sample smp = env.sample(U(rng), U(rng));
            for (int k = 0; k < 3; ++k) ASSERT_NEAR(smp.radiance[k], env.radiance(smp.direction)[k], 1e-4f * (1.0f + smp.radiance[k]));
        }
    }
}

namespace {

// OpenEXR's own latitude-longitude convention (ImfEnvmap.h, written out here as its documentation states it, not
// through deepgi's code): longitude = atan2(x, z), latitude = asin(y); pixel column = centre - longitude / 2pi x
// (W - 1), row = centre - latitude / pi x (H - 1), the edge pixels' centres on the poles and on longitude +-pi.
// Bilinear between pixel centres.
glm::vec3 openExrLatLong(const EnvironmentMap& m, glm::vec3 d) {
    d = glm::normalize(d);
    const double lon = std::atan2(double(d.x), double(d.z)), lat = std::asin(std::clamp(double(d.y), -1.0, 1.0));
    const double px = 0.5 * (m.width - 1) - lon / (2.0 * kPi) * (m.width - 1);
    const double py = 0.5 * (m.height - 1) - lat / kPi * (m.height - 1);
    const int x0 = std::clamp(int(std::floor(px)), 0, m.width - 2), y0 = std::clamp(int(std::floor(py)), 0, m.height - 2);
    const float fx = float(std::clamp(px - x0, 0.0, 1.0)), fy = float(std::clamp(py - y0, 0.0, 1.0));
    auto at = [&](int x, int y) {
        const float* p = &m.rgb[(size_t(y) * m.width + x) * 3];
        return glm::vec3(p[0], p[1], p[2]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

// Mean over a cone of half-angle 2 degrees around d (sharp text and lines, averaged so that the two conventions'
// sub-texel difference in where texel centres lie, up to half a texel, stays small).
template <class Lookup>
glm::vec3 coneMean(glm::vec3 d, Lookup&& lookup) {
    d = glm::normalize(d);
    const glm::vec3 a = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(a, d)), b = glm::cross(d, t);
    const float r = std::tan(glm::radians(2.0f));
    glm::vec3 sum(0.0f);
    const int n = 64;
    for (int i = 0; i < n; ++i) {
        const float rad = r * std::sqrt((float(i) + 0.5f) / float(n)), phi = 2.39996323f * float(i);
        sum += lookup(glm::normalize(d + rad * (std::cos(phi) * t + std::sin(phi) * b)));
    }
    return sum / float(n);
}

}  // namespace

// OpenEXR's orientation map (its +X, +Y, +Z axes drawn and labelled where its convention puts them) with
// environment.rotation = -90: deepgi's lookup is OpenEXR's over the whole sphere. The figure: the L1 difference of
// 2-degree cone means at 4000 directions over the L1 of OpenEXR's own deviation from its mean (the map is mostly
// white: this measures the drawing, not the paper), below 0.1 turned. The other three quarter turns (the same text
// repeats every quarter turn; the axes and their labels do not) are each at least 4 times further.
TEST(EnvironmentMap, PublicOrientationMapReadsAsOpenExrMeansItAtMinus90) {
    const EnvironmentMap m = loadEnvironmentMap(kPublicMaps + "/OrientationLatLong.exr");
    ASSERT_EQ(m.width, 1024);
    ASSERT_EQ(m.height, 512);
    auto relL1 = [&](float rotation) {
        Settings s;
        s.environmentRotation = rotation;
        const EnvironmentLight env(&m, s);
        const int n = 4000;
        std::vector<glm::vec3> ours(n), theirs(n);
        glm::dvec3 mean(0.0);
        for (int i = 0; i < n; ++i) {  // a Fibonacci sphere
            const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n), r = std::sqrt(1.0f - y * y);
            const float phi = 2.39996323f * float(i);
            const glm::vec3 d(r * std::cos(phi), y, r * std::sin(phi));
            ours[i] = coneMean(d, [&](glm::vec3 q) { return env.radiance(q); });
            theirs[i] = coneMean(d, [&](glm::vec3 q) { return openExrLatLong(m, q); });
            mean += glm::dvec3(theirs[i]) / double(n);
        }
        double num = 0.0, den = 0.0;
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                num += std::abs(double(ours[i][c]) - theirs[i][c]);
                den += std::abs(theirs[i][c] - mean[c]);
            }
        return num / den;
    };
    const double turned = relL1(-90.0f);
    std::printf("orientation map against OpenEXR's convention: L1 over the drawing's %.4f at rotation -90", turned);
    EXPECT_LT(turned, 0.1);
    for (float other : {0.0f, 90.0f, 180.0f}) {
        const double wrong = relL1(other);
        std::printf(", %.4f at %.0f", wrong, other);
        EXPECT_GT(wrong, 4.0 * turned) << other;
    }
    std::printf("\n");
}

// ---- Sampling -------------------------------------------------------------------------------------------------

// The density integrates to 1 over the sphere, and each sample reports the density pdf() gives its direction.
TEST(EnvironmentSampling, PdfIsADensityThatSamplesFollow) {
    auto map = blockMap(32, 16, 0.1f, 50.0f, 20, 23, 4, 6);
    Settings s;
    const EnvironmentLight env(map.get(), s, true);
    ASSERT_TRUE(env.sampled());
    double integral = 0.0;
    const int n = 512;
    for (int j = 0; j < n / 2; ++j)
        for (int i = 0; i < n; ++i) {
            const float u = (float(i) + 0.5f) / float(n), t = (float(j) + 0.5f) / float(n / 2);
            integral += double(env.pdf(directionFromEquirect(u, t))) * (2.0 * kPi / n) * (kPi / (n / 2)) *
                        std::sin(double(t) * kPi);
        }
    EXPECT_NEAR(integral, 1.0, 0.01);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    int mismatched = 0, inBright = 0;
    for (int k = 0; k < 4000; ++k) {
        const EnvironmentLight::Sample smp = env.sample(U(rng), U(rng));
        ASSERT_GT(smp.pdf, 0.0f);
        ASSERT_TRUE(std::isfinite(smp.pdf));
        ASSERT_NEAR(glm::length(smp.direction), 1.0f, 1e-4f);
        if (std::abs(env.pdf(smp.direction) / smp.pdf - 1.0f) > 1e-3f) ++mismatched;  // texel edges only
        const glm::vec2 ut = equirectFromDirection(smp.direction);
        if (ut.x >= 20.0f / 32 && ut.x < 23.0f / 32 && ut.y >= 4.0f / 16 && ut.y < 6.0f / 16) ++inBright;
    }
    EXPECT_LT(mismatched, 20);
    // The bright texels hold 6 x 50 of the weight, their 14 neighbours 14 x 12.5, the other 492 texels 0.1 each
    // (before sin(theta)): about 60% of the samples.
    EXPECT_GT(inBright, 2000) << "most samples go to the bright region";
}

// Irradiance of an upward surface under a map with one bright region: importance sampling and uniform hemisphere
// sampling agree with the quadrature within 4 standard errors, and importance sampling's variance is much lower.
TEST(EnvironmentSampling, ImportanceSamplingAgreesWithUniformWithLessVariance) {
    auto map = blockMap(64, 32, 0.2f, 100.0f, 40, 43, 6, 8);
    Settings s;
    const EnvironmentLight env(map.get(), s, true);
    const double exact = upwardIrradiance(env);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    const int N = 8192;
    double sumI = 0, sumI2 = 0, sumU = 0, sumU2 = 0;
    for (int k = 0; k < N; ++k) {
        const EnvironmentLight::Sample smp = env.sample(U(rng), U(rng));
        const double fi = smp.direction.y > 0.0f ? double(smp.radiance.x) * smp.direction.y / smp.pdf : 0.0;
        sumI += fi;
        sumI2 += fi * fi;
        // Uniform over the upper hemisphere: pdf 1 / 2pi.
        const float z = U(rng), phi = 2.0f * kPi * U(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::vec3 d(r * std::cos(phi), z, r * std::sin(phi));
        const double fu = double(env.radiance(d).x) * d.y * 2.0 * kPi;
        sumU += fu;
        sumU2 += fu * fu;
    }
    const double meanI = sumI / N, varI = sumI2 / N - meanI * meanI;
    const double meanU = sumU / N, varU = sumU2 / N - meanU * meanU;
    std::printf("upward irradiance: quadrature %.4f, importance %.4f +- %.4f, uniform %.4f +- %.4f (variance ratio %.1f)\n",
                exact, meanI, std::sqrt(varI / N), meanU, std::sqrt(varU / N), varU / varI);
    EXPECT_NEAR(meanI, exact, 4.0 * std::sqrt(varI / N) + 1e-3 * exact);
    EXPECT_NEAR(meanU, exact, 4.0 * std::sqrt(varU / N) + 1e-3 * exact);
    EXPECT_LT(varI * 10.0, varU);
}

// ---- The path tracer under a sky (analytic furnace-style answers) ---------------------------------------------

// An upward single-sided plane of albedo rho alone under a white sky of radiance 1: L = rho exactly (every bounce
// leaves for the sky). With the uniform sky the cosine sampling is exact; with a constant map the map's sampling
// and the cosine sampling are combined by MIS and must still sum to rho.
TEST(PathTracerSky, OpenPlaneUnderWhiteSkyIsItsAlbedo) {
    Scene scene;
    addFloor(scene, 50.0f, 0.0f, addMaterial(scene, glm::vec3(0.5f)));
    const Camera cam = lookAt({0, 3, 0.01f}, {0, 0, 0}, {0, 0, -1}, 40.0f);
    const ReferenceResult uniform = renderReference(scene, cam, skyOnly(1.0f), refOptions(16, 16, 4));
    for (float v : uniform.final.pixels) ASSERT_NEAR(v, 0.5f, 1e-3f);
    scene.environment = blockMap(16, 8, 1.0f, 1.0f, 0, 0, 0, 0);
    const ReferenceResult mapped = renderReference(scene, cam, skyOnly(0.0f), refOptions(16, 64, 4));
    const double mean = test::meanChannel(mapped.final, 0);
    std::printf("plane under a constant map: %.5f (rho 0.5), mean relative standard error %.4f\n", mean, mapped.meanRelStdError);
    EXPECT_NEAR(mean, 0.5, 0.005);
}

// A convex sphere of albedo rho under a white sky: L = rho on every point it shows (the rest is the sky, 1).
TEST(PathTracerSky, ConvexSphereIsItsAlbedoEverywhere) {
    Scene scene;
    addFacetedSphere(scene, glm::vec3(0.0f), 1.0f, addMaterial(scene, glm::vec3(0.7f)));
    const Camera cam = lookAt({0.3f, 0.8f, 4.0f}, {0, 0, 0}, {0, 1, 0}, 40.0f);
    ReferenceResult r = renderReference(scene, cam, skyOnly(1.0f), refOptions(24, 16, 4));
    // Pixels on the silhouette mix sphere (0.7) and sky (1): every pixel lies in [0.7, 1]; the interior ones
    // (themselves and their 4 neighbours at 0.7) are 0.7.
    const int W = r.final.width, H = r.final.height;
    auto isRho = [&](int x, int y) { return std::abs(r.final.at(x, y, 0) - 0.7f) < 1e-3f; };
    std::vector<std::pair<int, int>> interior;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_GE(r.final.at(x, y, c), 0.7f - 1e-3f) << x << "," << y;
                ASSERT_LE(r.final.at(x, y, c), 1.0f + 1e-4f) << x << "," << y;
            }
            if (x > 0 && y > 0 && x + 1 < W && y + 1 < H && isRho(x, y) && isRho(x - 1, y) && isRho(x + 1, y) &&
                isRho(x, y - 1) && isRho(x, y + 1))
                interior.push_back({x, y});
        }
    ASSERT_GT(interior.size(), 100u);
    scene.environment = blockMap(16, 8, 1.0f, 1.0f, 0, 0, 0, 0);
    r = renderReference(scene, cam, skyOnly(0.0f), refOptions(24, 64, 4));
    double sum = 0;
    for (auto [x, y] : interior) sum += r.final.at(x, y, 0);
    std::printf("faceted sphere under a constant map: %.5f (rho 0.7)\n", sum / interior.size());
    EXPECT_NEAR(sum / interior.size(), 0.7, 0.007);
}

// A closed box under the sky, seen from inside: black (no ray leaves it).
TEST(PathTracerSky, ClosedBoxUnderTheSkyIsBlackInside) {
    Scene scene;
    addBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f), addMaterial(scene, glm::vec3(0.8f)), true);
    scene.environment = blockMap(16, 8, 1.0f, 20.0f, 2, 4, 1, 3);
    const Camera cam = lookAt({0, 0, 0.5f}, {0, 0, -1}, {0, 1, 0});
    const ReferenceResult r = renderReference(scene, cam, skyOnly(1.0f), refOptions(16, 16, 8));
    for (float v : r.final.pixels) ASSERT_EQ(v, 0.0f);
}

// The plane under a map with a bright region: L = rho/pi x the quadrature's irradiance, with the map's sampling
// alone (0 bounces: no MIS partner) and with MIS (4 bounces).
TEST(PathTracerSky, MapLightsThePlaneAsItsIrradianceSays) {
    Scene scene;
    addFloor(scene, 50.0f, 0.0f, addMaterial(scene, glm::vec3(0.5f)));
    scene.environment = blockMap(64, 32, 0.2f, 100.0f, 40, 43, 6, 8);
    const EnvironmentLight env(scene.environment.get(), skyOnly(0.0f));
    const double expected = 0.5 / kPi * upwardIrradiance(env);
    const Camera cam = lookAt({0, 3, 0.01f}, {0, 0, 0}, {0, 0, -1}, 30.0f);
    for (int bounces : {0, 4}) {
        const ReferenceResult r = renderReference(scene, cam, skyOnly(0.0f), refOptions(16, 256, bounces));
        const double mean = test::meanChannel(r.final, 0);
        std::printf("plane under the block map, %d bounces: %.4f (expected %.4f), mean relative standard error %.4f\n",
                    bounces, mean, expected, r.meanRelStdError);
        EXPECT_NEAR(mean, expected, 0.01 * expected) << bounces << " bounces";
    }
}

// A real sky: OpenEXR's Kerner Blvd. parking lot (a sun of radiance 1678 in a sky of about 0.2, over 10^5 of
// dynamic range). The plane under it: L = rho/pi x the quadrature's irradiance within 2% (the sun's texels are
// sampled by the map's importance sampling; its standard error is printed).
TEST(PathTracerSky, PublicHdrSunLightsThePlaneAsItsIrradianceSays) {
    Scene scene;
    addFloor(scene, 50.0f, 0.0f, addMaterial(scene, glm::vec3(0.5f)));
    attachEnvironment(scene, kPublicMaps + "/KernerEnvLatLong.exr");
    Settings s = skyOnly(0.0f);
    s.environmentRotation = -90.0f;
    const EnvironmentLight env(scene.environment.get(), s);
    const double expected = 0.5 / kPi * upwardIrradiance(env, 2048);
    const Camera cam = lookAt({0, 3, 0.01f}, {0, 0, 0}, {0, 0, -1}, 30.0f);
    for (int bounces : {0, 4}) {
        const ReferenceResult r = renderReference(scene, cam, s, refOptions(16, 256, bounces));
        const double mean = test::meanChannel(r.final, 0);
        std::printf("plane under the Kerner map, %d bounces: %.4f (expected %.4f), mean relative standard error %.4f\n",
                    bounces, mean, expected, r.meanRelStdError);
        EXPECT_NEAR(mean, expected, 0.02 * expected) << bounces << " bounces";
    }
}

// ---- The real-time renderer ---------------------------------------------------------------------------------

namespace {

// Settings that converge the probes in few frames: every probe updated every frame.
Settings fastProbes(Settings s) {
    s.probeRaysPerFrame = 1 << 20;
    s.probeRaysPerProbe = 256;
    return s;
}

FloatImage renderFrames(Renderer& r, const Settings& s, int frames) {
    for (int i = 0; i < frames; ++i) r.render(s);
    return r.readFinalRadiance();
}

}  // namespace

// The open upward plane (albedo 0.5) under a white sky of radiance 1: the path tracer's (and the analytic) L = 0.5.
// Tolerance 3%: the probes' octahedral texels next to the normal tilt by up to ~6 degrees (8 texels a face).
TEST_F(GLTest, SkyLightsAnOpenPlaneAsThePathTracer) {
    auto scene = std::make_shared<Scene>();
    addFloor(*scene, 5.0f, 0.0f, addMaterial(*scene, glm::vec3(0.5f)));
    addCamera(*scene, "down", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
    auto r = test::rendererFor(scene, 64, 64, "down");
    const FloatImage img = renderFrames(*r, fastProbes(skyOnly(1.0f)), 24);
    ASSERT_TRUE(test::allFinite(img));
    const double mean = centreMean(img);
    std::printf("open plane under the sky: real-time %.4f, path tracer and analytic 0.5\n", mean);
    EXPECT_NEAR(mean, 0.5, 0.015);
    ASSERT_NE(r->probeVolume(), nullptr);
    EXPECT_TRUE(r->probeVolume()->hasSky());
    EXPECT_TRUE(r->textures().has("Probe Sky Irradiance"));
}

// The same plane under the test map (a sky and a small bright sun): L = rho/pi x the map's upward irradiance.
TEST_F(GLTest, MapLightsAnOpenPlaneAsItsIrradianceSays) {
    auto scene = std::make_shared<Scene>();
    addFloor(*scene, 5.0f, 0.0f, addMaterial(*scene, glm::vec3(0.5f)));
    addCamera(*scene, "down", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
    attachEnvironment(*scene, kAssets + "/sky_test.hdr");
    const Settings s = fastProbes(skyOnly(0.0f));
    const EnvironmentLight env(scene->environment.get(), s);
    const double expected = 0.5 / kPi * upwardIrradiance(env);
    auto r = test::rendererFor(scene, 64, 64, "down");
    const FloatImage img = renderFrames(*r, s, 24);
    const double mean = centreMean(img);
    std::printf("open plane under the test map: real-time %.4f, analytic %.4f\n", mean, expected);
    EXPECT_NEAR(mean, expected, 0.03 * expected);
}

// The same plane under the real sky of OpenEXR's Kerner map (a sun over 10^5 of dynamic range), within the same 3%.
TEST_F(GLTest, PublicHdrSunLightsAnOpenPlaneAsItsIrradianceSays) {
    auto scene = std::make_shared<Scene>();
    addFloor(*scene, 5.0f, 0.0f, addMaterial(*scene, glm::vec3(0.5f)));
    addCamera(*scene, "down", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
    attachEnvironment(*scene, kPublicMaps + "/KernerEnvLatLong.exr");
    Settings s = fastProbes(skyOnly(0.0f));
    s.environmentRotation = -90.0f;
    const EnvironmentLight env(scene->environment.get(), s);
    const double expected = 0.5 / kPi * upwardIrradiance(env, 2048);
    auto r = test::rendererFor(scene, 64, 64, "down");
    const FloatImage img = renderFrames(*r, s, 24);
    ASSERT_TRUE(test::allFinite(img));
    const double mean = centreMean(img);
    std::printf("open plane under the Kerner map: real-time %.4f, analytic %.4f\n", mean, expected);
    EXPECT_NEAR(mean, expected, 0.03 * expected);
}

// A closed room standing on an open ground (the test asset) under the sky, seen from inside: black in the path
// tracer, and in the real-time renderer the leak stays below 1% of what the open ground outside receives (0.5).
TEST_F(GLTest, SkyDoesNotLightAClosedRoom) {
    auto scene = std::make_shared<Scene>(loadScene(kAssets + "/closed_room.gltf"));
    auto r = test::rendererFor(scene, 64, 48, "inside");
    const FloatImage img = renderFrames(*r, fastProbes(skyOnly(1.0f)), 24);
    ASSERT_TRUE(test::allFinite(img));
    std::vector<float> red;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) red.push_back(img.at(x, y, 0));
    std::sort(red.begin(), red.end());
    const double mean = test::meanChannel(img, 0), p95 = red[red.size() * 95 / 100], maxV = red.back();
    std::printf("closed room under the sky: mean %.5f, 95th percentile %.5f, max %.5f (open ground: 0.5)\n", mean, p95, maxV);
    // Bounds, against the 0.5 the open ground receives: the mean below 2%, 95% of the pixels below 10% (the
    // brightest are the far corners, where the probes' cells reach past two walls).
    EXPECT_LT(mean, 0.01);
    EXPECT_LT(p95, 0.05);
}

// The backdrop shows the map in its convention: looking along +X, +Z, -X, -Z and up, the centre pixel is the
// CPU's lookup (half-float texture, a mip level at most: 3%), unturned and turned by environment.rotation.
TEST_F(GLTest, BackdropShowsTheMapInItsOrientation) {
    auto scene = std::make_shared<Scene>();
    addFloor(*scene, 0.1f, -50.0f, addMaterial(*scene, glm::vec3(0.5f)));  // far below every view
    scene->environment = std::make_shared<EnvironmentMap>(loadEnvironmentMap(kAssets + "/sky_test.hdr"));
    Settings s;
    s.sunIntensity = 0.0f;
    s.environmentIntensity = 2.0f;
    s.background = 0.0f;
    const glm::vec3 dirs[] = {{1, 0.3f, 0}, {0, 0.3f, 1}, {-1, 0.3f, 0}, {0, 0.3f, -1}, {0.01f, 1, 0}};
    for (float rotation : {0.0f, -90.0f, 37.0f}) {
        for (const glm::vec3& d0 : dirs) {
            s.environmentRotation = rotation;
            const EnvironmentLight env(scene->environment.get(), s);
            const glm::vec3 d = glm::normalize(d0);
            Renderer r;
            r.setScene(scene);
            r.resize(33, 33);
            r.setCamera(lookAt(glm::vec3(0.0f), d, std::abs(d.y) > 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0), 10.0f));
            r.render(s);
            const FloatImage img = r.readFinalRadiance();
            const glm::vec3 expected = env.radiance(d);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.at(16, 16, c), expected[c], 0.03f * expected[c] + 1e-3f)
                    << "rotation " << rotation << " direction " << d.x << " " << d.y << " " << d.z << " channel " << c;
        }
    }
}

// Zero sky, no map: nothing of the environment exists (no texture, no probes for it); the sky alone brings the
// probe volume even with probes.enabled off.
TEST_F(GLTest, ZeroSkyCostsNothing) {
    auto scene = std::make_shared<Scene>();
    addFloor(*scene, 5.0f, 0.0f, addMaterial(*scene, glm::vec3(0.5f)));
    addCamera(*scene, "down", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
    auto r = test::rendererFor(scene, 32, 32, "down");
    Settings s;
    r->render(s);
    EXPECT_FALSE(r->textures().has("Probe Sky Irradiance"));
    EXPECT_FALSE(r->textures().has("Environment Map"));
    ASSERT_NE(r->probeVolume(), nullptr);
    EXPECT_FALSE(r->probeVolume()->hasSky());
    s.probesEnabled = false;
    r->render(s);
    EXPECT_EQ(r->probeVolume(), nullptr);
    s.skyRadiance = 1.0f;
    r->render(s);
    ASSERT_NE(r->probeVolume(), nullptr);
    EXPECT_TRUE(r->config().sky);
    EXPECT_FALSE(r->config().probes);
    s.environmentIntensity = 0.0f;
    r->render(s);
    EXPECT_EQ(r->probeVolume(), nullptr);
}

// The open-sky test asset under the test map (sun off): the real-time image against the path tracer. The ground
// in the centre of the view within 10% (the probes' sky visibility is interpolated over a probe spacing near the
// objects), and the mean over the image within 8%.
TEST_F(GLTest, OpenSkyAssetUnderTheMapMatchesThePathTracer) {
    auto scene = std::make_shared<Scene>(loadScene(kAssets + "/open_sky.gltf"));
    attachEnvironment(*scene, kAssets + "/sky_test.hdr");
    Settings s = fastProbes(skyOnly(0.0f));
    const int W = 48, H = 32;
    auto r = test::rendererFor(scene, W, H, "overview");
    const FloatImage rt = renderFrames(*r, s, 24);
    ReferenceOptions o = refOptions(W, 64, 6);
    o.height = H;
    const ReferenceResult ref = renderReference(*scene, selectCamera(*scene, "overview"), s, o);
    test::dumpIfRequested("open_sky_realtime", rt);
    test::dumpIfRequested("open_sky_reference", ref.final);
    double sumRt = 0, sumRef = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                sumRt += rt.at(x, y, c);
                sumRef += ref.final.at(x, y, c);
            }
    std::printf("open sky asset: mean real-time %.4f, path tracer %.4f\n", sumRt / (W * H * 3), sumRef / (W * H * 3));
    EXPECT_NEAR(sumRt / sumRef, 1.0, 0.08);
}

// ---- The command line ---------------------------------------------------------------------------------------

namespace {

std::pair<int, std::string> runDeepgi(const std::string& args) {
    const std::string cmd = std::string(DEEPGI_BINARY) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    if (!p) return {-1, out};
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int st = pclose(p);
    return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

}  // namespace

// --environment on render and reference: a bad file is refused naming it (no crash); a good one renders.
TEST(EnvironmentCli, RenderAndReferenceTakeTheMap) {
    const fs::path dir = fs::temp_directory_path() / ("deepgi_envcli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string scene = kAssets + "/open_sky.gltf";
    std::ofstream(dir / "bad.exr") << "garbage";
    for (const std::string& cmd : {std::string("render"), std::string("reference")}) {
        const std::string extra = cmd == "render" ? " --frames 1" : " --spp 1 --quiet";
        auto [status, out] = runDeepgi(cmd + " " + scene + " --size 8x8" + extra + " --out " + (dir / cmd).string() +
                                       " --environment " + (dir / "bad.exr").string());
        EXPECT_NE(status, 0) << out;
        EXPECT_LT(status, 128) << "no crash: " << out;
        EXPECT_NE(out.find((dir / "bad.exr").string()), std::string::npos) << out;
        std::tie(status, out) = runDeepgi(cmd + " " + scene + " --size 8x8" + extra + " --out " + (dir / cmd).string() +
                                          " --environment " + kAssets + "/sky_test.hdr --set light.sun_intensity=0");
        EXPECT_EQ(status, 0) << out;
        const FloatImage img = readImage((dir / cmd / "final.exr").string());
        double sum = 0;
        for (float v : img.pixels) sum += v;
        EXPECT_GT(sum / img.pixels.size(), 0.05) << cmd << ": the map lights and shows";
    }
    fs::remove_all(dir);
}

// ---- The GLSL sky lookup against the C++ one ----------------------------------------------------------------


// shaders/environment.glsl's probeSkyIrradiance() against ProbeVolume::skyIrradiance() on the open-sky asset
// under the test map: within 2% (GL's bilinear filtering weights have 8 bits of fraction).
TEST_F(GLTest, SkyShaderMatchesTheCpp) {
    Scene scene = loadScene(kAssets + "/open_sky.gltf");
    attachEnvironment(scene, kAssets + "/sky_test.hdr");
    const Settings s = fastProbes(skyOnly(0.5f));
    ProbeVolume v(scene, s);
    for (int i = 0; i < 4; ++i) v.update(s);
    ASSERT_TRUE(v.hasSky());
    std::vector<glm::vec3> ps, ns;
    for (int i = 0; i < 12; ++i) {
        const float t = -1.0f + 2.0f * float(i) / 11.0f;
        ps.push_back({2.0f * t, 0.0f, 1.5f * t}); ns.push_back({0, 1, 0});
        ps.push_back({0.5f * std::cos(3.0f * t), 0.5f + 0.45f * t, 0.5f * std::sin(3.0f * t)});
        ns.push_back(glm::normalize(ps.back() - glm::vec3(0, 0.5f, 0)));
        ps.push_back({0.9f, 0.3f + 0.25f * t, -0.6f + 0.25f * t}); ns.push_back({-1, 0, 0});
    }
    const int N = int(ps.size());
    std::vector<ProbeTextureDesc> descs = v.textures();
    descs.resize(3);  // irradiance, depth, data: what the sky lookup reads (not the radiance atlas)
    descs.push_back(v.skyTexture());
    std::vector<gl::TextureHandle> tex = probeAtlasTextures(descs);
    v.uploadSkyTexture(tex[3].id(), true);
    v.uploadTextures(tex[0].id(), tex[1].id(), tex[2].id(), true);
    gl::BufferHandle ubo = gl::createBuffer("probe uniforms");
    glNamedBufferStorage(ubo.id(), sizeof(ProbeVolumeUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    v.uploadUniforms(ubo.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, ubo.id());
    glBindTextureUnit(2, tex[0].id());
    glBindTextureUnit(3, tex[1].id());
    glBindTextureUnit(5, tex[2].id());
    glBindTextureUnit(6, tex[3].id());
    const std::vector<float> out = evaluateAtPoints(
        "#version 450 core\n#define PROBE_VOLUME_FIXED_UNITS\n#define DEEPGI_SKY\n" + readShaderSource("common.glsl") +
            readShaderSource("probe_volume.glsl") + readShaderSource("environment.glsl"),
        "vec4(probeSkyIrradiance(uPoints[i], uNormals[i]), 1.0)", ps, ns,
        [](GLuint prog) { glProgramUniform1i(prog, glGetUniformLocation(prog, "uProbeSky"), 6); });
    ASSERT_EQ(out.size(), size_t(N) * 4);
    int lit = 0;
    for (int i = 0; i < N; ++i) {
        const glm::vec3 E = v.skyIrradiance(ps[i], ns[i]);
        const float scale = std::max({E.x, E.y, E.z, 1e-3f});
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[4 * i + c], E[c], 0.02f * scale + 1e-4f) << "point " << i << " channel " << c;
        lit += E.x > 0.1f;
    }
    EXPECT_GT(lit, N / 2);
}
