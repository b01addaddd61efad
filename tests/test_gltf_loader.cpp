// glTF loader tests: small glTF files are written by the tests themselves (JSON built with nlohmann, buffers as
// base64 data URIs, .bin files or a GLB BIN chunk), then loaded and checked value by value.
#include "renderer/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;
using deepgi::GltfLoadOptions;
using deepgi::loadGltf;
using deepgi::Scene;
using deepgi::SceneLoadError;
using json = nlohmann::json;

namespace {

constexpr int kUByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;

std::string base64(const std::vector<uint8_t>& d) {
    static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < d.size(); i += 3) {
        uint32_t v = (uint32_t(d[i]) << 16) | (uint32_t(d[i + 1]) << 8) | d[i + 2];
        for (int k = 3; k >= 0; --k) out += tbl[(v >> (6 * k)) & 63];
    }
    if (i + 1 == d.size()) {
        uint32_t v = uint32_t(d[i]) << 16;
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == d.size()) {
        uint32_t v = (uint32_t(d[i]) << 16) | (uint32_t(d[i + 1]) << 8);
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += tbl[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

void writeFile(const fs::path& p, const std::string& bytes) {
    std::ofstream f(p, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}
void writeFile(const fs::path& p, const std::vector<uint8_t>& bytes) {
    writeFile(p, std::string(bytes.begin(), bytes.end()));
}

std::vector<uint8_t> ppm(int w, int h, const std::vector<uint8_t>& rgb) {
    std::string head = "P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
    std::vector<uint8_t> out(head.begin(), head.end());
    out.insert(out.end(), rgb.begin(), rgb.end());
    return out;
}
std::vector<uint8_t> pgm(int w, int h, const std::vector<uint8_t>& grey) {
    std::string head = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
    std::vector<uint8_t> out(head.begin(), head.end());
    out.insert(out.end(), grey.begin(), grey.end());
    return out;
}

// A real PNG (through stb_image_write) with `channels` channels.
std::vector<uint8_t> png(int w, int h, int channels, const std::vector<uint8_t>& pixels) {
    std::vector<uint8_t> out;
    auto sink = [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<uint8_t>*>(ctx);
        v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    stbi_write_png_to_func(sink, &out, w, h, channels, pixels.data(), w * channels);
    return out;
}

// Builds a glTF document with one binary buffer.
struct Builder {
    json j;
    std::vector<uint8_t> bin;

    Builder() {
        j["asset"] = {{"version", "2.0"}};
        j["buffers"] = json::array();
        j["bufferViews"] = json::array();
        j["accessors"] = json::array();
    }

    int addView(const void* data, size_t bytes) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t off = bin.size();
        bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + bytes);
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", off}, {"byteLength", bytes}});
        return int(j["bufferViews"].size()) - 1;
    }
    int addAccessor(const void* data, size_t bytes, int componentType, const std::string& type, size_t count,
                    bool normalized = false) {
        const int view = addView(data, bytes);
        json a = {{"bufferView", view}, {"componentType", componentType}, {"type", type}, {"count", count}};
        if (normalized) a["normalized"] = true;
        j["accessors"].push_back(a);
        return int(j["accessors"].size()) - 1;
    }
    int vec3(const std::vector<float>& v) { return addAccessor(v.data(), v.size() * 4, kFloat, "VEC3", v.size() / 3); }
    int vec2(const std::vector<float>& v) { return addAccessor(v.data(), v.size() * 4, kFloat, "VEC2", v.size() / 2); }
    int indices32(const std::vector<uint32_t>& v) { return addAccessor(v.data(), v.size() * 4, kUInt, "SCALAR", v.size()); }
    int indices16(const std::vector<uint16_t>& v) { return addAccessor(v.data(), v.size() * 2, kUShort, "SCALAR", v.size()); }
    int indices8(const std::vector<uint8_t>& v) { return addAccessor(v.data(), v.size(), kUByte, "SCALAR", v.size()); }

    // One mesh with one primitive; returns the mesh index.
    int mesh(json attributes, int indices = -1, int material = -1, int mode = -1) {
        json prim = {{"attributes", attributes}};
        if (indices >= 0) prim["indices"] = indices;
        if (material >= 0) prim["material"] = material;
        if (mode >= 0) prim["mode"] = mode;
        j["meshes"].push_back({{"primitives", json::array({prim})}});
        return int(j["meshes"].size()) - 1;
    }
    int node(json n) {
        j["nodes"].push_back(n);
        return int(j["nodes"].size()) - 1;
    }
    void scene(std::vector<int> roots) { j["scenes"] = json::array({{{"nodes", roots}}}); j["scene"] = 0; }

    void finishBuffer(const std::string& uri) {
        while (bin.size() % 4) bin.push_back(0);
        json b = {{"byteLength", bin.size()}};
        if (!uri.empty()) b["uri"] = uri;
        j["buffers"] = json::array({b});
        if (bin.empty()) { j.erase("buffers"); }
    }

    // .gltf with the buffer embedded as a data URI
    fs::path writeGltf(const fs::path& dir, const std::string& name) {
        while (bin.size() % 4) bin.push_back(0);
        finishBuffer(bin.empty() ? "" : "data:application/octet-stream;base64," + base64(bin));
        fs::path p = dir / name;
        writeFile(p, j.dump(1));
        return p;
    }
    // .gltf + external .bin
    fs::path writeGltfBin(const fs::path& dir, const std::string& name, const std::string& binName) {
        finishBuffer(binName);
        writeFile(dir / binName, bin);
        fs::path p = dir / name;
        writeFile(p, j.dump(1));
        return p;
    }
    std::vector<uint8_t> glbBytes() {
        finishBuffer("");
        std::string js = j.dump();
        while (js.size() % 4) js += ' ';
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) { for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k))); };
        const uint32_t total = uint32_t(12 + 8 + js.size() + (bin.empty() ? 0 : 8 + bin.size()));
        out.insert(out.end(), {'g', 'l', 'T', 'F'});
        u32(2);
        u32(total);
        u32(uint32_t(js.size()));
        u32(0x4E4F534Au);
        out.insert(out.end(), js.begin(), js.end());
        if (!bin.empty()) {
            u32(uint32_t(bin.size()));
            u32(0x004E4942u);
            out.insert(out.end(), bin.begin(), bin.end());
        }
        return out;
    }
    fs::path writeGlb(const fs::path& dir, const std::string& name) {
        fs::path p = dir / name;
        writeFile(p, glbBytes());
        return p;
    }
};

// A unit right triangle in the XY plane, CCW seen from +Z, normals +Z.
const std::vector<float> kTriPos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
const std::vector<float> kTriNrm = {0, 0, 1, 0, 0, 1, 0, 0, 1};

class GltfLoader : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("deepgi_gltf_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir);
        fs::create_directories(dir / "scene");
        dir = dir / "scene";  // files live one level down, so "../x" escapes into a real folder
    }
    void TearDown() override { fs::remove_all(dir.parent_path()); }

    // Loads `p`, expecting a SceneLoadError whose message names the file and contains `word`.
    void expectError(const fs::path& p, const std::string& word, const GltfLoadOptions& opt = {}) {
        try {
            Scene s = loadGltf(p.string(), opt);
            ADD_FAILURE() << "expected an error containing '" << word << "' for " << p;
        } catch (const SceneLoadError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(p.filename().string()), std::string::npos) << msg;
            EXPECT_EQ(msg.rfind(p.string() + ": ", 0), 0u) << msg;
            EXPECT_NE(msg.find(word), std::string::npos) << "missing '" << word << "' in: " << msg;
        }
    }
};

bool hasWarning(const Scene& s, const std::string& a, const std::string& b = "") {
    for (const auto& w : s.warnings)
        if (w.find(a) != std::string::npos && (b.empty() || w.find(b) != std::string::npos)) return true;
    return false;
}

