// Bad input end to end (issue 5, docs/ROBUSTNESS.md). The loader's own bad-input tests (truncated .glb, invalid
// JSON, accessors out of range, wrong component types, overflowing counts, missing/escaping buffers, Draco,
// missing/corrupt/escaping/huge images, deep nesting) are in test_gltf_loader.cpp; here: what the renderer and
// the deepgi binary make of a scene whose images are missing, corrupt, embedded or lying about their size.
#include "gl_fixture.h"

#include "renderer/core/camera.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/gltf_loader.h"
#include "renderer/scene/lighting.h"
#include "renderer/scene/scene_validation.h"

#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <unistd.h>

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace deepgi;
using namespace deepgi::test;

namespace {

std::string base64(const std::vector<uint8_t>& d) {
    static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < d.size(); i += 3) {
        uint32_t v = uint32_t(d[i]) << 16;
        if (i + 1 < d.size()) v |= uint32_t(d[i + 1]) << 8;
        if (i + 2 < d.size()) v |= d[i + 2];
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += i + 1 < d.size() ? tbl[(v >> 6) & 63] : '=';
        out += i + 2 < d.size() ? tbl[v & 63] : '=';
    }
    return out;
}

std::vector<uint8_t> png1x1(uint8_t r, uint8_t g, uint8_t b) {
    std::vector<uint8_t> out;
    const uint8_t px[3] = {r, g, b};
    stbi_write_png_to_func([](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<uint8_t>*>(ctx);
        v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    }, &out, 1, 1, 3, px, 3);
    return out;
}

