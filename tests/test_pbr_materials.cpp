// glTF metallic-roughness against independent answers: the GGX lobe written out again here (Smith G2 from the
// Lambda functions, D from tan(theta_h): not the code of renderer/scene/brdf.h), numerical integration for energy,
// the analytic N.L change of a normal map, and the loader's warnings.
#include "gl_fixture.h"

#include "renderer/reference/path_tracer.h"
#include "renderer/scene/brdf.h"
#include "renderer/scene/gltf_loader.h"

#include <fstream>
#include <random>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The glTF appendix B specular term in another form: F * D * G2 / (4 n.l n.v) with
// D = 1 / (pi a^2 cos^4 th (1 + tan^2 th / a^2)^2), G2 = 1 / (1 + Lambda(v) + Lambda(l)),
// Lambda = (-1 + sqrt(1 + a^2 tan^2)) / 2, F = Schlick.
glm::dvec3 analyticSpecular(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, glm::dvec3 f0, double roughness) {
    const double nl = glm::dot(n, l), nv = glm::dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return glm::dvec3(0.0);
    const double a = roughness * roughness, a2 = a * a;
    const glm::dvec3 h = glm::normalize(v + l);
    const double ch = glm::dot(n, h), t2h = (1.0 - ch * ch) / (ch * ch);
    const double D = 1.0 / (kPi * a2 * ch * ch * ch * ch * (1.0 + t2h / a2) * (1.0 + t2h / a2));
    auto lambda = [&](double c) { return (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))) / 2.0; };
    const double G2 = 1.0 / (1.0 + lambda(nv) + lambda(nl));
    const glm::dvec3 F = f0 + (glm::dvec3(1.0) - f0) * std::pow(1.0 - glm::dot(v, h), 5.0);
    return F * (D * G2 / (4.0 * nl * nv));
}

// A metal floor (base, metallic 1, roughness r) lit by one sun, seen from above at an angle.
std::shared_ptr<Scene> metalFloor(glm::vec3 base, float roughness, glm::vec3 sunDir, float irradiance) {
    auto s = std::make_shared<Scene>();
    const int m = addMaterial(*s, base);
    s->materials[m].metallic = 1.0f;
    s->materials[m].roughness = roughness;
    addFloor(*s, 30.0f, 0.0f, m);
    addSun(*s, sunDir, irradiance);
    addCamera(*s, "cam", {0.0f, 2.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, 50.0f);
    s->computeBounds();
    return s;
}

// The world point where the ray through (x, y) of a w x h image meets the plane y = 0 (false: it misses).
bool floorHit(const Camera& cam, float x, float y, int w, int h, glm::dvec3& p, glm::dvec3& toEye) {
    glm::vec3 o, d;
    cam.primaryRay(x, y, w, h, o, d);
    if (!(d.y < -1e-4f)) return false;
    const double t = -double(o.y) / double(d.y);
    p = glm::dvec3(o) + t * glm::dvec3(d);
    toEye = -glm::normalize(glm::dvec3(d));
    return std::abs(p.x) < 29.0 && std::abs(p.z) < 29.0;
}

std::string writeTemp(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

float luminance(const FloatImage& img, int x, int y) {
    return 0.2126f * img.at(x, y, 0) + 0.7152f * img.at(x, y, 1) + 0.0722f * img.at(x, y, 2);
}

}  // namespace

// The composite's direct specular of a metal floor under one sun, pixel by pixel, against the analytic GGX value
// at that pixel's n, v, l (n = +Y exactly; v from the camera; F0 = base colour).
TEST_F(GLTest, MetalFloorDirectSpecularMatchesAnalyticGgx) {
    const glm::vec3 base(0.9f, 0.6f, 0.3f);
    const glm::vec3 sunDir = glm::normalize(glm::vec3(0.0f, -1.0f, 1.2f));  // towards the camera: a highlight in view
    const float E = 2.0f, roughness = 0.6f;
    auto s = metalFloor(base, roughness, sunDir, E);
    const int W = 96, H = 72;
    auto r = rendererFor(s, W, H, "cam");
    Settings st;
    st.indirect = false;
    r->render(st);
    ASSERT_TRUE(r->textures().has("Specular"));
    const FloatImage img = r->readFinalRadiance();
    dumpIfRequested("metal_floor", img);
    ASSERT_TRUE(allFinite(img));
    const Camera cam = selectCamera(*s, "cam");
    const glm::dvec3 n(0, 1, 0), l = -glm::dvec3(sunDir);
    double worst = 0.0, peak = 0.0;
    int checked = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            glm::dvec3 p, v;
            if (!floorHit(cam, x + 0.5f, y + 0.5f, W, H, p, v)) continue;
            const glm::dvec3 f = analyticSpecular(n, v, l, glm::dvec3(base), roughness);
            const double want = f.y * E * glm::dot(n, l);  // green; diffuse albedo is 0 for a metal
            peak = std::max(peak, want);
            if (want < 0.02) continue;
            worst = std::max(worst, std::abs(img.at(x, y, 1) - want) / want);
            ++checked;
        }
    EXPECT_GT(checked, 100);
    EXPECT_GT(peak, 0.3);  // the highlight is in view
    // 8-bit roughness and F0, oct16 normals: a few percent at most.
    EXPECT_LT(worst, 0.04);
}