std::string allWarnings(const Scene& s) {
    std::string out;
    for (const auto& w : s.warnings) out += w + "\n";
    return out;
}

void expectVec3(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// Every triangle's CCW geometric normal agrees with its vertex normals.
void expectCcwMatchesNormals(const deepgi::MeshPart& part) {
    for (size_t t = 0; t + 2 < part.indices.size(); t += 3) {
        const auto& a = part.vertices[part.indices[t]];
        const auto& b = part.vertices[part.indices[t + 1]];
        const auto& c = part.vertices[part.indices[t + 2]];
        const glm::vec3 g = glm::cross(b.position - a.position, c.position - a.position);
        EXPECT_GT(glm::dot(g, a.normal + b.normal + c.normal), 0.0f) << "triangle " << t / 3;
    }
}

}  // namespace

// ---------------------------------------------------------------- geometry and transforms

TEST_F(GltfLoader, HierarchyFlattensToWorldSpace) {
    Builder b;
    const int m = b.mesh({{"POSITION", b.vec3(kTriPos)}, {"NORMAL", b.vec3(kTriNrm)}});
    // child: rotate +90 degrees about Y, uniform scale 2; parent: translate (10,0,0)
    const float s = std::sqrt(0.5f);
    const int child = b.node({{"mesh", m}, {"rotation", {0, s, 0, s}}, {"scale", {2, 2, 2}}});
    const int parent = b.node({{"translation", {10, 0, 0}}, {"children", {child}}});
    b.scene({parent});
    const fs::path p = b.writeGltf(dir, "hier.gltf");
    Scene sc = loadGltf(p.string());
    EXPECT_EQ(sc.sourcePath, p.string());
    ASSERT_EQ(sc.parts.size(), 1u);
    const auto& part = sc.parts[0];
    ASSERT_EQ(part.vertices.size(), 3u);
    ASSERT_EQ(part.indices, (std::vector<uint32_t>{0, 1, 2}));
    // R_y(90): x -> -z, z -> +x
    expectVec3(part.vertices[0].position, {10, 0, 0});
    expectVec3(part.vertices[1].position, {10, 0, -2});
    expectVec3(part.vertices[2].position, {10, 2, 0});
    for (const auto& v : part.vertices) expectVec3(v.normal, {1, 0, 0});
    expectCcwMatchesNormals(part);
    ASSERT_TRUE(sc.bounds.valid());
    expectVec3(sc.bounds.lo, {10, 0, -2});
    expectVec3(sc.bounds.hi, {10, 2, 0});
    EXPECT_EQ(sc.triangleCount(), 1u);
}

TEST_F(GltfLoader, MatrixNodeNonUniformScaleUsesInverseTranspose) {
    Builder b;
    const float r = std::sqrt(0.5f);
    const int m = b.mesh({{"POSITION", b.vec3(kTriPos)}, {"NORMAL", b.vec3({r, r, 0, r, r, 0, r, r, 0})}});
    // column-major: scale (2,1,1), translate (0,0,5)
    const int n = b.node({{"mesh", m}, {"matrix", {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}});
    b.scene({n});
    Scene sc = loadGltf(b.writeGlb(dir, "matrix.glb").string());
    ASSERT_EQ(sc.parts.size(), 1u);
    const auto& v = sc.parts[0].vertices;
    expectVec3(v[1].position, {2, 0, 5});
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));
    for (const auto& x : v) {
        expectVec3(x.normal, expected);
        EXPECT_NEAR(glm::length(x.normal), 1.0f, 1e-5f);
    }
}

TEST_F(GltfLoader, NegativeScaleKeepsCounterClockwiseFrontFaces) {
    Builder b;
    const int m = b.mesh({{"POSITION", b.vec3(kTriPos)}, {"NORMAL", b.vec3(kTriNrm)}});
    const int n = b.node({{"mesh", m}, {"scale", {1, 1, -1}}, {"translation", {0, 0, 3}}});
    const int n2 = b.node({{"mesh", m}, {"scale", {-1, 1, 1}}});
    b.scene({n, n2});
    Scene sc = loadGltf(b.writeGltf(dir, "mirror.gltf").string());
    ASSERT_EQ(sc.parts.size(), 2u);
    for (const auto& v : sc.parts[0].vertices) expectVec3(v.normal, {0, 0, -1});
    for (const auto& v : sc.parts[1].vertices) expectVec3(v.normal, {0, 0, 1});  // x-mirror keeps a +z plane's normal
    expectCcwMatchesNormals(sc.parts[0]);
    expectCcwMatchesNormals(sc.parts[1]);
    // winding flipped: (0, 2, 1)
    expectVec3(sc.parts[0].vertices[sc.parts[0].indices[1]].position, {0, 1, 3});
}

TEST_F(GltfLoader, IndexedAndNonIndexedWithAllIndexTypes) {
    Builder b;
    const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<float> quadN = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const int pos = b.vec3(quad), nrm = b.vec3(quadN);
    const int m8 = b.mesh({{"POSITION", pos}, {"NORMAL", nrm}}, b.indices8({0, 1, 2, 0, 2, 3}));
    const int m16 = b.mesh({{"POSITION", pos}, {"NORMAL", nrm}}, b.indices16({0, 1, 2, 0, 2, 3}));
    const int m32 = b.mesh({{"POSITION", pos}, {"NORMAL", nrm}}, b.indices32({0, 1, 2, 0, 2, 3}));
    const std::vector<float> soup = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<float> soupN(18, 0.0f);
    std::vector<float> sn = soupN;
    for (int i = 0; i < 6; ++i) sn[i * 3 + 2] = 1.0f;
    const int mNone = b.mesh({{"POSITION", b.vec3(soup)}, {"NORMAL", b.vec3(sn)}});
    std::vector<int> roots;
    for (int m : {m8, m16, m32, mNone}) roots.push_back(b.node({{"mesh", m}}));
    b.scene(roots);
    Scene sc = loadGltf(b.writeGltfBin(dir, "idx.gltf", "idx.bin").string());
    ASSERT_EQ(sc.parts.size(), 4u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(sc.parts[i].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        ASSERT_EQ(sc.parts[i].vertices.size(), 4u);
        expectVec3(sc.parts[i].vertices[2].position, {1, 1, 0});
    }
    EXPECT_EQ(sc.parts[3].indices.size(), 6u);
    EXPECT_EQ(sc.parts[3].vertices.size(), 6u);
    expectVec3(sc.parts[3].vertices[sc.parts[3].indices[4]].position, {1, 1, 0});
    EXPECT_EQ(sc.triangleCount(), 8u);
    EXPECT_EQ(sc.parts[0].material, -1);
}

TEST_F(GltfLoader, GeneratesFlatNormalsWhereMissingOrInvalid) {
    Builder b;
    // Two triangles forming a tent: normals differ per face, so shared vertices must be split.
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1};
    const int mNo = b.mesh({{"POSITION", b.vec3(pos)}}, b.indices16({0, 1, 2, 0, 3, 1}));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const int mBad = b.mesh({{"POSITION", b.vec3(kTriPos)}, {"NORMAL", b.vec3({0, 0, 0, nan, 0, 0, 0, 1, 0})}});
    b.scene({b.node({{"mesh", mNo}}), b.node({{"mesh", mBad}})});
    Scene sc = loadGltf(b.writeGltf(dir, "flat.gltf").string());
    ASSERT_EQ(sc.parts.size(), 2u);
    const auto& p0 = sc.parts[0];
    EXPECT_EQ(p0.vertices.size(), 6u);
    for (int k = 0; k < 3; ++k) expectVec3(p0.vertices[p0.indices[k]].normal, {0, 0, 1});
    for (int k = 3; k < 6; ++k) expectVec3(p0.vertices[p0.indices[k]].normal, {0, -1, 0});
    expectCcwMatchesNormals(p0);
    const auto& p1 = sc.parts[1];
    expectVec3(p1.vertices[p1.indices[0]].normal, {0, 0, 1});  // zero-length -> face normal
    expectVec3(p1.vertices[p1.indices[1]].normal, {0, 0, 1});  // NaN -> face normal
    expectVec3(p1.vertices[p1.indices[2]].normal, {0, 1, 0});  // valid normal kept
}

