// Reference path tracer: analytic cases (furnace, sun, point and spot lights), convergence, determinism, alpha.
// Every scene is built in code; images are small so the suite runs in seconds on two cores.
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/lighting.h"
#include "renderer/scene/procedural.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace deepgi;

namespace {

constexpr float kPi = 3.14159265358979323846f;

using procedural::addMaterial;

// A square of half size h centred at c whose front face (counter-clockwise) looks along n.
// uv (0,0) at corner c - h*t - h*b, u along t, v along b.
void addQuad(Scene& scene, glm::vec3 c, glm::vec3 n, float h, int material) {
    n = glm::normalize(n);
    const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(helper, n));
    const glm::vec3 b = glm::cross(n, t);  // cross(t, b) == n
    MeshPart part;
    part.name = "quad" + std::to_string(scene.parts.size());
    const glm::vec3 corner = c - h * t - h * b;
    const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const glm::vec3 ps[4] = {corner, corner + 2.0f * h * t, corner + 2.0f * h * (t + b), corner + 2.0f * h * b};
    for (int i = 0; i < 4; ++i) part.vertices.push_back({ps[i], n, uvs[i]});
    part.indices = {0, 1, 2, 0, 2, 3};
    part.material = material;
    scene.parts.push_back(part);
    scene.computeBounds();
}

Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfovDeg = 60.0f) {
    Camera cam;
    cam.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
    cam.yfov = glm::radians(yfovDeg);
    return cam;
}

// Straight down at the XZ plane: image right = +x, image top = -z.
Camera topDownOrtho(float height, float halfHeight) {
    Camera cam = lookAtCamera(glm::vec3(0, height, 0), glm::vec3(0), glm::vec3(0, 0, -1));
    cam.perspective = false;
    cam.orthoHalfHeight = halfHeight;
    return cam;
}

ReferenceOptions smallOptions(int size, int spp, int bounces, uint64_t seed = 1) {
    ReferenceOptions o;
    o.width = o.height = size;
    o.spp = spp;
    o.maxBounces = bounces;
    o.seed = seed;
    o.progress = false;
    return o;
}

Settings noSun() {
    Settings s;
    s.sunIntensity = 0.0f;
    return s;
}

// The world point seen at the centre of pixel (x, y) on the plane y = 0.
glm::vec3 planePointAt(const Camera& cam, int x, int y, int w, int h) {
    glm::vec3 o, d;
    cam.primaryRay(float(x) + 0.5f, float(y) + 0.5f, w, h, o, d);
    return o + d * (-o.y / d.y);
}

double rmse(const FloatImage& a, const FloatImage& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) sum += double(a.pixels[i] - b.pixels[i]) * (a.pixels[i] - b.pixels[i]);
    return std::sqrt(sum / double(a.pixels.size()));
}

bool sameBits(const FloatImage& a, const FloatImage& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// Open-topped box of albedo 0.6 lit by the default sun through the opening: plenty of indirect light.
Scene openBox() {
    Scene scene;
    const int m = addMaterial(scene, glm::vec3(0.6f));
    addQuad(scene, {0, -1, 0}, {0, 1, 0}, 1.0f, m);
    addQuad(scene, {-1, 0, 0}, {1, 0, 0}, 1.0f, m);
    addQuad(scene, {1, 0, 0}, {-1, 0, 0}, 1.0f, m);
    addQuad(scene, {0, 0, -1}, {0, 0, 1}, 1.0f, m);
    addQuad(scene, {0, 0, 1}, {0, 0, -1}, 1.0f, m);
    return scene;
}
Camera openBoxCamera() { return lookAtCamera({0.3f, 2.5f, 0.6f}, {0, -0.5f, 0}, {0, 1, 0}, 50.0f); }

}  // namespace