// material.diffuse_only: the same floor is Lambertian with albedo = base colour and no Specular texture.
TEST_F(GLTest, DiffuseOnlyRendersTheMetalAsItsBaseColour) {
    const glm::vec3 base(0.9f, 0.6f, 0.3f);
    auto s = metalFloor(base, 0.6f, glm::vec3(0.0f, -1.0f, 0.0f), 2.0f);
    auto r = rendererFor(s, 64, 48, "cam");
    Settings st;
    st.indirect = false;
    st.diffuseOnly = true;
    r->render(st);
    EXPECT_FALSE(r->textures().has("Specular"));
    const FloatImage img = r->readFinalRadiance();
    EXPECT_NEAR(img.at(32, 30, 0), base.x / kPi * 2.0, 0.01);
    EXPECT_NEAR(img.at(32, 30, 2), base.z / kPi * 2.0, 0.01);
}

// The path tracer's direct light at the first hit (bounces 0) on the same floor: the analytic value averaged over
// the pixel (the tracer jitters within it).
TEST(PathTracerMaterials, MetalFloorDirectMatchesAnalyticGgx) {
    const glm::vec3 base(0.9f, 0.6f, 0.3f);
    const glm::vec3 sunDir = glm::normalize(glm::vec3(0.0f, -1.0f, 1.2f));
    const float E = 2.0f, roughness = 0.4f;
    auto s = metalFloor(base, roughness, sunDir, E);
    const Camera cam = selectCamera(*s, "cam");
    ReferenceOptions o;
    o.width = 24;
    o.height = 18;
    o.spp = 64;
    o.maxBounces = 0;
    o.progress = false;
    const ReferenceResult res = renderReference(*s, cam, Settings{}, o);
    const glm::dvec3 n(0, 1, 0), l = -glm::dvec3(sunDir);
    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            double want = 0.0;
            int k = 0;
            bool all = true;
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i, ++k) {
                    glm::dvec3 p, v;
                    if (!floorHit(cam, x + (i + 0.5f) / 8.0f, y + (j + 0.5f) / 8.0f, o.width, o.height, p, v)) { all = false; continue; }
                    want += analyticSpecular(n, v, l, glm::dvec3(base), roughness).x * E * glm::dot(n, l);
                }
            if (!all) continue;
            want /= k;
            if (want < 0.05) continue;
            // The tracer's jitter noise (4 standard errors) plus 1 % for the 8 x 8 quadrature of the pixel here.
            const double err = std::abs(res.final.at(x, y, 0) - want) / (4.0 * res.stdError.at(x, y, 0) + 0.01 * want);
            worst = std::max(worst, err);
            ++checked;
        }
    EXPECT_GT(checked, 50);
    EXPECT_LT(worst, 1.0);
}