TEST_F(GltfLoader, StripsAndFansConvertedOtherModesSkipped) {
    Builder b;
    const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};  // strip order
    const int pos = b.vec3(quad);
    const int strip = b.mesh({{"POSITION", pos}}, -1, -1, 5);
    const std::vector<float> fan = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const int fanM = b.mesh({{"POSITION", b.vec3(fan)}}, -1, -1, 6);
    const int lines = b.mesh({{"POSITION", pos}}, -1, -1, 1);
    b.scene({b.node({{"mesh", strip}}), b.node({{"mesh", fanM}}), b.node({{"mesh", lines}})});
    Scene sc = loadGltf(b.writeGltf(dir, "modes.gltf").string());
    ASSERT_EQ(sc.parts.size(), 2u);
    EXPECT_EQ(sc.triangleCount(), 4u);
    for (const auto& part : sc.parts)
        for (const auto& v : part.vertices) expectVec3(v.normal, {0, 0, 1});  // all triangles CCW from +z
    EXPECT_TRUE(hasWarning(sc, "mode 1")) << allWarnings(sc);
}

TEST_F(GltfLoader, TexcoordsFloatAndNormalized) {
    Builder b;
    const int pos = b.vec3(kTriPos);
    const int uvF = b.vec2({0.25f, 0.5f, 1, 0, 0, 1});
    const std::vector<uint8_t> u8 = {0, 255, 255, 0, 51, 102};
    const int uvB = b.addAccessor(u8.data(), u8.size(), kUByte, "VEC2", 3, true);
    const std::vector<uint16_t> u16 = {0, 65535, 65535, 0, 13107, 0};
    const int uvS = b.addAccessor(u16.data(), u16.size() * 2, kUShort, "VEC2", 3, true);
    std::vector<int> roots;
    for (int uv : {uvF, uvB, uvS}) roots.push_back(b.node({{"mesh", b.mesh({{"POSITION", pos}, {"TEXCOORD_0", uv}})}}));
    b.scene(roots);
    Scene sc = loadGltf(b.writeGltf(dir, "uv.gltf").string());
    ASSERT_EQ(sc.parts.size(), 3u);
    EXPECT_NEAR(sc.parts[0].vertices[0].uv.x, 0.25f, 1e-6f);
    EXPECT_NEAR(sc.parts[0].vertices[0].uv.y, 0.5f, 1e-6f);
    EXPECT_NEAR(sc.parts[1].vertices[0].uv.y, 1.0f, 1e-6f);
    EXPECT_NEAR(sc.parts[1].vertices[2].uv.x, 0.2f, 1e-6f);
    EXPECT_NEAR(sc.parts[1].vertices[2].uv.y, 0.4f, 1e-6f);
    EXPECT_NEAR(sc.parts[2].vertices[1].uv.x, 1.0f, 1e-6f);
    EXPECT_NEAR(sc.parts[2].vertices[2].uv.x, 0.2f, 1e-6f);
}

TEST_F(GltfLoader, NonFiniteVerticesSkippedWithWarning) {
    Builder b;
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, inf, 0, 0};
    const int m = b.mesh({{"POSITION", b.vec3(pos)}}, b.indices16({0, 1, 2, 0, 3, 1, 3, 2, 1}));
    b.scene({b.node({{"mesh", m}})});
    Scene sc = loadGltf(b.writeGltf(dir, "nan.gltf").string());
    EXPECT_EQ(sc.triangleCount(), 1u);
    EXPECT_TRUE(hasWarning(sc, "skipped 2 triangle")) << allWarnings(sc);
    ASSERT_TRUE(sc.bounds.valid());
    expectVec3(sc.bounds.hi, {1, 1, 0});
}

TEST_F(GltfLoader, EmptySceneLoads) {
    Builder b;
    b.scene({b.node({{"name", "empty"}})});
    Scene sc = loadGltf(b.writeGltf(dir, "empty.gltf").string());
    EXPECT_TRUE(sc.parts.empty());
    EXPECT_EQ(sc.triangleCount(), 0u);
    EXPECT_FALSE(sc.bounds.valid());
    Builder b2;
    Scene sc2 = loadGltf(b2.writeGlb(dir, "bare.glb").string());
    EXPECT_TRUE(sc2.parts.empty());
}

// ---------------------------------------------------------------- materials and textures

TEST_F(GltfLoader, MaterialsTexturesAndSamplers) {
    Builder b;
    // base colour: 2x1 RGB PPM in a buffer view; emissive: 1x1 grey PNG as a data URI
    const auto rgb = ppm(2, 1, {255, 0, 0, 0, 128, 255});
    const int view = b.addView(rgb.data(), rgb.size());
    b.j["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/x-portable-pixmap"}},
                                 {{"uri", "data:image/png;base64," + base64(png(1, 1, 1, {77}))}}});
    b.j["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33648}}});
    b.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 1}}});
    b.j["materials"] = json::array({
        {{"name", "painted"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}}, {"baseColorTexture", {{"index", 0}}}}},
         {"emissiveFactor", {1.0, 0.5, 0.0}},
         {"emissiveTexture", {{"index", 1}}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
         {"alphaMode", "MASK"},
         {"alphaCutoff", 0.3},
         {"doubleSided", true}},
        {{"name", "glass"}, {"alphaMode", "BLEND"}},
        {{"name", "plain"}}});
    b.j["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    b.j["extensionsRequired"] = {"KHR_materials_emissive_strength"};
    const int pos = b.vec3(kTriPos);
    std::vector<int> roots;
    for (int mat = 0; mat < 3; ++mat) roots.push_back(b.node({{"mesh", b.mesh({{"POSITION", pos}}, -1, mat)}}));
    b.scene(roots);
    Scene sc = loadGltf(b.writeGlb(dir, "mat.glb").string());
    ASSERT_EQ(sc.materials.size(), 3u);
    const auto& m = sc.materials[0];
    EXPECT_EQ(m.name, "painted");
    EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    EXPECT_EQ(m.emissiveFactor, glm::vec3(4.0f, 2.0f, 0.0f));
    EXPECT_EQ(m.alphaMode, deepgi::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
    EXPECT_TRUE(m.doubleSided);
    ASSERT_GE(m.baseColorTexture, 0);
    ASSERT_GE(m.emissiveTexture, 0);
    const auto& t = sc.textures[size_t(m.baseColorTexture)];
    EXPECT_EQ(t.wrapS, deepgi::WrapMode::ClampToEdge);
    EXPECT_EQ(t.wrapT, deepgi::WrapMode::MirroredRepeat);
    EXPECT_EQ(t.magFilter, deepgi::FilterMode::Nearest);
    EXPECT_FALSE(t.mipmaps);
    const auto& img = sc.images[size_t(t.image)];
    EXPECT_EQ(img.width, 2);
    EXPECT_EQ(img.height, 1);
    EXPECT_EQ(img.rgba8, (std::vector<uint8_t>{255, 0, 0, 255, 0, 128, 255, 255}));
    const auto& te = sc.textures[size_t(m.emissiveTexture)];
    EXPECT_EQ(te.wrapS, deepgi::WrapMode::Repeat);
    EXPECT_EQ(te.magFilter, deepgi::FilterMode::Linear);
    EXPECT_TRUE(te.mipmaps);
    EXPECT_EQ(sc.images[size_t(te.image)].rgba8, (std::vector<uint8_t>{77, 77, 77, 255}));
    EXPECT_EQ(sc.materials[1].alphaMode, deepgi::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(sc.materials[1].alphaCutoff, 0.5f);
    EXPECT_TRUE(hasWarning(sc, "glass", "BLEND")) << allWarnings(sc);
    EXPECT_EQ(sc.materials[2].alphaMode, deepgi::AlphaMode::Opaque);
    EXPECT_FALSE(sc.materials[2].doubleSided);
    EXPECT_EQ(sc.materials[2].baseColorTexture, -1);
    EXPECT_EQ(sc.parts[1].material, 1);
    EXPECT_TRUE(sc.hasEmission());
    EXPECT_TRUE(sc.hasMaskedMaterial());
}

TEST_F(GltfLoader, BadImagesFallBackToFactorColour) {
    Builder b;
    writeFile(dir / "corrupt.png", std::string("\x89PNG\r\n\x1a\nthis is not really a png"));
    writeFile(dir.parent_path() / "outside.ppm", ppm(1, 1, {1, 2, 3}));
    writeFile(dir / "huge.ppm", std::string("P6\n100000 100000\n255\n") + std::string(16, '\0'));
    writeFile(dir / "good.pgm", pgm(1, 1, {9}));
    const std::vector<std::string> uris = {"missing.png", "corrupt.png", "../outside.ppm", "huge.ppm", "good.pgm"};
    json images = json::array(), textures = json::array(), materials = json::array();
    for (size_t i = 0; i < uris.size(); ++i) {
        images.push_back({{"uri", uris[i]}});
        textures.push_back({{"source", i}});
        materials.push_back({{"name", "m" + std::to_string(i)},
                             {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 0.4, 1.0}},
                                                       {"baseColorTexture", {{"index", i}}}}}});
    }
    b.j["images"] = images;
    b.j["textures"] = textures;
    b.j["materials"] = materials;
    b.scene({b.node({{"mesh", b.mesh({{"POSITION", b.vec3(kTriPos)}}, -1, 0)}})});
    Scene sc = loadGltf(b.writeGltf(dir, "badimg.gltf").string());
    ASSERT_EQ(sc.materials.size(), 5u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(sc.materials[size_t(i)].baseColorTexture, -1) << uris[size_t(i)];
        EXPECT_EQ(sc.materials[size_t(i)].baseColorFactor, glm::vec4(0.2f, 0.3f, 0.4f, 1.0f));
        EXPECT_TRUE(hasWarning(sc, uris[size_t(i)])) << uris[size_t(i)] << "\n" << allWarnings(sc);
    }
    EXPECT_TRUE(hasWarning(sc, "../outside.ppm", "escapes")) << allWarnings(sc);
    EXPECT_TRUE(hasWarning(sc, "huge.ppm", "limit")) << allWarnings(sc);
    ASSERT_GE(sc.materials[4].baseColorTexture, 0);
    ASSERT_EQ(sc.images.size(), 1u);
    EXPECT_EQ(sc.images[0].rgba8, (std::vector<uint8_t>{9, 9, 9, 255}));
    EXPECT_EQ(sc.parts.size(), 1u);
}