// 1. Closed box, every surface emits E with albedo a: radiance E/(1-a) everywhere.
TEST(ReferencePathTracer, WhiteFurnace) {
    for (float albedo : {0.5f, 0.8f}) {
        Scene scene;
        const float E = 1.0f;
        const int m = addMaterial(scene, glm::vec3(albedo), glm::vec3(E));
        const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (const glm::vec3& a : axes) {
            addQuad(scene, -a, a, 1.0f, m);  // inward-facing
            addQuad(scene, a, -a, 1.0f, m);
        }
        const Camera cam = lookAtCamera({0.2f, -0.1f, 0.3f}, {1, 0.4f, -0.7f}, {0, 1, 0}, 90.0f);
        const ReferenceResult r = renderReference(scene, cam, noSun(), smallOptions(16, 256, 10000));
        const double expected = E / (1.0 - albedo);
        double sum = 0.0, maxDev = 0.0, maxTol = 0.0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double v = r.final.at(x, y, c), se = r.stdError.at(x, y, c);
                    const double tol = 4.0 * se + 0.01 * expected;
                    EXPECT_NEAR(v, expected, tol) << "albedo " << albedo << " pixel " << x << "," << y;
                    EXPECT_GT(se, 0.0);
                    sum += v;
                    maxDev = std::max(maxDev, std::abs(v - expected));
                    maxTol = std::max(maxTol, tol);
                }
        const double mean = sum / (16 * 16 * 3);
        // The image mean averages 768 independent estimates: much tighter.
        EXPECT_NEAR(mean, expected, 0.005 * expected) << "albedo " << albedo;
        EXPECT_GT(r.meanRelStdError, 0.0);
        EXPECT_LT(r.meanRelStdError, 0.1);
        std::printf("[furnace a=%.1f] expected %.4f, image mean %.4f, max |dev| %.4f (max tolerance %.4f), "
                    "mean relative stderr %.4f, %.1f Mrays/s\n",
                    albedo, expected, mean, maxDev, maxTol, r.meanRelStdError, r.raysPerSecond() * 1e-6);
    }
}

// 2. A plane under the default sun: rho/pi * E * cos(theta), noiseless; an occluder casts an exact shadow.
TEST(ReferencePathTracer, PlaneUnderSun) {
    Scene scene;
    const float rho = 0.7f;
    addQuad(scene, {0, 0, 0}, {0, 1, 0}, 100.0f, addMaterial(scene, glm::vec3(rho)));
    Settings settings;
    settings.sunIntensity = 3.0f;
    settings.sunElevation = 40.0f;  // angle from the normal: 50 degrees
    settings.sunAzimuth = 30.0f;
    const double expected = rho / kPi * 3.0 * std::sin(glm::radians(40.0));
    const Camera cam = lookAtCamera({0, 5, 3}, {0, 0, 0}, {0, 1, 0}, 40.0f);
    const ReferenceResult r = renderReference(scene, cam, settings, smallOptions(16, 4, 4));
    double worst = 0.0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(r.direct.at(x, y, c) - expected) / expected);
                EXPECT_EQ(r.indirect.at(x, y, c), 0.0f);  // bounce rays leave into the empty sky
            }
    EXPECT_LT(worst, 0.005);
    EXPECT_LT(r.meanRelStdError, 1e-5);
    std::printf("[sun] expected %.6f, worst relative error %.2e\n", expected, worst);
}

TEST(ReferencePathTracer, SunShadowFromBothFaces) {
    // Sun from +z at 45 degrees; a unit square at height 1 shadows x in [-0.5, 0.5], z in [-1.5, -0.5].
    Settings settings;
    settings.sunIntensity = 2.0f;
    settings.sunElevation = 45.0f;
    settings.sunAzimuth = 0.0f;
    const float rho = 0.5f;
    const double lit = rho / kPi * 2.0 * std::sin(glm::radians(45.0));
    const int N = 32;
    const Camera cam = topDownOrtho(5.0f, 2.0f);
    for (bool facingUp : {true, false}) {
        Scene scene;
        const int m = addMaterial(scene, glm::vec3(rho));
        addQuad(scene, {0, 0, 0}, {0, 1, 0}, 100.0f, m);
        addQuad(scene, {0, 1, 0}, {0, facingUp ? 1.0f : -1.0f, 0}, 0.5f, m);
        const ReferenceResult r = renderReference(scene, cam, settings, smallOptions(N, 4, 0));
        int shadowed = 0, litCount = 0;
        const float margin = 4.0f / N;  // one pixel
        for (int y = 0; y < N; ++y)
            for (int x = 0; x < N; ++x) {
                const glm::vec3 p = planePointAt(cam, x, y, N, N);
                const bool underOccluder = std::abs(p.x) < 0.5f + margin && std::abs(p.z) < 0.5f + margin;
                const bool inShadow = std::abs(p.x) < 0.5f - margin && p.z > -1.5f + margin && p.z < -0.5f - margin;
                const bool outside = std::abs(p.x) > 0.5f + margin || p.z < -1.5f - margin || p.z > -0.5f + margin;
                const float v = r.direct.at(x, y, 1);
                if (inShadow) {
                    EXPECT_EQ(v, 0.0f) << "facing up " << facingUp << " pixel " << x << "," << y;
                    ++shadowed;
                } else if (outside && (!underOccluder || !facingUp)) {
                    // Seen from above, the down-facing occluder shows its back face: culled, the plane shows.
                    EXPECT_NEAR(v, lit, 0.005 * lit) << "facing up " << facingUp << " pixel " << x << "," << y;
                    ++litCount;
                }
            }
        EXPECT_GT(shadowed, 20);
        EXPECT_GT(litCount, 500);
    }
}