// Energy of the GGX lobe with F0 = 1 (white furnace of the BRDF alone): the directional albedo estimated with the
// path tracer's sampler (visible normals, pdf from brdf.h) equals a plain uniform-hemisphere integration and is <= 1.
TEST(BrdfEnergy, VisibleNormalSamplingIntegratesTheLobeAndLosesEnergyOnly) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    const glm::vec3 n(0, 0, 1), f0(1.0f);
    for (float roughness : {0.3f, 1.0f})
        for (float nv : {1.0f, 0.5f, 0.15f}) {
            const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
            const float alpha = brdf::alphaOf(roughness);
            double vndf = 0.0, uniform = 0.0;
            const int N = 200000;
            for (int i = 0; i < N; ++i) {
                const glm::vec3 h = brdf::sampleVisibleNormal(v, alpha, U(rng), U(rng));
                const glm::vec3 l = glm::reflect(-v, h);
                if (l.z > 0.0f) {
                    const float pdf = brdf::reflectionPdf(nv, h.z, alpha);
                    vndf += double(brdf::specular(n, v, l, f0, alpha).x) * l.z / pdf;
                }
                const float z = U(rng), phi = 2.0f * float(kPi) * U(rng), sr = std::sqrt(1.0f - z * z);
                const glm::dvec3 lu(sr * std::cos(phi), sr * std::sin(phi), z);
                uniform += analyticSpecular(glm::dvec3(n), glm::dvec3(v), lu, glm::dvec3(1.0), roughness).x * z * 2.0 * kPi;
            }
            vndf /= N;
            uniform /= N;
            EXPECT_LE(vndf, 1.0) << "roughness " << roughness << " n.v " << nv;
            EXPECT_GT(vndf, 0.2) << "roughness " << roughness << " n.v " << nv;  // single scattering loses up to ~60 %
            // Uniform sampling of a sharp lobe is noisy: 3 % at roughness 0.3.
            EXPECT_NEAR(vndf, uniform, 0.03 * uniform) << "roughness " << roughness << " n.v " << nv;
        }
}