// ---------------------------------------------------------------- lights and cameras

TEST_F(GltfLoader, PunctualLightsInWorldSpace) {
    Builder b;
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"]["KHR_lights_punctual"]["lights"] = json::array({
        {{"name", "sun"}, {"type", "directional"}, {"color", {1.0, 0.9, 0.8}}, {"intensity", 3.0}},
        {{"name", "bulb"}, {"type", "point"}, {"intensity", 50.0}, {"range", 12.0}},
        {{"type", "spot"}, {"intensity", 20.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}}});
    const float s = std::sqrt(0.5f);
    auto light = [](int i) { return json{{"KHR_lights_punctual", {{"light", i}}}}; };
    const int sun = b.node({{"rotation", {-s, 0, 0, s}}, {"extensions", light(0)}});  // -90 deg about X: -Z -> -Y
    const int bulb = b.node({{"translation", {1, 2, 3}}, {"extensions", light(1)}});
    const int spotChild = b.node({{"name", "spotNode"}, {"rotation", {0, s, 0, s}}, {"extensions", light(2)}});
    const int spotParent = b.node({{"translation", {0, 5, 0}}, {"children", {spotChild}}});
    b.scene({sun, bulb, spotParent});
    Scene sc = loadGltf(b.writeGltf(dir, "lights.gltf").string());
    ASSERT_EQ(sc.lights.size(), 3u);
    const auto& l0 = sc.lights[0];
    EXPECT_EQ(l0.name, "sun");
    EXPECT_EQ(l0.type, deepgi::LightType::Directional);
    expectVec3(l0.direction, {0, -1, 0});
    expectVec3(l0.color, {1.0f, 0.9f, 0.8f});
    EXPECT_FLOAT_EQ(l0.intensity, 3.0f);
    const auto& l1 = sc.lights[1];
    EXPECT_EQ(l1.type, deepgi::LightType::Point);
    expectVec3(l1.position, {1, 2, 3});
    EXPECT_FLOAT_EQ(l1.range, 12.0f);
    EXPECT_FLOAT_EQ(l1.intensity, 50.0f);
    const auto& l2 = sc.lights[2];
    EXPECT_EQ(l2.type, deepgi::LightType::Spot);
    EXPECT_EQ(l2.name, "spotNode");
    expectVec3(l2.position, {0, 5, 0});
    expectVec3(l2.direction, {-1, 0, 0});  // R_y(90): -Z -> -X
    EXPECT_FLOAT_EQ(l2.innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(l2.outerConeAngle, 0.5f);
    EXPECT_FLOAT_EQ(l2.range, 0.0f);
    EXPECT_TRUE(sc.hasLight(deepgi::LightType::Spot));
}

TEST_F(GltfLoader, CamerasNamedAndPlaced) {
    Builder b;
    b.j["cameras"] = json::array({
        {{"name", "front"}, {"type", "perspective"},
         {"perspective", {{"yfov", 0.6}, {"aspectRatio", 1.5}, {"znear", 0.1}, {"zfar", 100.0}}}},
        {{"type", "orthographic"}, {"orthographic", {{"xmag", 3.0}, {"ymag", 2.0}, {"znear", 0.0}, {"zfar", 50.0}}}}});
    const int c0 = b.node({{"camera", 0}, {"translation", {0, 1, 10}}});
    const int c1 = b.node({{"camera", 1}, {"translation", {4, 0, 0}}, {"scale", {3, 3, 3}}});
    b.scene({c0, c1});
    Scene sc = loadGltf(b.writeGltf(dir, "cams.gltf").string());
    ASSERT_EQ(sc.cameras.size(), 2u);
    const auto& a = sc.cameras[0];
    EXPECT_EQ(a.name, "front");
    EXPECT_TRUE(a.perspective);
    EXPECT_FLOAT_EQ(a.yfov, 0.6f);
    EXPECT_FLOAT_EQ(a.aspectRatio, 1.5f);
    EXPECT_FLOAT_EQ(a.znear, 0.1f);
    EXPECT_FLOAT_EQ(a.zfar, 100.0f);
    expectVec3(glm::vec3(a.cameraToWorld[3]), {0, 1, 10});
    const auto& o = sc.cameras[1];
    EXPECT_EQ(o.name, "camera1");
    EXPECT_FALSE(o.perspective);
    EXPECT_FLOAT_EQ(o.xmag, 3.0f);
    EXPECT_FLOAT_EQ(o.ymag, 2.0f);
    EXPECT_FLOAT_EQ(o.zfar, 50.0f);
    expectVec3(glm::vec3(o.cameraToWorld[3]), {4, 0, 0});
    expectVec3(glm::vec3(o.cameraToWorld[0]), {1, 0, 0});  // scale removed
}

// ---------------------------------------------------------------- bad input: errors