// 3. Error against a converged render falls as 1/sqrt(spp).
TEST(ReferencePathTracer, ErrorFallsAsInverseSqrtSpp) {
    const Scene scene = openBox();
    const Camera cam = openBoxCamera();
    const Settings settings;
    ReferenceTracer tracer(scene);
    const int N = 24;
    const ReferenceResult ref = tracer.render(cam, settings, smallOptions(N, 2048, 8, 999));
    double prev = 0.0;
    for (int spp : {4, 16, 64}) {
        const ReferenceResult r = tracer.render(cam, settings, smallOptions(N, spp, 8, 7));
        const double e = rmse(r.final, ref.final);
        if (prev > 0.0) {
            const double ratio = prev / e;
            std::printf("[convergence] spp %d -> %d: RMSE %.5f -> %.5f, ratio %.3f\n", spp / 4, spp, prev, e, ratio);
            EXPECT_GE(ratio, 1.6);
            EXPECT_LE(ratio, 2.5);
        }
        prev = e;
    }
    // The indirect part is real (the walls are lit mostly by the floor), and final = direct + indirect.
    double indirect = 0.0, total = 0.0;
    for (size_t i = 0; i < ref.final.pixels.size(); ++i) {
        indirect += ref.indirect.pixels[i];
        total += ref.final.pixels[i];
        const float sum = ref.direct.pixels[i] + ref.indirect.pixels[i];
        EXPECT_NEAR(ref.final.pixels[i], sum, 1e-5f * sum + 1e-7f);
    }
    EXPECT_GT(indirect, 0.1 * total);
    std::printf("[convergence] indirect share of the image: %.3f\n", indirect / total);
}

// 4. Same seed: bit-identical whatever the thread count; another seed: a different image.
TEST(ReferencePathTracer, DeterministicAcrossThreadCounts) {
    const Scene scene = openBox();
    const Camera cam = openBoxCamera();
    const Settings settings;
    ReferenceTracer tracer(scene);
    ReferenceOptions o = smallOptions(20, 8, 8, 42);
    o.threads = 1;
    const ReferenceResult a = tracer.render(cam, settings, o);
    o.threads = 2;
    const ReferenceResult b = tracer.render(cam, settings, o);
    o.threads = 3;
    const ReferenceResult c = tracer.render(cam, settings, o);
    EXPECT_TRUE(sameBits(a.final, b.final));
    EXPECT_TRUE(sameBits(a.direct, b.direct));
    EXPECT_TRUE(sameBits(a.indirect, b.indirect));
    EXPECT_TRUE(sameBits(a.stdError, b.stdError));
    EXPECT_TRUE(sameBits(a.final, c.final));
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.meanRelStdError, b.meanRelStdError);
    o.seed = 43;
    const ReferenceResult d = tracer.render(cam, settings, o);
    EXPECT_FALSE(sameBits(a.final, d.final));
}