// White furnace through the path tracer: a rough metal sphere (F0 = 1, roughness 1) inside a closed box emitting
// radiance 1 and reflecting nothing. The sphere's centre pixel is that lobe's directional albedo at normal
// incidence (integrated here independently), at most 1.
TEST(PathTracerMaterials, MetalSphereInAWhiteFurnaceReflectsAtMostWhatArrives) {
    Scene s;
    const int box = addMaterial(s, glm::vec3(0.0f), glm::vec3(1.0f));
    addBox(s, glm::vec3(-4.0f), glm::vec3(4.0f), box, true);
    const int metal = addMaterial(s, glm::vec3(1.0f));
    s.materials[metal].metallic = 1.0f;
    s.materials[metal].roughness = 1.0f;
    MeshPart sphere;
    sphere.material = metal;
    const int rings = 48, segs = 96;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segs; ++j) {
            const float th = float(kPi) * i / rings, ph = 2.0f * float(kPi) * j / segs;
            const glm::vec3 nn(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
            sphere.vertices.push_back(Vertex{nn, nn, glm::vec2(0.0f)});
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segs; ++j) {
            const uint32_t a = uint32_t(i * (segs + 1) + j), b = a + uint32_t(segs + 1);
            sphere.indices.insert(sphere.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    s.parts.push_back(sphere);
    addCamera(s, "cam", {0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 30.0f);
    s.computeBounds();
    Settings st;
    st.sunIntensity = 0.0f;
    ReferenceOptions o;
    o.width = o.height = 9;
    o.spp = 4096;
    o.maxBounces = 1;
    o.progress = false;
    const ReferenceResult res = renderReference(s, selectCamera(s, "cam"), st, o);
    // Directional albedo at n.v = 1 by uniform hemisphere integration of the analytic lobe.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double albedo = 0.0;
    const int N = 400000;
    for (int i = 0; i < N; ++i) {
        const double z = U(rng), phi = 2.0 * kPi * U(rng), sr = std::sqrt(1.0 - z * z);
        albedo += analyticSpecular({0, 0, 1}, {0, 0, 1}, {sr * std::cos(phi), sr * std::sin(phi), z}, glm::dvec3(1.0), 1.0).x * z * 2.0 * kPi;
    }
    albedo /= N;
    const float centre = res.final.at(4, 4, 0);
    EXPECT_LE(albedo, 1.0);
    EXPECT_NEAR(centre, albedo, 0.03 * albedo);
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) EXPECT_LE(res.final.at(x, y, 1), 1.0f + 4.0f * res.stdError.at(x, y, 1) + 1e-3f);
}

// A constant normal texture tilting the normal by 30 degrees towards +X, a light 80 degrees off the wall's normal
// from +X: the diffuse radiance follows cos(50 deg) of the texture's decoded normal instead of cos(80 deg). With
// glTF TANGENT and with tangents generated at load; renderer and path tracer.
TEST_F(GLTest, NormalMappedWallAtGrazingLightFollowsTheMappedNormal) {
    // The texel as stored (tools/gen_test_assets.py): round((n * 0.5 + 0.5) * 255) of (sin 30, 0, cos 30).
    const glm::dvec3 stored(std::round((0.5 * 0.5 + 0.5) * 255), std::round(0.5 * 255), std::round((std::cos(kPi / 6) * 0.5 + 0.5) * 255));
    const glm::dvec3 nMapped = glm::normalize(stored / 255.0 * 2.0 - 1.0);  // tangent (1,0,0), bitangent (0,1,0)
    const glm::dvec3 l(std::sin(80.0 * kPi / 180.0), 0.0, std::cos(80.0 * kPi / 180.0));
    const double want = 0.8 / kPi * 3.0 * glm::dot(nMapped, l), flat = 0.8 / kPi * 3.0 * l.z;
    ASSERT_GT(want, 3.0 * flat);
    for (const char* file : {"normal_wall.gltf", "normal_wall_generated.gltf"}) {
        auto s = std::make_shared<Scene>(loadGltf(std::string(DEEPGI_ASSET_DIR) + "/test/materials/" + file));
        EXPECT_TRUE(s->warnings.empty()) << file << ": " << (s->warnings.empty() ? "" : s->warnings[0]);
        auto r = rendererFor(s, 48, 36, "front");
        Settings st;
        st.indirect = false;
        st.diffuseOnly = true;  // Lambertian: the normal alone decides
        r->render(st);
        const FloatImage img = r->readFinalRadiance();
        EXPECT_NEAR(img.at(24, 18, 1), want, 0.03 * want) << file << " (flat normal would give " << flat << ")";
        ReferenceOptions o;
        o.width = 12;
        o.height = 9;
        o.spp = 4;
        o.maxBounces = 0;
        o.progress = false;
        const ReferenceResult ref = renderReference(*s, selectCamera(*s, "front"), st, o);
        EXPECT_NEAR(ref.final.at(6, 4, 1), want, 0.01 * want) << file << " (path tracer)";
    }
}

// The occlusion texture darkens indirect light only: direct light is unchanged, the floor's indirect part scales
// by the texel's value.
TEST_F(GLTest, OcclusionTextureDarkensOnlyIndirectLight) {
    auto build = [](bool occluded) {
        auto s = cornellScene();
        Image img;
        img.name = "occlusion";
        img.width = img.height = 1;
        img.rgba8 = {128, 128, 128, 255};
        s->images.push_back(img);
        Texture t;
        t.image = 0;
        t.srgb = false;
        s->textures.push_back(t);
        if (occluded)
            for (auto& m : s->materials) m.occlusionTexture = 0;
        return s;
    };
    FloatImage final[2], direct[2];
    for (int k = 0; k < 2; ++k) {
        auto s = build(k == 1);
        auto r = rendererFor(s, 64, 48, "front");
        Settings st;
        for (int i = 0; i < 12; ++i) r->render(st);
        final[k] = r->readFinalRadiance();
        st.indirect = false;
        r->render(st);
        direct[k] = r->readFinalRadiance();
    }
    double d0 = 0, d1 = 0, i0 = 0, i1 = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            d0 += luminance(direct[0], x, y);
            d1 += luminance(direct[1], x, y);
            i0 += luminance(final[0], x, y) - luminance(direct[0], x, y);
            i1 += luminance(final[1], x, y) - luminance(direct[1], x, y);
        }
    EXPECT_NEAR(d1, d0, 1e-4 * d0);
    ASSERT_GT(i0, 0.0);
    // 128/255 darkens the indirect light of every surface (and so the light they pass on): at most that factor.
    EXPECT_LT(i1 / i0, 128.0 / 255.0 + 0.02);
    EXPECT_GT(i1 / i0, 0.15);
}

// One warning per unsupported material extension per file, naming it and the first material using it; the core
// model's textures warn nothing.
TEST(GltfMaterialWarnings, EachIgnoredExtensionWarnsOncePerFile) {
    const std::string path = writeTemp("ext_materials.gltf", R"({
 "asset": {"version": "2.0"},
 "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_emissive_strength"],
 "materials": [
  {"name": "a", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}}},
  {"name": "b", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.5}, "KHR_materials_sheen": {}}},
  {"name": "c", "pbrMetallicRoughness": {"metallicFactor": 0.25, "roughnessFactor": 0.5},
   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}}],
 "scenes": [{"nodes": []}], "scene": 0})");
    const Scene s = loadGltf(path);
    std::vector<std::string> mine;
    for (const auto& w : s.warnings) {
        EXPECT_EQ(w.find("ignoring unsupported"), std::string::npos) << w;
        if (w.find("which deepgi ignores") != std::string::npos) mine.push_back(w);
    }
    ASSERT_EQ(mine.size(), 2u);
    EXPECT_EQ(mine[0], "ext_materials.gltf: material 'a' uses KHR_materials_clearcoat, which deepgi ignores");
    EXPECT_EQ(mine[1], "ext_materials.gltf: material 'b' uses KHR_materials_sheen, which deepgi ignores");
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_FLOAT_EQ(s.materials[0].metallic, 1.0f);  // glTF's default
    EXPECT_FLOAT_EQ(s.materials[2].metallic, 0.25f);
    EXPECT_FLOAT_EQ(s.materials[2].roughness, 0.5f);
    EXPECT_FLOAT_EQ(s.materials[2].dielectricF0, 0.04f);
}