TEST_F(GltfLoader, RequiredUnsupportedExtensionIsAnError) {
    Builder b;
    b.j["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness"};
    b.j["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
    expectError(b.writeGltf(dir, "specgloss.gltf"), "required extension 'KHR_materials_pbrSpecularGlossiness'");
    Builder ok;  // optional unknown extension: loads, with a warning
    ok.j["extensionsUsed"] = {"EXT_something"};
    Scene sc = loadGltf(ok.writeGltf(dir, "optional.gltf").string());
    EXPECT_TRUE(hasWarning(sc, "EXT_something"));
}

TEST_F(GltfLoader, TruncatedGlbIsAnError) {
    Builder b;
    b.scene({b.node({{"mesh", b.mesh({{"POSITION", b.vec3(kTriPos)}})}})});
    const auto bytes = b.glbBytes();
    for (size_t cut : {size_t(6), size_t(16), bytes.size() / 2, bytes.size() - 4}) {
        const fs::path p = dir / ("cut" + std::to_string(cut) + ".glb");
        writeFile(p, std::vector<uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut)));
        expectError(p, "truncated");
    }
    // BIN chunk length that runs 8 bytes past the end (tinygltf 2.7 alone would accept it)
    std::vector<uint8_t> bad = bytes;
    const size_t binHeader = 20 + (size_t(bad[12]) | size_t(bad[13]) << 8);
    bad[binHeader] = uint8_t(bad[binHeader] + 4);
    writeFile(dir / "binlong.glb", bad);
    expectError(dir / "binlong.glb", "truncated");
}

TEST_F(GltfLoader, InvalidJsonIsAnError) {
    writeFile(dir / "broken.gltf", std::string("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {"));
    expectError(dir / "broken.gltf", "JSON");
    writeFile(dir / "empty.gltf", std::string());
    expectError(dir / "empty.gltf", "JSON");
    expectError(dir / "does_not_exist.gltf", "not found");
}

TEST_F(GltfLoader, AccessorOutOfRangeIsAnError) {
    {
        Builder b;  // accessor claims more elements than its buffer view holds
        const int acc = b.vec3(kTriPos);
        b.j["accessors"][acc]["count"] = 4;
        b.scene({b.node({{"mesh", b.mesh({{"POSITION", acc}})}})});
        expectError(b.writeGltf(dir, "acc.gltf"), "out of range");
    }
    {
        Builder b;  // byteOffset past the view
        const int acc = b.vec3(kTriPos);
        b.j["accessors"][acc]["byteOffset"] = 8;
        b.scene({b.node({{"mesh", b.mesh({{"POSITION", acc}})}})});
        expectError(b.writeGltf(dir, "offset.gltf"), "out of range");
    }
    {
        Builder b;  // buffer view longer than its buffer
        const int acc = b.vec3(kTriPos);
        b.scene({b.node({{"mesh", b.mesh({{"POSITION", acc}})}})});
        b.j["bufferViews"][0]["byteLength"] = 4096;
        expectError(b.writeGltf(dir, "view.gltf"), "out of range");
    }
    {
        Builder b;  // accessor index that does not exist
        b.scene({b.node({{"mesh", b.mesh({{"POSITION", 7}})}})});
        expectError(b.writeGltf(dir, "noacc.gltf"), "accessor 7");
    }
}

TEST_F(GltfLoader, WrongComponentTypeIsAnError) {
    Builder b;
    const std::vector<uint8_t> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int acc = b.addAccessor(pos.data(), pos.size(), kUByte, "VEC3", 3);
    b.scene({b.node({{"mesh", b.mesh({{"POSITION", acc}})}})});
    expectError(b.writeGltf(dir, "ubytepos.gltf"), "component type");
    Builder b2;  // POSITION declared as VEC2
    const int acc2 = b2.vec2({0, 0, 1, 0, 0, 1});
    b2.scene({b2.node({{"mesh", b2.mesh({{"POSITION", acc2}})}})});
    expectError(b2.writeGltf(dir, "vec2pos.gltf"), "wrong type");
    Builder b3;  // float indices
    const int p3 = b3.vec3(kTriPos);
    const std::vector<float> fi = {0, 1, 2};
    const int i3 = b3.addAccessor(fi.data(), 12, kFloat, "SCALAR", 3);
    b3.scene({b3.node({{"mesh", b3.mesh({{"POSITION", p3}}, i3)}})});
    expectError(b3.writeGltf(dir, "floatidx.gltf"), "component type");
}

TEST_F(GltfLoader, OverflowingCountsAreErrors) {
    Builder b;
    const int acc = b.vec3(kTriPos);
    b.j["accessors"][acc]["count"] = uint64_t(1) << 62;  // count*stride wraps 64 bits
    b.scene({b.node({{"mesh", b.mesh({{"POSITION", acc}})}})});
    expectError(b.writeGltf(dir, "count.gltf"), "count");
    Builder b2;  // under the element limit but count*stride far beyond the view
    const int acc2 = b2.vec3(kTriPos);
    b2.j["accessors"][acc2]["count"] = 100000000;
    b2.scene({b2.node({{"mesh", b2.mesh({{"POSITION", acc2}})}})});
    expectError(b2.writeGlb(dir, "count2.glb"), "out of range");
    GltfLoadOptions small;  // a smaller element budget is honoured
    small.maxElements = 2;
    Builder b3;
    b3.scene({b3.node({{"mesh", b3.mesh({{"POSITION", b3.vec3(kTriPos)}})}})});
    expectError(b3.writeGltf(dir, "budget.gltf"), "limit", small);
}

TEST_F(GltfLoader, MissingOrEscapingBufferIsAnError) {
    Builder b;
    b.scene({b.node({{"mesh", b.mesh({{"POSITION", b.vec3(kTriPos)}})}})});
    const fs::path p = b.writeGltfBin(dir, "nobin.gltf", "geometry.bin");
    fs::remove(dir / "geometry.bin");
    expectError(p, "not found");
    Builder b2;
    b2.scene({b2.node({{"mesh", b2.mesh({{"POSITION", b2.vec3(kTriPos)}})}})});
    const fs::path p2 = b2.writeGltfBin(dir, "escape.gltf", "../escape.bin");
    ASSERT_TRUE(fs::exists(dir.parent_path() / "escape.bin"));
    expectError(p2, "escapes the scene folder");
    Builder b3;
    b3.scene({b3.node({{"mesh", b3.mesh({{"POSITION", b3.vec3(kTriPos)}})}})});
    const fs::path abs = dir.parent_path() / "abs.bin";
    const fs::path p3 = b3.writeGltfBin(dir, "absolute.gltf", abs.string());
    expectError(p3, "escapes the scene folder");
}

TEST_F(GltfLoader, IndexOutOfRangeIsAnError) {
    Builder b;
    const int m = b.mesh({{"POSITION", b.vec3(kTriPos)}}, b.indices16({0, 1, 3}));
    b.scene({b.node({{"mesh", m}})});
    expectError(b.writeGltf(dir, "badidx.gltf"), "index 3 out of range");
}

TEST_F(GltfLoader, NodeCycleIsAnError) {
    Builder b;
    b.node({{"children", {1}}});
    b.node({{"children", {0}}});
    b.scene({0});
    expectError(b.writeGltf(dir, "cycle.gltf"), "node");
    Builder b2;
    b2.node({{"children", {5}}});
    b2.scene({0});
    expectError(b2.writeGltf(dir, "dangling.gltf"), "node 5");
}

// ---------------------------------------------------------------- real scenes and fuzz regressions