// 5. Alpha-masked geometry is invisible where alpha < cutoff, to camera and shadow rays alike.
TEST(ReferencePathTracer, AlphaMaskedQuadIsInvisible) {
    Settings settings;
    settings.sunElevation = 70.0f;
    const Camera cam = lookAtCamera({0, 4, 1}, {0, 0, 0}, {0, 1, 0}, 50.0f);
    Scene plain;
    addQuad(plain, {0, 0, 0}, {0, 1, 0}, 50.0f, addMaterial(plain, glm::vec3(0.5f)));
    Scene masked = plain;
    Material m;
    m.baseColorFactor = glm::vec4(1, 0, 0, 0);  // alpha 0
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = 0.5f;
    m.doubleSided = true;
    masked.materials.push_back(m);
    addQuad(masked, {0, 1, 0}, {0, 1, 0.2f}, 1.0f, int(masked.materials.size()) - 1);
    const ReferenceOptions o = smallOptions(16, 4, 2);
    const ReferenceResult a = renderReference(plain, cam, settings, o);
    const ReferenceResult b = renderReference(masked, cam, settings, o);
    EXPECT_TRUE(sameBits(a.final, b.final));

    // Same quad, opaque: it shows (red) and shadows.
    masked.materials.back().baseColorFactor.w = 1.0f;
    const ReferenceResult c = renderReference(masked, cam, settings, o);
    EXPECT_FALSE(sameBits(a.final, c.final));
}

TEST(ReferencePathTracer, AlphaTextureCutsOutHalfAQuad) {
    // Nearest-filtered 2x1 texture: left texel transparent white, right texel opaque white.
    Scene scene;
    const int ground = addMaterial(scene, glm::vec3(0.0f), glm::vec3(1.0f));  // emits 1, black
    addQuad(scene, {0, 0, 0}, {0, 1, 0}, 50.0f, ground);
    scene.images.push_back({"alpha", 2, 1, {255, 255, 255, 0, 255, 255, 255, 255}});
    Texture t;
    t.image = 0;
    t.magFilter = FilterMode::Nearest;
    scene.textures.push_back(t);
    Material m;
    m.baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    m.baseColorTexture = 0;
    m.emissiveFactor = glm::vec3(3.0f);
    m.alphaMode = AlphaMode::Mask;
    scene.materials.push_back(m);
    // Up-facing quad at height 1 over x, z in [-1, 1]; its u runs along +x.
    addQuad(scene, {0, 1, 0}, {0, 1, 0}, 1.0f, int(scene.materials.size()) - 1);
    const Camera cam = topDownOrtho(5.0f, 2.0f);
    const int N = 16;
    const ReferenceResult r = renderReference(scene, cam, noSun(), smallOptions(N, 4, 0));
    int seenQuad = 0, seenGround = 0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const glm::vec3 p = planePointAt(cam, x, y, N, N);
            if (std::abs(p.z) > 0.75f || std::abs(p.x) > 0.75f) continue;
            // Which half is transparent depends on the quad's u axis: find it from the geometry.
            const glm::vec3 p0 = scene.parts[1].vertices[0].position, p1 = scene.parts[1].vertices[1].position;
            const float u = glm::dot(p - p0, p1 - p0) / glm::dot(p1 - p0, p1 - p0);
            if (std::abs(u - 0.5f) < 0.15f) continue;  // the edge between the texels
            const float v = r.final.at(x, y, 0);
            if (u < 0.5f) {
                EXPECT_FLOAT_EQ(v, 1.0f) << x << "," << y;
                ++seenGround;
            } else {
                EXPECT_FLOAT_EQ(v, 3.0f) << x << "," << y;
                ++seenQuad;
            }
        }
    EXPECT_GT(seenQuad, 4);
    EXPECT_GT(seenGround, 4);
}

TEST(ReferencePathTracer, BackFaceOfSingleSidedQuadIsInvisibleToCamera) {
    // An emitting ground seen from above; no lights. A dark quad in between shows only with its front face up.
    const Camera cam = topDownOrtho(5.0f, 2.0f);
    const int N = 16;
    for (bool facingCamera : {false, true}) {
        Scene scene;
        addQuad(scene, {0, 0, 0}, {0, 1, 0}, 50.0f, addMaterial(scene, glm::vec3(0.5f), glm::vec3(1.0f)));
        addQuad(scene, {0, 1, 0}, {0, facingCamera ? 1.0f : -1.0f, 0}, 1.0f, addMaterial(scene, glm::vec3(0.5f)));
        const ReferenceResult r = renderReference(scene, cam, noSun(), smallOptions(N, 1, 0));
        const float centre = r.final.at(N / 2, N / 2, 0), corner = r.final.at(0, 0, 0);
        EXPECT_FLOAT_EQ(corner, 1.0f);
        EXPECT_FLOAT_EQ(centre, facingCamera ? 0.0f : 1.0f);
    }
    // A double-sided quad shows from both sides.
    Scene scene;
    addQuad(scene, {0, 0, 0}, {0, 1, 0}, 50.0f, addMaterial(scene, glm::vec3(0.5f), glm::vec3(1.0f)));
    addQuad(scene, {0, 1, 0}, {0, -1, 0}, 1.0f, addMaterial(scene, glm::vec3(0.5f), glm::vec3(2.0f), true));
    const ReferenceResult r = renderReference(scene, cam, noSun(), smallOptions(N, 1, 0));
    EXPECT_FLOAT_EQ(r.final.at(N / 2, N / 2, 0), 2.0f);
}