// A quad facing +Z at z = -2 (covering the view of a camera at the origin), textured with `imageUri`, base colour
// factor (0.2, 0.4, 0.6), a camera "cam" and a sun; written as <dir>/<name>.
fs::path writeTexturedQuad(const fs::path& dir, const std::string& name, const std::string& imageUri) {
    const std::vector<float> pos = {-4, -4, -2, 4, -4, -2, 4, 4, -2, -4, 4, -2};
    const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    const std::vector<uint16_t> idx = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> bin(reinterpret_cast<const uint8_t*>(pos.data()), reinterpret_cast<const uint8_t*>(pos.data()) + 48);
    bin.insert(bin.end(), reinterpret_cast<const uint8_t*>(uv.data()), reinterpret_cast<const uint8_t*>(uv.data()) + 32);
    bin.insert(bin.end(), reinterpret_cast<const uint8_t*>(idx.data()), reinterpret_cast<const uint8_t*>(idx.data()) + 12);
    json j;
    j["asset"] = {{"version", "2.0"}};
    j["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    j["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                        {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}};
    j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 4},
                       {"min", {-4, -4, -2}}, {"max", {4, 4, -2}}},
                      {{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC2"}, {"count", 4}},
                      {{"bufferView", 2}, {"componentType", 5123}, {"type", "SCALAR"}, {"count", 6}}};
    j["images"] = {{{"uri", imageUri}}};
    j["textures"] = {{{"source", 0}}};
    // A dielectric (glTF's default metallicFactor is 1: a metal has no diffuse albedo).
    j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1.0}}, {"metallicFactor", 0.0},
                                                 {"baseColorTexture", {{"index", 0}}}}}}};
    j["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}};
    j["cameras"] = {{{"type", "perspective"}, {"name", "cam"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    j["nodes"] = {{{"mesh", 0}}, {{"camera", 0}}};
    j["scenes"] = {{{"nodes", {0, 1}}}};
    j["scene"] = 0;
    const fs::path p = dir / name;
    std::ofstream(p) << j.dump(1);
    return p;
}

class BadInput : public GLTest {
protected:
    fs::path dir;
    void SetUp() override {
        GLTest::SetUp();
        dir = fs::temp_directory_path() / ("deepgi_badinput_" + std::to_string(getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir / "scene");
        dir /= "scene";
    }
    void TearDown() override {
        fs::remove_all(dir.parent_path());
        GLTest::TearDown();
    }

    // Loads and renders the scene; returns the albedo at the centre of layer 1 (after checking every buffer).
    glm::vec3 renderCentreAlbedo(const Scene& loaded) {
        auto scene = std::make_shared<Scene>(loaded);
        auto renderer = rendererFor(scene, 32, 32, "cam");
        Renderer& r = *renderer;
        for (int i = 0; i < 3; ++i) r.render(Settings{});
        for (const auto& name : r.textures().layerNames()) EXPECT_TRUE(allFinite(r.readLayer(name))) << name;
        EXPECT_GT(meanChannel(r.readFinalRadiance(), 1), 0.0) << "lit by the default sun";
        FloatImage a = r.readLayer("Albedo 1");
        return {a.at(16, 16, 0), a.at(16, 16, 1), a.at(16, 16, 2)};
    }
};

bool hasWarning(const Scene& s, const std::string& a, const std::string& b = "") {
    for (const auto& w : s.warnings)
        if (w.find(a) != std::string::npos && (b.empty() || w.find(b) != std::string::npos)) return true;
    return false;
}

void expectColour(const glm::vec3& got, const glm::vec3& want, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1.0f / 255.0f) << what << " channel " << c;
}

}  // namespace

// A missing and a corrupt image: the scene loads with a warning naming the image, renders finite, and the surface
// shows the fallback colour (the base colour factor alone, 0.2 0.4 0.6) in the albedo buffer.
TEST_F(BadInput, MissingOrCorruptImageRendersWithFallbackColour) {
    std::ofstream(dir / "corrupt.png", std::ios::binary) << std::string("\x89PNG\r\n\x1a\nnot really a png", 24);
    for (const std::string uri : {"missing.png", "corrupt.png"}) {
        const Scene s = loadGltf(writeTexturedQuad(dir, "quad.gltf", uri).string());
        EXPECT_TRUE(hasWarning(s, uri)) << uri;
        EXPECT_EQ(s.materials.at(0).baseColorTexture, -1) << uri;
        expectColour(renderCentreAlbedo(s), {0.2f, 0.4f, 0.6f}, uri);
    }
}

// A data: URI image works: a 1x1 PNG (255, 128, 0) multiplies the factor: albedo = factor * sRGB-decoded texel.
TEST_F(BadInput, DataUriImageRenders) {
    const Scene s = loadGltf(writeTexturedQuad(dir, "quad.gltf", "data:image/png;base64," + base64(png1x1(255, 128, 0))).string());
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.images.size(), 1u);
    const float g = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
    expectColour(renderCentreAlbedo(s), {0.2f, 0.4f * g, 0.0f}, "data: PNG");
}

// A PNG whose header claims 100000 x 100000 pixels (the IHDR of a real 1x1 PNG patched; the pixel data is tiny) is
// refused before allocation (stbi_info fails on its header check, nothing is decoded) with a warning naming the
// image; the message says "corrupt or in an unsupported format", not "too large" (stb_image's last failure reason
// is that of the last format it tried). The loader's own pixel limit, for headers stb does accept, is tested in
// GltfLoader.BadImagesFallBackToFactorColour. The scene renders with the fallback colour. As a data: URI and as a file; an image URI escaping the scene folder is refused the same way.
TEST_F(BadInput, ImageClaimingEnormousSizeOrEscapingIsRefused) {
    std::vector<uint8_t> png = png1x1(10, 20, 30);
    for (int k : {16, 20}) {  // IHDR width and height, big-endian
        png[size_t(k)] = 0x00; png[size_t(k) + 1] = 0x01; png[size_t(k) + 2] = 0x86; png[size_t(k) + 3] = 0xA0;  // 100000
    }
    std::ofstream(dir / "huge.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    const std::vector<uint8_t> ok = png1x1(10, 20, 30);
    std::ofstream(dir.parent_path() / "outside.png", std::ios::binary).write(reinterpret_cast<const char*>(ok.data()), std::streamsize(ok.size()));
    for (const std::string uri : {"data:image/png;base64," + base64(png), std::string("huge.png"), std::string("../outside.png")}) {
        const Scene s = loadGltf(writeTexturedQuad(dir, "quad.gltf", uri).string());
        const bool escape = uri[0] == '.';
        EXPECT_TRUE(hasWarning(s, escape ? "../outside.png" : "corrupt or in an unsupported format", escape ? "escapes" : "")) << uri << ": " << (s.warnings.empty() ? "" : s.warnings.front());
        EXPECT_TRUE(s.images.empty()) << uri;
        expectColour(renderCentreAlbedo(s), {0.2f, 0.4f, 0.6f}, uri.substr(0, 20));
    }
}

// Through the deepgi binary: a scene with a missing image renders (exit 0, final.png written) and the warning
// naming the image is printed.
TEST_F(BadInput, CliRendersMissingImageWithAWarning) {
    const fs::path scene = writeTexturedQuad(dir, "quad.gltf", "missing_texture.png");
    const std::string cmd = std::string(DEEPGI_BINARY) + " render " + scene.string() + " --size 16x16 --frames 2 --out " +
                            (dir / "out").string() + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string output;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) output.append(buf, n);
    const int st = pclose(p);
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << output;
    EXPECT_NE(output.find("missing_texture.png"), std::string::npos) << output;
    EXPECT_NE(output.find("warning"), std::string::npos) << output;
    EXPECT_TRUE(fs::exists(dir / "out" / "final.png"));
}

// ---------------------------------------------------------------- renderer and path tracer agree (issue 11)
namespace {
ReferenceOptions tinyReference() {
    ReferenceOptions o;
    o.width = 16;
    o.height = 16;
    o.spp = 4;
    o.maxBounces = 0;
    o.threads = 1;
    o.progress = false;
    return o;
}
// Rewrites the quad scene's JSON through `edit`.
fs::path editQuad(const fs::path& dir, const std::string& name, const std::function<void(json&)>& edit) {
    const fs::path p = writeTexturedQuad(dir, name, "missing.png");
    json j = json::parse(std::ifstream(p));
    edit(j);
    std::ofstream(p) << j.dump(1);
    return p;
}
}  // namespace

// crash: `reference` aborted inside Embree (ray.valid()) on a camera whose world transform is degenerate, while
// `render` drew black. The shared validation skips such a camera with one warning: both render the scene through
// the framing camera. A degenerate runtime Camera is an exception in the path tracer, never an abort.
TEST_F(BadInput, DegenerateCameraNeitherAbortsNorDrawsBlack) {
    for (const std::string& kind : {"scale0", "far"}) {
        const fs::path p = editQuad(dir, kind + ".gltf", [&](json& j) {
            if (kind == "scale0") j["nodes"][1]["scale"] = {0, 0, 0};
            else j["nodes"][1]["translation"] = {1e38, 0, 0};
        });
        auto scene = std::make_shared<Scene>(loadGltf(p.string()));
        EXPECT_TRUE(scene->cameras.empty()) << kind;
        EXPECT_TRUE(hasWarning(*scene, "camera 'cam'", "skipped")) << kind;
        auto renderer = rendererFor(scene, 16, 16, "");
        for (int i = 0; i < 2; ++i) renderer->render(Settings{});
        EXPECT_GT(meanChannel(renderer->readFinalRadiance(), 1), 0.0) << kind << ": renderer not black";
        const ReferenceResult ref = renderReference(*scene, selectCamera(*scene, ""), Settings{}, tinyReference());
        EXPECT_GT(meanChannel(ref.final, 1), 0.0) << kind << ": reference not black";
    }
    Scene scene = loadGltf(writeTexturedQuad(dir, "ok.gltf", "missing.png").string());
    Camera zero = selectCamera(scene, "cam");
    zero.cameraToWorld = glm::mat4(0.0f);
    EXPECT_THROW(renderReference(scene, zero, Settings{}, tinyReference()), std::invalid_argument);
    Camera far = selectCamera(scene, "cam");
    far.cameraToWorld[3] = glm::vec4(1e38f, 0.0f, 0.0f, 1.0f);
    EXPECT_THROW(renderReference(scene, far, Settings{}, tinyReference()), std::invalid_argument);
}

// silent wrong: znear beyond the geometry clipped it in `render` (black) while `reference` showed the scene; the
// path tracer's camera rays now start at the near plane, so both show the background; with a near plane in front
// of the quad both show it lit.
TEST_F(BadInput, NearPlaneMeansTheSameInBothRenderers) {
    for (double znear : {3.0, 0.1}) {  // the quad is 2 units in front of the camera
        const fs::path p = editQuad(dir, "near.gltf", [&](json& j) { j["cameras"][0]["perspective"]["znear"] = znear; });
        auto scene = std::make_shared<Scene>(loadGltf(p.string()));
        auto renderer = rendererFor(scene, 16, 16, "cam");
        for (int i = 0; i < 2; ++i) renderer->render(Settings{});
        const double gl = meanChannel(renderer->readFinalRadiance(), 1, 4, 4, 12, 12);
        const ReferenceResult ref = renderReference(*scene, selectCamera(*scene, "cam"), Settings{}, tinyReference());
        const double pt = meanChannel(ref.final, 1, 4, 4, 12, 12);
        if (znear > 2.0) {
            EXPECT_EQ(gl, 0.0) << "renderer clips the quad";
            EXPECT_EQ(pt, 0.0) << "reference clips the quad";
        } else {
            EXPECT_GT(gl, 0.0);
            EXPECT_GT(pt, 0.0);
            EXPECT_NEAR(pt, gl, 0.05 * gl) << "directly lit quad, no bounces";
        }
    }
}

// silent wrong: baseColorFactor above 1 was clamped by the renderer (RGBA8 albedo) but not by the path tracer. The
// loader clamps it with a warning; a scene built in code is clamped by the path tracer's shading the same way.
TEST_F(BadInput, BaseColorFactorAboveOneMeansOneInBothRenderers) {
    const fs::path p = editQuad(dir, "bright.gltf", [](json& j) {
        j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {3.0, 3.0, 3.0, 1.0};
    });
    Scene loaded = loadGltf(p.string());
    EXPECT_TRUE(hasWarning(loaded, "baseColorFactor", "clamped"));
    EXPECT_FLOAT_EQ(loaded.materials[0].baseColorFactor.x, 1.0f);
    Scene inCode = loaded;
    inCode.materials[0].baseColorFactor = glm::vec4(3.0f, 3.0f, 3.0f, 1.0f);  // bypasses the loader
    const Camera cam = selectCamera(loaded, "cam");
    const ReferenceResult a = renderReference(loaded, cam, Settings{}, tinyReference());
    const ReferenceResult b = renderReference(inCode, cam, Settings{}, tinyReference());
    EXPECT_GT(meanChannel(a.final, 0), 0.0);
    EXPECT_EQ(a.final.pixels, b.final.pixels);
}

// silent wrong: a spot light with inner cone > outer cone differed by 41 % between the renderers. Loader and
// effectiveLights (which both renderers use) apply the same correction: the angles are swapped.
TEST(SharedValidation, InvertedSpotConesAreSwappedForBothRenderers) {
    Scene s;
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0, 2, 0);
    spot.direction = glm::vec3(0, -2, 0);  // not unit: normalised by the validation
    spot.innerConeAngle = 0.7f;
    spot.outerConeAngle = 0.3f;
    s.lights.push_back(spot);
    Light bad = spot;
    bad.name = "nan";
    bad.intensity = std::numeric_limits<float>::quiet_NaN();
    s.lights.push_back(bad);
    const std::vector<Light> lights = effectiveLights(s, Settings{});
    ASSERT_EQ(lights.size(), 1u) << "the NaN light is refused";
    EXPECT_FLOAT_EQ(lights[0].innerConeAngle, 0.3f);
    EXPECT_FLOAT_EQ(lights[0].outerConeAngle, 0.7f);
    EXPECT_FLOAT_EQ(glm::length(lights[0].direction), 1.0f);
    std::vector<std::string> warnings;
    Light again = spot;
    EXPECT_TRUE(validateLight(again, &warnings));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("swapped"), std::string::npos);
    EXPECT_EQ(again.innerConeAngle, lights[0].innerConeAngle);
    EXPECT_EQ(again.outerConeAngle, lights[0].outerConeAngle);
}