namespace {
// Triangles the file itself declares: sum over mesh nodes of index count / 3 (the test scenes are indexed triangles).
size_t declaredTriangles(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    json j;
    if (bytes.compare(0, 4, "glTF") == 0) {
        uint32_t len;
        std::memcpy(&len, bytes.data() + 12, 4);
        j = json::parse(bytes.substr(20, len));
    } else {
        j = json::parse(bytes);
    }
    size_t tris = 0;
    for (const auto& node : j["nodes"]) {
        if (!node.contains("mesh")) continue;
        for (const auto& prim : j["meshes"][node["mesh"].get<size_t>()]["primitives"])
            tris += j["accessors"][prim["indices"].get<size_t>()]["count"].get<size_t>() / 3;
    }
    return tris;
}

void checkRealScene(const fs::path& p) {
    if (!fs::exists(p)) GTEST_SKIP() << p << " not present";
    Scene sc = loadGltf(p.string());
    const size_t expected = declaredTriangles(p);
    EXPECT_GT(expected, 1000u);
    EXPECT_EQ(sc.triangleCount(), expected);
    ASSERT_FALSE(sc.materials.empty());
    ASSERT_GE(sc.materials[0].baseColorTexture, 0);
    ASSERT_FALSE(sc.images.empty());
    for (const auto& img : sc.images) {
        EXPECT_GT(img.width, 0);
        EXPECT_GT(img.height, 0);
        EXPECT_EQ(img.rgba8.size(), size_t(img.width) * size_t(img.height) * 4);
    }
    EXPECT_TRUE(sc.bounds.valid());
    for (const auto& part : sc.parts)
        for (const auto& v : part.vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-3f);
}
}  // namespace

TEST(GltfRealScenes, DamagedHelmetGlb) {
    checkRealScene(fs::path(DEEPGI_SHARED_SCENES) / "DamagedHelmet/glTF-Binary/DamagedHelmet.glb");
}

TEST(GltfRealScenes, SuzanneGltf) {
    checkRealScene(fs::path(DEEPGI_SHARED_SCENES) / "Suzanne/glTF/Suzanne.gltf");
}

// Inputs the fuzzer once crashed on (tests/data/gltf/regress/): each must load or throw SceneLoadError.
TEST(GltfRegress, FuzzerFindingsLoadOrFailCleanly) {
    const fs::path dir = fs::path(DEEPGI_TEST_DATA) / "gltf/regress";
    if (!fs::exists(dir)) GTEST_SKIP() << "no regression inputs";
    GltfLoadOptions opt;
    opt.maxElements = 1 << 20;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        try {
            Scene sc = loadGltf(e.path().string(), opt);
            SUCCEED() << e.path() << ": loaded " << sc.triangleCount() << " triangles";
        } catch (const SceneLoadError& err) {
            EXPECT_EQ(std::string(err.what()).rfind(e.path().string() + ": ", 0), 0u) << err.what();
        }
    }
}

// The fuzzer's seed corpus (tests/fuzz/corpus/) must stay valid; rich.* exercises sparse accessors, strips,
// images in buffer views, lights and cameras.
TEST(GltfRegress, FuzzSeedCorpusLoads) {
    const fs::path dir = DEEPGI_FUZZ_CORPUS;
    ASSERT_TRUE(fs::exists(dir));
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        Scene sc;
        ASSERT_NO_THROW(sc = loadGltf(e.path().string())) << e.path();
        ++files;
        const std::string name = e.path().filename().string();
        if (name.rfind("rich", 0) == 0) {
            ASSERT_EQ(sc.parts.size(), 2u) << name;
            EXPECT_EQ(sc.triangleCount(), 2u);
            ASSERT_EQ(sc.images.size(), 1u);
            EXPECT_EQ(sc.images[0].rgba8, (std::vector<uint8_t>{200, 100, 50, 255}));
            EXPECT_EQ(sc.textures[0].magFilter, deepgi::FilterMode::Nearest);
            EXPECT_TRUE(sc.textures[0].mipmaps);
            EXPECT_FLOAT_EQ(sc.materials[0].emissiveFactor.x, 2.0f);
            // strip primitive reads the sparse accessor: vertex 1 replaced by (2,0,0); node mirrored in z
            bool found = false;
            for (const auto& v : sc.parts[1].vertices) found |= glm::length(v.position - glm::vec3(2, 0, 0)) < 1e-5f;
            EXPECT_TRUE(found);
            expectCcwMatchesNormals(sc.parts[1]);
            ASSERT_EQ(sc.lights.size(), 1u);
            expectVec3(sc.lights[0].position, {0, 5, 0});
            ASSERT_EQ(sc.cameras.size(), 1u);
            EXPECT_EQ(sc.cameras[0].name, "camera0");
        }
    }
    EXPECT_GE(files, 4);
}

// Found by review, reproduced before the fix: tinygltf 2.7 converts extras/extensions recursively and overflowed
// the stack on deeply nested JSON (a regression input also lives in tests/data/gltf/regress/).
TEST_F(GltfLoader, DeeplyNestedJsonIsAnError) {
    const int depth = 100000;
    const std::string arrays = std::string(depth, '[') + std::string(depth, ']');
    writeFile(dir / "deep.gltf", "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + arrays + "}");
    expectError(dir / "deep.gltf", "nesting");
    std::string objs;
    for (int i = 0; i < depth; ++i) objs += "{\"a\":";
    objs += "1" + std::string(depth, '}');
    Builder b;
    b.node({{"name", "n"}});
    b.j["nodes"][0]["extras"] = 0;
    std::string js = b.j.dump();
    js.replace(js.find("\"extras\":0"), 10, "\"extras\":" + objs);
    writeFile(dir / "deep_obj.gltf", js);
    expectError(dir / "deep_obj.gltf", "nesting");
    // strings containing brackets do not count
    Builder ok;
    ok.j["extras"] = {{"text", std::string(1000, '[') + "\\\"{"}};
    EXPECT_NO_THROW(loadGltf(ok.writeGltf(dir, "brackets.gltf").string()));
}

// ---------------------------------------------------------------- hardening, round two (issue 11)