// 6. Point and spot lights: rho/pi * I / h^2 at the foot point; nothing outside the spot cone.
TEST(ReferencePathTracer, PointAndSpotLightFootPoint) {
    const float rho = 0.6f, I = 5.0f, h = 2.0f;
    const double expected = rho / kPi * I / (h * h);
    const int N = 9;  // odd: the centre pixel's centre is the foot point
    for (LightType type : {LightType::Point, LightType::Spot}) {
        Scene scene;
        addQuad(scene, {0, 0, 0}, {0, 1, 0}, 50.0f, addMaterial(scene, glm::vec3(rho)));
        Light l;
        l.type = type;
        l.intensity = I;
        l.position = {0, h, 0};
        l.direction = {0, -1, 0};
        l.innerConeAngle = 0.3f;
        l.outerConeAngle = 0.5f;
        scene.lights.push_back(l);
        // Tiny footprint around the foot point (jitter spans +-0.001: relative change ~1e-6).
        const Camera cam = topDownOrtho(5.0f, 0.01f);
        const ReferenceResult r = renderReference(scene, cam, Settings{}, smallOptions(N, 16, 0));
        const double v = r.direct.at(N / 2, N / 2, 1);
        EXPECT_NEAR(v, expected, 0.005 * expected) << int(type);
        std::printf("[%s] expected %.6f got %.6f (relative error %.2e)\n", type == LightType::Point ? "point" : "spot",
                    expected, v, std::abs(v - expected) / expected);

        // Wide view: the spot lights nothing beyond its outer cone; the point light follows h / d^3.
        const Camera wide = topDownOrtho(5.0f, 3.0f);
        const int M = 21;
        const ReferenceResult w = renderReference(scene, wide, Settings{}, smallOptions(M, 1, 0));
        for (int y = 0; y < M; ++y)
            for (int x = 0; x < M; ++x) {
                const glm::vec3 p = planePointAt(wide, x, y, M, M);
                const float r = glm::length(glm::vec2(p.x, p.z));
                const float pixel = 6.0f / M;
                const float angle = std::atan2(r, h);
                if (type == LightType::Spot && std::atan2(r - pixel, h) > l.outerConeAngle) {
                    EXPECT_EQ(w.direct.at(x, y, 0), 0.0f) << x << "," << y;
                } else if (type == LightType::Point) {
                    const double e = rho / kPi * lightIrradiance(l, p, {0, 1, 0}).x;
                    EXPECT_NEAR(w.direct.at(x, y, 0), e, 0.2 * e + 1e-4) << x << "," << y << " angle " << angle;
                }
            }
    }
}