// The public asset for the whole core model (../shared/scenes/DamagedHelmet, CC BY 4.0): metallic-roughness,
// normal, occlusion and emissive textures load without a warning, data textures linear, colour ones sRGB,
// every normal-mapped vertex has a unit tangent perpendicular to its normal, and it renders finite with Specular.
TEST_F(GLTest, DamagedHelmetLoadsItsWholeMaterial) {
    const std::string file = std::string(DEEPGI_SHARED_SCENES) + "/DamagedHelmet/glTF-Binary/DamagedHelmet.glb";
    if (!std::ifstream(file)) GTEST_SKIP() << file << " not present";
    auto s = std::make_shared<Scene>(loadGltf(file));
    for (const auto& w : s->warnings) ADD_FAILURE() << "unexpected warning: " << w;
    ASSERT_EQ(s->materials.size(), 1u);
    const Material& m = s->materials[0];
    ASSERT_GE(m.metallicRoughnessTexture, 0);
    ASSERT_GE(m.normalTexture, 0);
    ASSERT_GE(m.occlusionTexture, 0);
    ASSERT_GE(m.baseColorTexture, 0);
    EXPECT_FALSE(s->textures[size_t(m.metallicRoughnessTexture)].srgb);
    EXPECT_FALSE(s->textures[size_t(m.normalTexture)].srgb);
    EXPECT_FALSE(s->textures[size_t(m.occlusionTexture)].srgb);
    EXPECT_TRUE(s->textures[size_t(m.baseColorTexture)].srgb);
    double worstDot = 0.0, worstLen = 0.0;
    for (const auto& p : s->parts)
        for (const auto& v : p.vertices) {
            const glm::vec3 t(v.tangent);
            worstDot = std::max(worstDot, double(std::abs(glm::dot(t, v.normal))));
            worstLen = std::max(worstLen, double(std::abs(glm::length(t) - 1.0f)));
            EXPECT_EQ(std::abs(v.tangent.w), 1.0f);
        }
    EXPECT_LT(worstDot, 0.05);  // generated: Gram-Schmidt exact; a file's TANGENT may be off by its quantization
    EXPECT_LT(worstLen, 1e-3);
    auto r = rendererFor(s, 64, 48, "");
    r->render(Settings{});
    EXPECT_TRUE(r->textures().has("Specular"));
    EXPECT_TRUE(r->textures().has("Occlusion"));
    for (const auto& name : r->textures().layerNames()) EXPECT_TRUE(allFinite(r->readLayer(name))) << name;
}