namespace {
// A one-triangle scene whose node 0 holds the mesh; `extra` is merged into the document.
Builder triangleScene() {
    Builder b;
    const int pos = b.vec3(kTriPos);
    b.mesh({{"POSITION", pos}});
    b.node({{"mesh", 0}});
    b.scene({0});
    return b;
}
std::string firstError(const fs::path& p, const GltfLoadOptions& opt = {}) {
    try {
        loadGltf(p.string(), opt);
    } catch (const SceneLoadError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

// memory: an accessor without bufferView (valid glTF: all zeros) has a count bounded by no file size; it is
// counted against the budget before anything is allocated (67 M vertices took 7.3 GB and a minute before).
TEST_F(GltfLoader, AccessorWithoutBufferViewIsCountedAgainstTheBudget) {
    Builder b;
    b.j["accessors"].push_back({{"componentType", kFloat}, {"type", "VEC3"}, {"count", 67000000}});
    b.mesh({{"POSITION", 0}});
    b.node({{"mesh", 0}, {"name", "huge"}});
    b.scene({0});
    const fs::path p = b.writeGltf(dir, "zeros.gltf");
    expectError(p, "memory budget");
    const std::string msg = firstError(p);
    EXPECT_NE(msg.find("mesh 'mesh0/0'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("MiB"), std::string::npos) << msg;
    // a small one loads, with the warning it always had
    Builder small;
    small.j["accessors"].push_back({{"componentType", kFloat}, {"type", "VEC3"}, {"count", 3}});
    small.mesh({{"POSITION", 0}});
    small.node({{"mesh", 0}});
    small.scene({0});
    Scene sc = loadGltf(small.writeGltf(dir, "zeros_small.gltf").string());
    EXPECT_TRUE(hasWarning(sc, "no data")) << allWarnings(sc);
}

// memory: instancing copies a mesh per node; the copies are counted, the message names the instance.
TEST_F(GltfLoader, InstancedMeshIsCountedPerInstance) {
    Builder b;
    std::vector<float> pos;
    std::vector<uint32_t> idx;
    for (int i = 0; i < 1000; ++i) {  // 1000 separate triangles
        for (float v : kTriPos) pos.push_back(v + float(i));
        for (uint32_t k = 0; k < 3; ++k) idx.push_back(uint32_t(i * 3) + k);
    }
    const int pa = b.vec3(pos), ia = b.indices32(idx);
    b.mesh({{"POSITION", pa}}, ia);
    std::vector<int> roots;
    for (int i = 0; i < 200; ++i) roots.push_back(b.node({{"mesh", 0}, {"translation", {0, 0, i}}}));
    b.scene(roots);
    const fs::path p = b.writeGltf(dir, "instances.gltf");
    Scene all = loadGltf(p.string());
    EXPECT_EQ(all.triangleCount(), 200000u);
    // what the Scene keeps is at least its vertices and indices; the peak is below the default budget
    const uint64_t kept = 200000ull * 3 * (sizeof(deepgi::Vertex) + 4);
    EXPECT_GE(all.loadPeakBytes, kept);
    EXPECT_LE(all.loadPeakBytes, GltfLoadOptions{}.memoryBudget);
    GltfLoadOptions opt;
    opt.memoryBudget = kept / 2;  // room for about half of the instances
    expectError(p, "memory budget", opt);
    const std::string msg = firstError(p, opt);
    EXPECT_NE(msg.find("(instance "), std::string::npos) << msg;
    EXPECT_EQ(msg.find("(instance 1 "), std::string::npos) << "the first instances fit: " << msg;
}

// memory: buffers are counted before tinygltf allocates them.
TEST_F(GltfLoader, BufferLargerThanTheBudgetIsRefusedBeforeReading) {
    Builder b = triangleScene();
    const fs::path p = b.writeGltfBin(dir, "buf.gltf", "buf.bin");
    GltfLoadOptions opt;
    opt.memoryBudget = fs::file_size(p) + 16;  // the .gltf itself fits, the 36-byte buffer does not
    expectError(p, "buffer 0 (byteLength)", opt);
}

// safety check bypassed: a symlink inside the folder that leads outside it is refused like "../".
TEST_F(GltfLoader, SymlinkLeadingOutsideTheFolderIsRefused) {
    Builder b = triangleScene();
    b.writeGltfBin(dir.parent_path(), "unused.gltf", "outside.bin");  // the real buffer, outside the scene folder
    fs::create_symlink(dir.parent_path() / "outside.bin", dir / "link.bin");
    Builder viaLink = triangleScene();
    viaLink.finishBuffer("link.bin");
    writeFile(dir / "link.gltf", viaLink.j.dump());
    expectError(dir / "link.gltf", "symlink that leads outside the scene folder");
    // a symlink to a system file used as a buffer
    fs::create_symlink("/etc/passwd", dir / "passwd.bin");
    Builder sys = triangleScene();
    sys.finishBuffer("passwd.bin");
    writeFile(dir / "sys.gltf", sys.j.dump());
    expectError(dir / "sys.gltf", "symlink that leads outside");
    // a symlink that stays inside the folder is fine
    fs::create_directories(dir / "data");
    fs::copy_file(dir.parent_path() / "outside.bin", dir / "data" / "real.bin");
    fs::create_symlink("data/real.bin", dir / "inside.bin");
    Builder in = triangleScene();
    in.finishBuffer("inside.bin");
    writeFile(dir / "inside.gltf", in.j.dump());
    EXPECT_EQ(loadGltf((dir / "inside.gltf").string()).triangleCount(), 1u);
    // an image through an escaping symlink: dropped with a warning naming the reason
    fs::create_symlink("/etc/hostname", dir / "img.png");
    Builder img = triangleScene();
    img.j["images"] = {{{"uri", "img.png"}}};
    img.j["textures"] = {{{"source", 0}}};
    img.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    Scene sc = loadGltf(img.writeGltf(dir, "img.gltf").string());
    EXPECT_TRUE(hasWarning(sc, "img.png", "symlink")) << allWarnings(sc);
}

// unclear message: a FIFO or a device is not "File not found" (and opening a FIFO would block forever).
TEST_F(GltfLoader, NonRegularFilesAreRefusedWithTheirOwnMessage) {
    ASSERT_EQ(mkfifo((dir / "pipe.bin").c_str(), 0600), 0);
    Builder b = triangleScene();
    b.finishBuffer("pipe.bin");
    writeFile(dir / "fifo.gltf", b.j.dump());
    expectError(dir / "fifo.gltf", "FIFO");
    ASSERT_EQ(mkfifo((dir / "main.gltf").c_str(), 0600), 0);
    expectError(dir / "main.gltf", "is a FIFO (named pipe), not a regular file");
    fs::create_symlink("/dev/zero", dir / "zero.gltf");
    expectError(dir / "zero.gltf", "character device");
}

// silent wrong: tinygltf stores indices in int via static_cast, so 2^32 became 0 and passed every range check.
TEST_F(GltfLoader, IndicesOf2To32AndAboveAreErrorsNotWrapped) {
    struct Case { std::string name; std::function<void(json&)> edit; std::string where; };
    const std::vector<Case> cases = {
        {"node_mesh", [](json& j) { j["nodes"][0]["mesh"] = 4294967296ull; }, "nodes[0].mesh"},
        {"scene_nodes", [](json& j) { j["scenes"][0]["nodes"][0] = 4294967296ull; }, "scenes[0].nodes[0]"},
        {"scene", [](json& j) { j["scene"] = 4294967296ull; }, "scene"},
        {"attribute", [](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 4294967296ull; },
         "attributes.POSITION"},
        {"material", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = 4294967297ull; }, "material"},
        {"camera", [](json& j) { j["nodes"][0]["camera"] = 8589934592ull; }, "nodes[0].camera"},
        {"accessor_view", [](json& j) { j["accessors"][0]["bufferView"] = 4294967296ull; }, "accessors[0].bufferView"},
        {"negative", [](json& j) { j["nodes"][0]["mesh"] = -5; }, "nodes[0].mesh"},
        {"fraction", [](json& j) { j["nodes"][0]["mesh"] = 0.5; }, "not an integer"},
    };
    for (const auto& c : cases) {
        Builder b = triangleScene();
        c.edit(b.j);
        const fs::path p = b.writeGltf(dir, c.name + ".gltf");
        expectError(p, c.where);
        if (c.name != "fraction") expectError(p, "out of range");
    }
}

// silent wrong: a texture larger than GL_MAX_TEXTURE_SIZE rendered black; it is downscaled with a warning.
TEST_F(GltfLoader, TextureLargerThanTheLimitIsDownscaledWithAWarning) {
    const int w = 16400, h = 2;
    std::vector<uint8_t> px(size_t(w) * h * 3, 0);
    for (int x = 0; x < w; ++x)
        for (int y = 0; y < h; ++y) px[(size_t(y) * w + x) * 3 + 0] = 200;  // all red 200
    const std::vector<uint8_t> bytes = png(w, h, 3, px);
    writeFile(dir / "wide.png", bytes);
    Builder b = triangleScene();
    b.j["images"] = {{{"uri", "wide.png"}}};
    b.j["textures"] = {{{"source", 0}}};
    b.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    Scene sc = loadGltf(b.writeGltf(dir, "wide.gltf").string());
    ASSERT_EQ(sc.images.size(), 1u);
    EXPECT_EQ(sc.images[0].width, 16384);
    EXPECT_EQ(sc.images[0].height, 2);
    EXPECT_TRUE(hasWarning(sc, "wide.png", "downscaled to 16384x2")) << allWarnings(sc);
    // a constant image stays that constant (sRGB-correct filter)
    EXPECT_NEAR(sc.images[0].rgba8[4 * 5000], 200, 1);
    EXPECT_EQ(sc.images[0].rgba8[4 * 5000 + 3], 255);
    GltfLoadOptions opt;
    opt.maxTextureSize = 4096;
    Scene small = loadGltf((dir / "wide.gltf").string(), opt);
    EXPECT_EQ(small.images[0].width, 4096);
    EXPECT_EQ(small.images[0].height, 1);
}

// unclear messages: each names the element and what is wrong with it, in one readable line.
TEST_F(GltfLoader, MessagesNameTheProblem) {
    // Draco data that is not Draco: the primitive and Draco, not "accessor[0] invalid bufferView"
    Builder draco = triangleScene();
    draco.j["accessors"].push_back({{"componentType", kUShort}, {"type", "SCALAR"}, {"count", 3}});
    draco.j["meshes"][0]["primitives"][0]["indices"] = 1;
    draco.j["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}};
    draco.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    expectError(draco.writeGltf(dir, "draco.gltf"), "(KHR_draco_mesh_compression): Draco decoding failed");
    draco.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expectError(draco.writeGltf(dir, "draco_req.gltf"), "Draco decoding failed");
    // a data URI whose byteLength is wrong: says byteLength, does not quote the payload
    Builder big;
    std::vector<float> pos(300000, 0.0f);
    big.vec3(pos);
    big.mesh({{"POSITION", 0}});
    big.node({{"mesh", 0}});
    big.scene({0});
    const fs::path bp = big.writeGltf(dir, "len.gltf");
    json j = json::parse(std::ifstream(bp));
    j["buffers"][0]["byteLength"] = 1200004;
    writeFile(bp, j.dump());
    expectError(bp, "data URI holds 1200000 bytes but byteLength says 1200004");
    EXPECT_LT(firstError(bp).size(), 400u);
    // a buffer without uri in a .gltf
    Builder nouri = triangleScene();
    nouri.writeGltf(dir, "tmp.gltf");
    nouri.j["buffers"][0].erase("uri");
    writeFile(dir / "nouri.gltf", nouri.j.dump());
    expectError(dir / "nouri.gltf", "buffer 0 has no uri");
    EXPECT_EQ(firstError(dir / "nouri.gltf").find("escapes"), std::string::npos);
    // a URI with \u0000: the message shows all of it
    Builder nul = triangleScene();
    nul.finishBuffer(std::string("a\0b.bin", 7));
    writeFile(dir / "nul.gltf", nul.j.dump());
    expectError(dir / "nul.gltf", "a\\x00b.bin");
}

// silent wrong / crash: the cameras that made `reference` abort in Embree and `render` draw black are refused
// (with one warning each) by the validation both renderers share; a tiny but valid scale is kept.
TEST_F(GltfLoader, DegenerateCameraTransformsAreSkippedWithAWarning) {
    struct Case { std::string name; json node; bool kept; };
    const std::vector<Case> cases = {
        {"scale0", {{"camera", 0}, {"scale", {0, 0, 0}}}, false},
        {"scale_tiny", {{"camera", 0}, {"scale", {1e-30, 1e-30, 1e-30}}}, true},
        {"zero_matrix", {{"camera", 0}, {"matrix", std::vector<double>(16, 0.0)}}, false},
        {"far", {{"camera", 0}, {"translation", {1e38, 0, 0}}}, false},
    };
    for (const auto& c : cases) {
        Builder b = triangleScene();
        b.j["cameras"] = {{{"type", "perspective"}, {"name", "cam"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
        b.node(c.node);
        b.scene({0, 1});
        Scene sc = loadGltf(b.writeGltf(dir, c.name + ".gltf").string());
        EXPECT_EQ(sc.cameras.size(), c.kept ? 1u : 0u) << c.name;
        EXPECT_EQ(hasWarning(sc, "camera 'cam'", "skipped"), !c.kept) << c.name << ": " << allWarnings(sc);
        if (c.kept) {
            const glm::mat4& m = sc.cameras[0].cameraToWorld;
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(glm::length(glm::vec3(m[i])), 1.0f, 1e-5f) << c.name;
        }
    }
    // a parent scaled to 0 collapses its child camera the same way
    Builder p = triangleScene();
    p.j["cameras"] = {{{"type", "perspective"}, {"name", "cam"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    p.node({{"scale", {0, 0, 0}}, {"children", {2}}});
    p.node({{"camera", 0}});
    p.scene({0, 1});
    Scene sc = loadGltf(p.writeGltf(dir, "parent0.gltf").string());
    EXPECT_TRUE(sc.cameras.empty());
}

TEST_F(GltfLoader, CameraClipPlanesAndMagnificationAreValidated) {
    Builder b = triangleScene();
    b.j["cameras"] = {{{"type", "perspective"}, {"name", "inverted"}, {"perspective", {{"yfov", 0.8}, {"znear", 10.0}, {"zfar", 1.0}}}},
                      {{"type", "orthographic"}, {"name", "flat"}, {"orthographic", {{"xmag", 0.0}, {"ymag", 0.0}, {"znear", 0.0}, {"zfar", 10.0}}}},
                      {{"type", "orthographic"}, {"name", "neg"}, {"orthographic", {{"xmag", -2.0}, {"ymag", -1.0}, {"znear", 0.0}, {"zfar", 10.0}}}}};
    b.node({{"camera", 0}});
    b.node({{"camera", 1}});
    b.node({{"camera", 2}});
    b.scene({0, 1, 2, 3});
    Scene sc = loadGltf(b.writeGltf(dir, "clip.gltf").string());
    ASSERT_EQ(sc.cameras.size(), 2u) << allWarnings(sc);
    EXPECT_EQ(sc.cameras[0].name, "inverted");
    EXPECT_EQ(sc.cameras[0].zfar, 0.0f) << "far plane ignored";
    EXPECT_TRUE(hasWarning(sc, "camera 'inverted'", "zfar ignored")) << allWarnings(sc);
    EXPECT_TRUE(hasWarning(sc, "camera 'flat'", "no size")) << allWarnings(sc);
    EXPECT_EQ(sc.cameras[1].name, "neg");
    EXPECT_EQ(sc.cameras[1].ymag, 1.0f);
    EXPECT_TRUE(hasWarning(sc, "camera 'neg'", "magnitude")) << allWarnings(sc);
}

TEST_F(GltfLoader, LightsAndMaterialFactorsAreValidatedWithWarnings) {
    Builder b = triangleScene();
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"] = {{"KHR_lights_punctual", {{"lights", {
        {{"type", "spot"}, {"name", "inverted"}, {"intensity", 5.0}, {"spot", {{"innerConeAngle", 0.7}, {"outerConeAngle", 0.3}}}},
        {{"type", "point"}, {"name", "negative"}, {"intensity", -1.0}, {"color", {1.0, -0.5, 1.0}}}}}}}};
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    b.j["materials"] = {{{"name", "bright"}, {"pbrMetallicRoughness", {{"baseColorFactor", {2.0, 0.5, -1.0, 1.0}}}},
                         {"emissiveFactor", {-1.0, 0.5, 0.0}}}};
    b.j["meshes"][0]["primitives"][0]["material"] = 0;
    b.scene({0, 1, 2});
    Scene sc = loadGltf(b.writeGltf(dir, "lights.gltf").string());
    ASSERT_EQ(sc.lights.size(), 2u);
    EXPECT_FLOAT_EQ(sc.lights[0].innerConeAngle, 0.3f);
    EXPECT_FLOAT_EQ(sc.lights[0].outerConeAngle, 0.7f);
    EXPECT_TRUE(hasWarning(sc, "light 'inverted'", "swapped")) << allWarnings(sc);
    EXPECT_EQ(sc.lights[1].intensity, 0.0f);
    EXPECT_EQ(sc.lights[1].color.y, 0.0f);
    EXPECT_TRUE(hasWarning(sc, "light 'negative'", "negative intensity")) << allWarnings(sc);
    EXPECT_TRUE(hasWarning(sc, "light 'negative'", "negative colour")) << allWarnings(sc);
    ASSERT_EQ(sc.materials.size(), 1u);
    expectVec3(glm::vec3(sc.materials[0].baseColorFactor), {1.0f, 0.5f, 0.0f});
    expectVec3(sc.materials[0].emissiveFactor, {0.0f, 0.5f, 0.0f});
    EXPECT_TRUE(hasWarning(sc, "material 'bright'", "baseColorFactor")) << allWarnings(sc);
    EXPECT_TRUE(hasWarning(sc, "material 'bright'", "emissiveFactor")) << allWarnings(sc);
}