TEST(ReferencePathTracer, BackgroundSeenButLightsNothing) {
    Settings settings;
    settings.background = 0.25f;
    settings.sunIntensity = 0.0f;
    Scene scene;
    addQuad(scene, {0, 0, 0}, {0, 1, 0}, 1.0f, addMaterial(scene, glm::vec3(0.9f)));
    const Camera cam = topDownOrtho(5.0f, 2.0f);
    const ReferenceResult r = renderReference(scene, cam, settings, smallOptions(16, 4, 8));
    EXPECT_FLOAT_EQ(r.final.at(0, 0, 0), 0.25f);   // miss
    EXPECT_FLOAT_EQ(r.direct.at(0, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(r.final.at(8, 8, 0), 0.0f);    // the plane: bounce rays see nothing
}

TEST(ReferencePathTracer, OptionsAndSizeParsing) {
    EXPECT_EQ(parseImageSize("320x180"), std::make_pair(320, 180));
    EXPECT_EQ(parseImageSize("1X1"), std::make_pair(1, 1));
    for (const char* bad : {"", "320", "0x180", "320x0", "-1x5", "32x", "x32", "3.5x2", "320x180x2", " 320x180",
                            "abcxdef", "99999999x1", "70000x10"})
        EXPECT_THROW(parseImageSize(bad), std::runtime_error) << bad;
    Scene scene;
    const Camera cam;
    ReferenceOptions o = smallOptions(4, 0, 0);
    EXPECT_THROW(renderReference(scene, cam, Settings{}, o), std::invalid_argument);
    o = smallOptions(4, 1, -1);
    EXPECT_THROW(renderReference(scene, cam, Settings{}, o), std::invalid_argument);
    o = smallOptions(0, 1, 0);
    EXPECT_THROW(renderReference(scene, cam, Settings{}, o), std::invalid_argument);
    // An empty scene renders the background.
    Settings s;
    s.background = 0.5f;
    const ReferenceResult r = renderReference(scene, cam, s, smallOptions(4, 2, 2));
    EXPECT_FLOAT_EQ(r.final.at(3, 3, 2), 0.5f);
    // Bad index buffers are refused with a message.
    addQuad(scene, {0, 0, 0}, {0, 1, 0}, 1.0f, -1);
    scene.parts[0].indices[2] = 17;
    EXPECT_THROW(ReferenceTracer{scene}, std::runtime_error);
}

// Textures: sRGB-decoded rgb, linear alpha, bilinear between texel centres, wrap modes, v = 0 at the image top.
TEST(ReferencePathTracer, TexturesAreSrgbDecodedBilinearAndTopDown) {
    // Emission only (no lights, no bounces): the pixel value is emissiveFactor * decoded texture.
    // 2x2 image: row 0 (top) = [black, white], row 1 = [grey 128, grey 128].
    Scene scene;
    scene.images.push_back({"tex", 2, 2, {0, 0, 0, 255, 255, 255, 255, 255, 128, 128, 128, 255, 128, 128, 128, 255}});
    Texture t;
    t.image = 0;
    t.wrapS = WrapMode::Repeat;
    t.wrapT = WrapMode::ClampToEdge;
    scene.textures.push_back(t);
    Material m;
    m.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    m.emissiveFactor = glm::vec3(2.0f);
    m.emissiveTexture = 0;
    scene.materials.push_back(m);
    // One quad in the XZ plane facing +y with uv = (x, z) over [0, 2] x [0, 1].
    MeshPart part;
    const glm::vec3 n(0, 1, 0);
    part.vertices = {{{0, 0, 0}, n, {0, 0}}, {{0, 0, 1}, n, {0, 1}}, {{2, 0, 1}, n, {2, 1}}, {{2, 0, 0}, n, {2, 0}}};
    part.indices = {0, 1, 2, 0, 2, 3};
    part.material = 0;
    scene.parts.push_back(part);
    scene.computeBounds();
    const auto valueAt = [&](float u, float v) {
        Camera cam = lookAtCamera({u, 1, v}, {u, 0, v}, {0, 0, -1});
        cam.perspective = false;
        cam.orthoHalfHeight = 1e-4f;
        const ReferenceResult r = renderReference(scene, cam, noSun(), smallOptions(1, 4, 0));
        return r.final.at(0, 0, 0);
    };
    const float grey = srgbToLinear(128.0f / 255.0f);
    EXPECT_NEAR(valueAt(0.25f, 0.05f), 0.0f, 1e-3f);                 // top-left texel (v clamped)
    EXPECT_NEAR(valueAt(0.75f, 0.05f), 2.0f, 2e-3f);                 // top-right texel
    EXPECT_NEAR(valueAt(0.5f, 0.05f), 1.0f, 2e-3f);                  // halfway: linear blend of decoded values
    EXPECT_NEAR(valueAt(1.0f, 0.05f), 1.0f, 2e-3f);                  // u wraps: blend of the right and left texels
    EXPECT_NEAR(valueAt(1.25f, 0.05f), 0.0f, 1e-3f);                 // repeated
    EXPECT_NEAR(valueAt(0.25f, 0.95f), 2.0f * grey, 2e-3f);          // bottom row, sRGB 128 -> 0.2158
    EXPECT_NEAR(valueAt(0.25f, 0.5f), 0.5f * 2.0f * grey, 2e-3f);    // between the rows
}
