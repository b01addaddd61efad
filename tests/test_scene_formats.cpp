// OBJ + MTL scenes and the glTF extensions real files use (KHR_mesh_quantization, KHR_texture_transform,
// KHR_draco_mesh_compression, EXT_meshopt_compression), on the assets of tools/gen_test_assets.py. Each compressed
// or quantized file is checked against the plain one it was made from (same geometry within the quantization
// step, same image), the texture transform against UVs the generator transformed itself, and the OBJ room's direct
// light against the path tracer and the analytic value Kd/pi * E * cos.
// One file (about 700 lines): the OBJ and extension tests share the encoders, writers and comparisons at its top.
#include "gl_fixture.h"

#include "renderer/reference/path_tracer.h"
#include "renderer/scene/gltf_loader.h"
#include "renderer/scene/obj_loader.h"
#include "renderer/scene/scene_loader.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <sys/stat.h>
#include <unistd.h>

using namespace deepgi;
using namespace deepgi::test;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const std::string kTestAssets = std::string(DEEPGI_ASSET_DIR) + "/test";

bool hasWarning(const Scene& s, const std::string& needle) {
    for (const auto& w : s.warnings)
        if (w.find(needle) != std::string::npos) return true;
    return false;
}
int countWarnings(const Scene& s, const std::string& needle) {
    int n = 0;
    for (const auto& w : s.warnings)
        if (w.find(needle) != std::string::npos) ++n;
    return n;
}

std::string loadError(const std::string& path, const GltfLoadOptions& opt = {}) {
    try {
        loadScene(path, opt);
    } catch (const SceneLoadError& e) {
        return e.what();
    }
    return "";
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream f(p, std::ios::binary);
    f << text;
}
std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

class TempDir {
public:
    TempDir() {
        char tmpl[] = "/tmp/deepgi_formats_XXXXXX";
        path_ = mkdtemp(tmpl);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

std::string base64(const std::vector<uint8_t>& d) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < d.size(); i += 3) {
        const uint32_t v = (uint32_t(d[i]) << 16) | (uint32_t(d[i + 1]) << 8) | d[i + 2];
        for (int k = 3; k >= 0; --k) out += t[(v >> (6 * k)) & 63];
    }
    if (i + 1 == d.size()) {
        const uint32_t v = uint32_t(d[i]) << 16;
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == d.size()) {
        const uint32_t v = (uint32_t(d[i]) << 16) | (uint32_t(d[i + 1]) << 8);
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += t[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

void writeGlb(const fs::path& p, const json& j, std::vector<uint8_t> bin) {
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> out;
    auto put32 = [&](uint32_t v) { for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k))); };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    put32(2);
    put32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    put32(uint32_t(text.size()));
    put32(0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    put32(uint32_t(bin.size()));
    put32(0x004E4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream f(p, std::ios::binary);
    f.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
}

// The plain sphere-and-floor glTF as JSON, and a folder holding a copy of its texture for derived files.
json plainJson() { return json::parse(readText(kTestAssets + "/quant/plain.gltf")); }
void copyTexture(const fs::path& dir) {
    fs::copy_file(kTestAssets + "/quant/checker.png", dir / "checker.png", fs::copy_options::overwrite_existing);
}

// ---- Draco and meshopt encodings of the plain scene's one mesh (the independent encoders of the libraries) ----

// Writes `dir/name` (a GLB) holding `part` compressed with Draco, the rest of the plain file unchanged.
fs::path writeDracoGlb(const MeshPart& part, const fs::path& dir, const std::string& name) {
    const int faces = int(part.indices.size() / 3);
    draco::TriangleSoupMeshBuilder mb;
    mb.Start(faces);
    const int pa = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int na = mb.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int ta = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < faces; ++f) {
        const Vertex& a = part.vertices[part.indices[size_t(f) * 3]];
        const Vertex& b = part.vertices[part.indices[size_t(f) * 3 + 1]];
        const Vertex& c = part.vertices[part.indices[size_t(f) * 3 + 2]];
        mb.SetAttributeValuesForFace(pa, draco::FaceIndex(uint32_t(f)), &a.position, &b.position, &c.position);
        mb.SetAttributeValuesForFace(na, draco::FaceIndex(uint32_t(f)), &a.normal, &b.normal, &c.normal);
        mb.SetAttributeValuesForFace(ta, draco::FaceIndex(uint32_t(f)), &a.uv, &b.uv, &c.uv);
    }
    std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
    EXPECT_TRUE(mesh);
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 16);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 12);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 14);
    draco::EncoderBuffer buf;
    const draco::Status st = enc.EncodeMeshToBuffer(*mesh, &buf);
    EXPECT_TRUE(st.ok()) << st.error_msg_string();
    // The accessor counts are the decoded mesh's (the encoder may merge points).
    draco::DecoderBuffer db;
    db.Init(buf.data(), buf.size());
    draco::Decoder dec;
    auto decoded = dec.DecodeMeshFromBuffer(&db);
    EXPECT_TRUE(decoded.ok());
    const size_t points = decoded.value()->num_points(), decodedFaces = decoded.value()->num_faces();

    json j = plainJson();
    j["buffers"] = json::array({{{"byteLength", buf.size()}}});
    j["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", buf.size()}}});
    j["accessors"] = json::array({
        {{"componentType", 5126}, {"type", "VEC3"}, {"count", points}},
        {{"componentType", 5126}, {"type", "VEC3"}, {"count", points}},
        {{"componentType", 5126}, {"type", "VEC2"}, {"count", points}},
        {{"componentType", 5125}, {"type", "SCALAR"}, {"count", decodedFaces * 3}}});
    json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}};
    prim["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", 0},
        {"attributes", {{"POSITION", mesh->attribute(pa)->unique_id()}, {"NORMAL", mesh->attribute(na)->unique_id()},
                        {"TEXCOORD_0", mesh->attribute(ta)->unique_id()}}}};
    j["meshes"] = json::array({{{"name", "sphere_and_floor"}, {"primitives", json::array({prim})}}});
    j["nodes"][0].erase("translation");
    j["nodes"][0].erase("scale");  // the part's vertices are in world space already
    j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const fs::path p = dir / name;
    writeGlb(p, j, std::vector<uint8_t>(buf.data(), buf.data() + buf.size()));
    return p;
}

// Writes `dir/name` (.gltf, data URI) holding `part` as three EXT_meshopt_compression views: positions and UVs
// interleaved (ATTRIBUTES), octahedral normals (ATTRIBUTES, OCTAHEDRAL filter, KHR_mesh_quantization bytes) and
// indices (TRIANGLES), the views' own buffer a placeholder without data.
fs::path writeMeshoptGltf(const MeshPart& part, const fs::path& dir, const std::string& name) {
    const size_t nv = part.vertices.size(), ni = part.indices.size();
    std::vector<uint8_t> interleaved(nv * 20), normals(nv * 4);
    std::vector<float> n4(nv * 4);
    for (size_t i = 0; i < nv; ++i) {
        std::memcpy(&interleaved[i * 20], &part.vertices[i].position, 12);
        std::memcpy(&interleaved[i * 20 + 12], &part.vertices[i].uv, 8);
        for (int c = 0; c < 3; ++c) n4[i * 4 + size_t(c)] = part.vertices[i].normal[c];
        n4[i * 4 + 3] = 0.0f;
    }
    meshopt_encodeFilterOct(normals.data(), nv, 4, 8, n4.data());
    std::vector<uint8_t> compressed;
    json views = json::array();
    size_t decodedOffset = 0;
    auto addView = [&](const void* data, size_t count, size_t stride, const std::string& mode, const std::string& filter) {
        std::vector<uint8_t> enc;
        if (mode == "ATTRIBUTES") {
            enc.resize(meshopt_encodeVertexBufferBound(count, stride));
            enc.resize(meshopt_encodeVertexBuffer(enc.data(), enc.size(), data, count, stride));
        } else {
            enc.resize(meshopt_encodeIndexBufferBound(count, nv));
            enc.resize(meshopt_encodeIndexBuffer(enc.data(), enc.size(), static_cast<const unsigned*>(data), count));
        }
        EXPECT_FALSE(enc.empty());
        while (compressed.size() % 4) compressed.push_back(0);
        json ext = {{"buffer", 0}, {"byteOffset", compressed.size()}, {"byteLength", enc.size()},
                    {"byteStride", stride}, {"count", count}, {"mode", mode}};
        if (!filter.empty()) ext["filter"] = filter;
        compressed.insert(compressed.end(), enc.begin(), enc.end());
        json v = {{"buffer", 1}, {"byteOffset", decodedOffset}, {"byteLength", count * stride}};
        if (mode == "ATTRIBUTES") v["byteStride"] = stride;
        v["extensions"]["EXT_meshopt_compression"] = ext;
        decodedOffset += (count * stride + 3) / 4 * 4;
        views.push_back(v);
    };
    addView(interleaved.data(), nv, 20, "ATTRIBUTES", "");
    addView(normals.data(), nv, 4, "ATTRIBUTES", "OCTAHEDRAL");
    addView(part.indices.data(), ni, 4, "TRIANGLES", "");

    json j = plainJson();
    j["buffers"] = json::array({{{"byteLength", compressed.size()},
                                 {"uri", "data:application/octet-stream;base64," + base64(compressed)}},
                                {{"byteLength", decodedOffset}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    j["bufferViews"] = views;
    j["accessors"] = json::array({
        {{"bufferView", 0}, {"byteOffset", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", nv}},
        {{"bufferView", 0}, {"byteOffset", 12}, {"componentType", 5126}, {"type", "VEC2"}, {"count", nv}},
        {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"type", "VEC3"}, {"count", nv}},
        {{"bufferView", 2}, {"componentType", 5125}, {"type", "SCALAR"}, {"count", ni}}});
    json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"NORMAL", 2}}}, {"indices", 3}, {"material", 0}};
    j["meshes"] = json::array({{{"name", "sphere_and_floor"}, {"primitives", json::array({prim})}}});
    j["nodes"][0].erase("translation");
    j["nodes"][0].erase("scale");
    j["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    j["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    const fs::path p = dir / name;
    writeText(p, j.dump(1));
    return p;
}

// Every vertex of `b` lies within `posTol` of a vertex of `a` whose normal and uv agree within their tolerances.
void expectSameVertices(const MeshPart& a, const MeshPart& b, float posTol, float nTol, float uvTol) {
    int unmatched = 0;
    for (const Vertex& v : b.vertices) {
        bool found = false;
        for (const Vertex& w : a.vertices)
            if (glm::length(v.position - w.position) <= posTol && glm::length(v.normal - w.normal) <= nTol &&
                glm::length(v.uv - w.uv) <= uvTol) { found = true; break; }
        if (!found) ++unmatched;
    }
    EXPECT_EQ(unmatched, 0) << "of " << b.vertices.size() << " vertices";
}

double triangleArea(const MeshPart& p) {
    double area = 0;
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3)
        area += 0.5 * glm::length(glm::cross(p.vertices[p.indices[t + 1]].position - p.vertices[p.indices[t]].position,
                                             p.vertices[p.indices[t + 2]].position - p.vertices[p.indices[t]].position));
    return area;
}

FloatImage renderDirect(const Scene& scene, const Camera& cam, int w, int h) {
    Settings s;
    s.indirect = false;
    Renderer r;
    r.setScene(std::make_shared<Scene>(scene));
    r.resize(w, h);
    r.setCamera(cam);
    r.render(s);
    return r.readFinalRadiance();
}

// mean |a - b| over every channel, relative to the mean of a
double relativeMeanAbs(const FloatImage& a, const FloatImage& b) {
    double diff = 0, sum = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        diff += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
        sum += std::abs(double(a.pixels[i]));
    }
    return sum > 0 ? diff / sum : 1.0;
}

}  // namespace

// ---------------------------------------------------------------- OBJ + MTL

TEST(ObjLoader, RoomMaterialsTexturesAndMask) {
    const Scene s = loadScene(kTestAssets + "/obj_room/room.obj");
    EXPECT_EQ(s.triangleCount(), 12u);  // six quads
    EXPECT_TRUE(s.lights.empty());      // the renderer adds the default sun
    EXPECT_TRUE(s.cameras.empty());     // and a framing camera
    ASSERT_EQ(s.materials.size(), 5u);
    auto mat = [&](const std::string& name) -> const Material& {
        for (const auto& m : s.materials) if (m.name == name) return m;
        ADD_FAILURE() << "no material " << name;
        return s.materials[0];
    };
    EXPECT_NEAR(mat("floor").baseColorFactor.x, 0.7f, 1e-6f);
    EXPECT_NEAR(mat("red_wall").baseColorFactor.y, 0.065f, 1e-6f);
    EXPECT_EQ(mat("floor").alphaMode, AlphaMode::Opaque);
    EXPECT_TRUE(mat("floor").doubleSided);
    const glm::vec3 ke = mat("panel").emissiveFactor;
    EXPECT_FLOAT_EQ(ke.x, 4.0f);
    EXPECT_FLOAT_EQ(ke.y, 3.0f);
    EXPECT_FLOAT_EQ(ke.z, 2.0f);
    // map_Kd with a backslash path
    const Material& chk = mat("checker_wall");
    ASSERT_GE(chk.baseColorTexture, 0);
    const Image& ci = s.images[size_t(s.textures[size_t(chk.baseColorTexture)].image)];
    EXPECT_EQ(ci.name, "textures/checker.png");
    EXPECT_EQ(ci.width, 64);
    // map_d: even stripes opaque, odd cut out, in the base colour texture's alpha
    const Material& fence = mat("fence");
    EXPECT_EQ(fence.alphaMode, AlphaMode::Mask);
    ASSERT_GE(fence.baseColorTexture, 0);
    const Image& fi = s.images[size_t(s.textures[size_t(fence.baseColorTexture)].image)];
    ASSERT_EQ(fi.width, 64);
    EXPECT_EQ(fi.rgba8[(10 * 64 + 4) * 4 + 3], 255);   // stripe 0
    EXPECT_EQ(fi.rgba8[(10 * 64 + 12) * 4 + 3], 0);    // stripe 1
    EXPECT_EQ(fi.rgba8[(10 * 64 + 4) * 4 + 0], 255);   // no map_Kd: white colour (Kd tints it)
    // OBJ's v runs up: the floor corner written with vt (0, 0) gets the Scene's uv (0, 1)
    bool cornerFound = false;
    for (const auto& p : s.parts)
        for (const auto& v : p.vertices)
            if (glm::length(v.position - glm::vec3(-2, 0, 2)) < 1e-6f && glm::length(v.normal - glm::vec3(0, 1, 0)) < 1e-6f) {
                EXPECT_NEAR(v.uv.x, 0.0f, 1e-6f);
                EXPECT_NEAR(v.uv.y, 1.0f, 1e-6f);
                cornerFound = true;
            }
    EXPECT_TRUE(cornerFound);
    EXPECT_TRUE(s.bounds.valid());
    EXPECT_NEAR(s.bounds.hi.y, 2.0f, 1e-6f);
}

TEST(ObjLoader, MissingTextureWarnsOnceNamingTheFile) {
    TempDir d;
    writeText(d.path() / "a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                  "usemtl m1\nf 1/1 2/2 3/3\nusemtl m2\nf 1/1 3/3 2/2\nusemtl undefined\nf 1 2 3\n");
    writeText(d.path() / "a.mtl", "newmtl m1\nKd 0.5 0.25 0.125\nmap_Kd tex\\absent_curtain.png\n"
                                  "newmtl m2\nKd 1 1 1\nmap_Kd tex\\absent_curtain.png\nmap_bump tex\\bump.png\nKs 0.5 0.5 0.5\n");
    const Scene s = loadScene((d.path() / "a.obj").string());
    EXPECT_EQ(countWarnings(s, "tex/absent_curtain.png"), 1);
    EXPECT_EQ(s.materials[0].baseColorTexture, -1);  // falls back to Kd
    EXPECT_FLOAT_EQ(s.materials[0].baseColorFactor.y, 0.25f);
    EXPECT_TRUE(hasWarning(s, "bump"));      // unsupported features: one warning each, naming the material
    EXPECT_TRUE(hasWarning(s, "specular"));
    EXPECT_EQ(s.triangleCount(), 3u);        // the undefined material's face uses the default material
}

TEST(ObjLoader, TexturesRelativeToTheirLibrary) {
    TempDir d;
    fs::create_directories(d.path() / "mat" / "tex");
    fs::copy_file(kTestAssets + "/obj_room/textures/checker.png", d.path() / "mat" / "tex" / "near_library.png");
    fs::copy_file(kTestAssets + "/obj_room/textures/checker.png", d.path() / "near_obj.png");
    writeText(d.path() / "m.obj", "mtllib mat/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
    writeText(d.path() / "mat" / "m.mtl", "newmtl a\nmap_Kd tex\\near_library.png\nnewmtl b\nmap_Kd near_obj.png\n");
    const Scene s = loadScene((d.path() / "m.obj").string());
    ASSERT_EQ(s.materials.size(), 2u);
    ASSERT_GE(s.materials[0].baseColorTexture, 0);
    ASSERT_GE(s.materials[1].baseColorTexture, 0);
    EXPECT_EQ(s.images[size_t(s.textures[size_t(s.materials[0].baseColorTexture)].image)].name, "mat/tex/near_library.png");
    EXPECT_EQ(s.images[size_t(s.textures[size_t(s.materials[1].baseColorTexture)].image)].name, "near_obj.png");
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(ObjLoader, DissolveIsAMask) {
    TempDir d;
    writeText(d.path() / "d.obj", "mtllib d.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\nusemtl gone\nf 1 3 2\n"
                                  "usemtl tr\nf 2 3 1\nusemtl solid\nf 3 2 1\n");
    writeText(d.path() / "d.mtl", "newmtl half\nKd 1 1 1\nd 0.25\nnewmtl gone\nd 0\nnewmtl tr\nTr 0.75\nnewmtl solid\nd 1\n");
    const Scene s = loadScene((d.path() / "d.obj").string());
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.materials[0].alphaMode, AlphaMode::Mask);  // d 0.25: below the 0.5 cutoff, cut out
    EXPECT_FLOAT_EQ(s.materials[0].baseColorFactor.w, 0.25f);
    EXPECT_EQ(s.materials[1].alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(s.materials[1].baseColorFactor.w, 0.0f);
    EXPECT_EQ(s.materials[2].alphaMode, AlphaMode::Mask);  // Tr is 1 - d
    EXPECT_FLOAT_EQ(s.materials[2].baseColorFactor.w, 0.25f);
    EXPECT_EQ(s.materials[3].alphaMode, AlphaMode::Opaque);
    EXPECT_TRUE(hasWarning(s, "partial transparency"));     // d between 0 and 1 is not blended: said once
    EXPECT_EQ(countWarnings(s, "partial transparency"), 1);
}

TEST(ObjLoader, FileRulesAsForGltf) {
    TempDir d;
    fs::create_directories(d.path() / "scene");
    writeText(d.path() / "outside.mtl", "newmtl m\nKd 0 1 0\n");
    writeText(d.path() / "outside.png", "not read");
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n";
    // a library outside the folder: refused (warning), the materials fall back
    writeText(d.path() / "scene" / "up.obj", "mtllib ../outside.mtl\nusemtl m\n" + tri);
    Scene s = loadScene((d.path() / "scene" / "up.obj").string());
    EXPECT_TRUE(hasWarning(s, "escapes the scene folder")) << (s.warnings.empty() ? "" : s.warnings[0]);
    EXPECT_TRUE(s.materials.empty());
    // a texture symlinked to outside the folder, and one that is a FIFO: refused with a warning naming them
    fs::create_symlink(d.path() / "outside.png", d.path() / "scene" / "link.png");
    ASSERT_EQ(mkfifo((d.path() / "scene" / "fifo.png").c_str(), 0600), 0);
    writeText(d.path() / "scene" / "t.mtl", "newmtl a\nmap_Kd link.png\nnewmtl b\nmap_Kd fifo.png\n");
    writeText(d.path() / "scene" / "t.obj", "mtllib t.mtl\nusemtl a\n" + tri + "usemtl b\nf 1/1 3/1 2/1\n");
    s = loadScene((d.path() / "scene" / "t.obj").string());
    EXPECT_TRUE(hasWarning(s, "link.png")) ;
    EXPECT_TRUE(hasWarning(s, "symlink that leads outside"));
    EXPECT_TRUE(hasWarning(s, "FIFO"));
    EXPECT_EQ(s.triangleCount(), 2u);
    // the OBJ itself: absent, a FIFO, a directory
    EXPECT_NE(loadError((d.path() / "none.obj").string()).find("not found"), std::string::npos);
    ASSERT_EQ(mkfifo((d.path() / "pipe.obj").c_str(), 0600), 0);
    EXPECT_NE(loadError((d.path() / "pipe.obj").string()).find("FIFO"), std::string::npos);
    fs::create_directories(d.path() / "dir.obj");
    EXPECT_NE(loadError((d.path() / "dir.obj").string()).find("directory"), std::string::npos);
    // an index past the vertices: an error naming the file and the object
    writeText(d.path() / "bad.obj", "o thing\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    const std::string e = loadError((d.path() / "bad.obj").string());
    EXPECT_NE(e.find("bad.obj"), std::string::npos) << e;
    EXPECT_NE(e.find("thing"), std::string::npos) << e;
    EXPECT_NE(e.find("out of range"), std::string::npos) << e;
    // the memory budget
    GltfLoadOptions tiny;
    tiny.memoryBudget = 200;
    const std::string b = loadError(kTestAssets + "/obj_room/room.obj", tiny);
    EXPECT_NE(b.find("memory budget"), std::string::npos) << b;
}

TEST(ObjLoader, DispatchOnExtension) {
    // An OBJ through the one entry point every command uses: not "invalid JSON".
    EXPECT_TRUE(isObjPath("x/Scene.OBJ"));
    EXPECT_FALSE(isObjPath("x/scene.gltf"));
    EXPECT_NO_THROW(loadScene(kTestAssets + "/obj_room/room.obj"));
    EXPECT_NO_THROW(loadScene(kTestAssets + "/quant/plain.gltf"));
}

// The room under the default sun, direct light only: against the path tracer's direct image, and one floor point
// against Kd / pi * E * sin(elevation).
TEST_F(GLTest, ObjRoomDirectLightMatchesPathTracerAndAnalytic) {
    Scene scene = loadScene(kTestAssets + "/obj_room/room.obj");
    // The panel's Ke (checked by RoomMaterialsTexturesAndMask) lights the floor in the path tracer's direct image
    // and through the GI in ours: off here, so both images are the sun alone.
    for (auto& m : scene.materials) m.emissiveFactor = glm::vec3(0.0f);
    procedural::addCamera(scene, "top", {0.0f, 6.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 60.0f);
    const Camera cam = selectCamera(scene, "top");
    const int W = 96, H = 96;
    Settings s;
    s.indirect = false;
    const FloatImage ours = renderDirect(scene, cam, W, H);
    ReferenceOptions o;
    o.width = W;
    o.height = H;
    o.spp = 16;
    o.maxBounces = 0;
    o.progress = false;
    const ReferenceResult ref = renderReference(scene, cam, s, o);
    dumpIfRequested("obj_room_ours", ours);
    dumpIfRequested("obj_room_ref", ref.direct);
    double sumAbs = 0, sumRef = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                sumAbs += std::abs(ours.at(x, y, c) - ref.direct.at(x, y, c));
                sumRef += ref.direct.at(x, y, c);
            }
    // 4%: as the direct-light tests (edge aliasing: the reference box-filters 16 samples per pixel)
    EXPECT_GT(sumRef, 0.0);
    EXPECT_LT(sumAbs, 0.04 * sumRef) << 100 * sumAbs / sumRef << "%";
    std::printf("obj room direct: mean |ours - reference| = %.2f%% of the reference\n", 100 * sumAbs / sumRef);
    // the floor at (0, 0, 1), lit (the walls' shadows fall behind them, the fence's towards -z)
    const glm::vec4 clip = cam.projection(float(W) / float(H)) * cam.view() * glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    const int px = int((clip.x / clip.w * 0.5f + 0.5f) * W), py = int((0.5f - 0.5f * clip.y / clip.w) * H);
    const double expected = 0.7 / M_PI * double(s.sunIntensity) * std::sin(double(s.sunElevation) * M_PI / 180.0);
    EXPECT_NEAR(meanChannel(ours, 0, px - 1, py - 1, px + 2, py + 2), expected, 0.02 * expected);
    EXPECT_NEAR(meanChannel(ref.direct, 0, px - 1, py - 1, px + 2, py + 2), expected, 0.02 * expected);
}

// ---------------------------------------------------------------- glTF extensions

TEST(GltfExtensions, QuantizedMeshEqualsPlainWithinTheStep) {
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const Scene quant = loadGltf(kTestAssets + "/quant/quantized.gltf");
    ASSERT_EQ(plain.parts.size(), 1u);
    ASSERT_EQ(quant.parts.size(), 1u);
    const MeshPart &a = plain.parts[0], &b = quant.parts[0];
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    ASSERT_EQ(a.indices, b.indices);
    // steps: positions 3 m / 65534, normals 1/127 per component, uvs 2/65535 (then the transform's scale of 2)
    float maxP = 0, maxN = 0, maxT = 0;
    for (size_t i = 0; i < a.vertices.size(); ++i) {
        maxP = std::max(maxP, glm::length(a.vertices[i].position - b.vertices[i].position));
        maxN = std::max(maxN, glm::length(a.vertices[i].normal - b.vertices[i].normal));
        maxT = std::max(maxT, glm::length(a.vertices[i].uv - b.vertices[i].uv));
    }
    EXPECT_LT(maxP, 1e-4f);
    EXPECT_LT(maxN, 0.015f);
    EXPECT_LT(maxT, 1e-4f);
    // without the extension declared, integer positions are refused, and the message says why
    TempDir d;
    json j = json::parse(readText(kTestAssets + "/quant/quantized.gltf"));
    j.erase("extensionsUsed");
    j.erase("extensionsRequired");
    writeText(d.path() / "undeclared.gltf", j.dump());
    EXPECT_NE(loadError((d.path() / "undeclared.gltf").string()).find("KHR_mesh_quantization"), std::string::npos);
}

TEST(GltfExtensions, TextureTransformEqualsUvsTransformedByTheGenerator) {
    const Scene t = loadGltf(kTestAssets + "/texture_transform/transformed.gltf");
    const Scene b = loadGltf(kTestAssets + "/texture_transform/baked.gltf");
    ASSERT_EQ(t.parts.size(), 1u);
    ASSERT_EQ(b.parts.size(), 1u);
    ASSERT_EQ(t.parts[0].vertices.size(), b.parts[0].vertices.size());
    for (size_t i = 0; i < t.parts[0].vertices.size(); ++i)
        EXPECT_LT(glm::length(t.parts[0].vertices[i].uv - b.parts[0].vertices[i].uv), 1e-5f) << i;
    EXPECT_FALSE(hasWarning(t, "KHR_texture_transform"));
}

TEST(GltfExtensions, DracoMeshEqualsPlainWithinQuantization) {
    TempDir d;
    copyTexture(d.path());
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const fs::path p = writeDracoGlb(plain.parts[0], d.path(), "draco.glb");
    const Scene draco = loadGltf(p.string());
    ASSERT_EQ(draco.parts.size(), 1u);
    EXPECT_EQ(draco.triangleCount(), plain.triangleCount());
    // 16-bit positions over 3 m, 12-bit octahedral normals, 14-bit uvs over [0, 2]
    expectSameVertices(plain.parts[0], draco.parts[0], 1e-4f, 2e-3f, 5e-4f);
    EXPECT_NEAR(triangleArea(draco.parts[0]), triangleArea(plain.parts[0]), 1e-3 * triangleArea(plain.parts[0]));
    EXPECT_EQ(draco.materials.size(), 1u);
    // corrupt Draco data: an error naming Draco, not tinygltf's "invalid bufferView"
    std::string bytes = readText(p);
    for (size_t i = bytes.size() - 40; i < bytes.size(); ++i) bytes[i] = char(0x5a);
    const size_t jsonLen = size_t(uint8_t(bytes[12])) | size_t(uint8_t(bytes[13])) << 8;
    for (size_t i = 20 + jsonLen + 8; i < 20 + jsonLen + 8 + 16 && i < bytes.size(); ++i) bytes[i] = 0;
    writeText(d.path() / "corrupt.glb", bytes);
    const std::string e = loadError((d.path() / "corrupt.glb").string());
    EXPECT_NE(e.find("Draco"), std::string::npos) << e;
}

// A file written by another producer: Debian's draco_transcoder (package draco) compresses plain.gltf with its
// default quantization (11-bit positions, 8-bit normals, 10-bit texture coordinates) and writes its own JSON.
TEST(GltfExtensions, DracoTranscoderFileEqualsPlain) {
    if (!fs::exists("/usr/bin/draco_transcoder")) GTEST_SKIP() << "draco_transcoder not installed (package draco)";
    TempDir d;
    copyTexture(d.path());
    const std::string cmd = "/usr/bin/draco_transcoder -i " + kTestAssets + "/quant/plain.gltf -o " +
                            (d.path() / "transcoded.gltf").string() + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const Scene t = loadGltf((d.path() / "transcoded.gltf").string());
    ASSERT_EQ(t.parts.size(), 1u);
    EXPECT_EQ(t.triangleCount(), plain.triangleCount());
    expectSameVertices(plain.parts[0], t.parts[0], 3.0f / 2047.0f, 0.02f, 4.0f / 1023.0f);
    EXPECT_NEAR(triangleArea(t.parts[0]), triangleArea(plain.parts[0]), 0.01 * triangleArea(plain.parts[0]));
}

// Another producer of meshopt files: Debian's gltfpack (-cc) quantizes positions (KHR_mesh_quantization, 14 bits),
// normals (8-bit octahedral filter) and texture coordinates (normalized 16 bits rescaled by a KHR_texture_transform),
// reorders the vertices and compresses every view with EXT_meshopt_compression: all four code paths at once.
TEST(GltfExtensions, GltfpackFileEqualsPlain) {
    if (!fs::exists("/usr/bin/gltfpack")) GTEST_SKIP() << "gltfpack not installed (package gltfpack)";
    TempDir d;
    copyTexture(d.path());
    const std::string cmd = "/usr/bin/gltfpack -cc -i " + kTestAssets + "/quant/plain.gltf -o " +
                            (d.path() / "packed.gltf").string() + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const json j = json::parse(readText(d.path() / "packed.gltf"));
    ASSERT_TRUE(j.contains("extensionsRequired"));
    EXPECT_NE(j["extensionsRequired"].dump().find("EXT_meshopt_compression"), std::string::npos);
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const Scene p = loadGltf((d.path() / "packed.gltf").string());
    ASSERT_EQ(p.parts.size(), 1u);
    EXPECT_EQ(p.triangleCount(), plain.triangleCount());
    expectSameVertices(plain.parts[0], p.parts[0], 3.0f / 16383.0f, 0.02f, 1e-3f);
    EXPECT_NEAR(triangleArea(p.parts[0]), triangleArea(plain.parts[0]), 1e-3 * triangleArea(plain.parts[0]));
}

TEST(GltfExtensions, MeshoptMeshEqualsPlain) {
    TempDir d;
    copyTexture(d.path());
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const fs::path p = writeMeshoptGltf(plain.parts[0], d.path(), "meshopt.gltf");
    const Scene mo = loadGltf(p.string());
    ASSERT_EQ(mo.parts.size(), 1u);
    const MeshPart &a = plain.parts[0], &b = mo.parts[0];
    // lossless positions, uvs and indices: the same vertices in the same order, the same triangles (the index
    // codec may rotate the corners of a triangle, keeping its winding)
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    ASSERT_EQ(a.indices.size(), b.indices.size());
    int differing = 0;
    for (size_t t = 0; t + 2 < a.indices.size(); t += 3) {
        bool same = false;
        for (int r = 0; r < 3; ++r)
            same = same || (a.indices[t] == b.indices[t + size_t(r)] && a.indices[t + 1] == b.indices[t + size_t(r + 1) % 3] &&
                            a.indices[t + 2] == b.indices[t + size_t(r + 2) % 3]);
        differing += same ? 0 : 1;
    }
    EXPECT_EQ(differing, 0);
    float maxN = 0;
    for (size_t i = 0; i < a.vertices.size(); ++i) {
        EXPECT_EQ(a.vertices[i].position, b.vertices[i].position) << i;
        EXPECT_EQ(a.vertices[i].uv, b.vertices[i].uv) << i;
        maxN = std::max(maxN, glm::length(a.vertices[i].normal - b.vertices[i].normal));
    }
    EXPECT_LT(maxN, 0.02f);  // 8-bit octahedral normals
    // truncated compressed data: an error naming the view and meshopt
    json j = json::parse(readText(p));
    j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 8;
    writeText(d.path() / "truncated.gltf", j.dump());
    const std::string e = loadError((d.path() / "truncated.gltf").string());
    EXPECT_NE(e.find("meshopt"), std::string::npos) << e;
}

TEST(GltfExtensions, UnsupportedRequiredExtensionRefusedBeforeParsing) {
    TempDir d;
    json j = plainJson();
    // an accessor tinygltf itself would refuse ("invalid bufferView"): the extension is named first
    j["accessors"][3].erase("bufferView");
    j["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness"};
    j["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
    writeText(d.path() / "req.gltf", j.dump());
    const std::string e = loadError((d.path() / "req.gltf").string());
    EXPECT_NE(e.find("required extension 'KHR_materials_pbrSpecularGlossiness' is not supported"), std::string::npos) << e;
}

// The compressed, quantized and transformed files render as the plain ones do (direct light, 96x72).
TEST_F(GLTest, CompressedAndQuantizedRenderLikePlain) {
    TempDir d;
    copyTexture(d.path());
    const Scene plain = loadGltf(kTestAssets + "/quant/plain.gltf");
    const Camera cam = selectCamera(plain, "cam");
    const FloatImage ref = renderDirect(plain, cam, 96, 72);
    const Scene quant = loadGltf(kTestAssets + "/quant/quantized.gltf");
    const Scene draco = loadGltf(writeDracoGlb(plain.parts[0], d.path(), "draco.glb").string());
    const Scene mo = loadGltf(writeMeshoptGltf(plain.parts[0], d.path(), "meshopt.gltf").string());
    const std::pair<const char*, const Scene*> cases[] = {{"quantized", &quant}, {"draco", &draco}, {"meshopt", &mo}};
    for (const auto& [name, scene] : cases) {
        const FloatImage img = renderDirect(*scene, cam, 96, 72);
        const double rel = relativeMeanAbs(ref, img);
        std::printf("%s against plain: mean |difference| %.3f%% of the mean\n", name, 100 * rel);
        // 1%: quantized normals and positions move shading and silhouette pixels slightly
        EXPECT_LT(rel, 0.01) << name;
    }
    const Scene t = loadGltf(kTestAssets + "/texture_transform/transformed.gltf");
    const Scene b = loadGltf(kTestAssets + "/texture_transform/baked.gltf");
    const Camera top = selectCamera(t, "top");
    const double rel = relativeMeanAbs(renderDirect(b, top, 96, 72), renderDirect(t, top, 96, 72));
    EXPECT_LT(rel, 1e-3);
}

// ---------------------------------------------------------------- the binary: an OBJ through render and buffers

namespace {
std::string runDeepgi(const std::string& args, int* status) {
    const std::string cmd = std::string(DEEPGI_BINARY) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    if (!p) return out;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int st = pclose(p);
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return out;
}
}  // namespace

TEST(ObjLoader, RenderAndBuffersCommandsOpenObj) {
    TempDir d;
    const std::string room = kTestAssets + "/obj_room/room.obj";
    int status = -1;
    std::string out = runDeepgi("render " + room + " --size 32x32 --frames 1 --out " + (d.path() / "r").string(), &status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_TRUE(fs::exists(d.path() / "r" / "final.png")) << out;
    // geometry: 48-byte vertices (position, normal, uv, tangent) each with a 4-byte part index, 4-byte indices, and
    // per part 3 matrices + an id (208 bytes); textures: two 64x64 RGBA8 images with their full mip chains,
    // 4 * (4096 + 1024 + 256 + 64 + 16 + 4 + 1) bytes each
    static_assert(sizeof(Vertex) == 48, "Vertex: 3 + 3 + 2 + 4 floats");
    const Scene s = loadScene(room);
    size_t geometry = s.parts.size() * 208;
    for (const auto& p : s.parts) geometry += p.vertices.size() * (48 + 4) + p.indices.size() * 4;
    out = runDeepgi("buffers " + room + " --size 64x64", &status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_NE(out.find("scene geometry: " + std::to_string(geometry) + " bytes"), std::string::npos) << out;
    EXPECT_NE(out.find("scene textures: 43688 bytes"), std::string::npos) << out;
}

// A real public asset (DamagedHelmet, ../shared/scenes) compressed by gltfpack -cc (meshopt, quantization, texture
// transforms) and by draco_transcoder (Draco, 11-bit positions): same triangles, same bounds within the
// quantization step, and the same image (direct light, one camera for all) within 1 %, as for the small mesh
// (measured 0.04 % and 0.12 %; a wrong normal or UV decoding moves it by tens of percent).
TEST_F(GLTest, RealAssetCompressedByTheToolsRendersLikeTheOriginal) {
    const fs::path helmet = fs::path(DEEPGI_SHARED_SCENES) / "DamagedHelmet/glTF-Binary/DamagedHelmet.glb";
    if (!fs::exists(helmet) || !fs::exists("/usr/bin/gltfpack") || !fs::exists("/usr/bin/draco_transcoder"))
        GTEST_SKIP() << "needs " << helmet << ", gltfpack and draco_transcoder";
    TempDir d;
    const fs::path gp = d.path() / "helmet_meshopt.glb", dt = d.path() / "helmet_draco.glb";
    ASSERT_EQ(std::system(("/usr/bin/gltfpack -cc -i " + helmet.string() + " -o " + gp.string() + " > /dev/null 2>&1").c_str()), 0);
    ASSERT_EQ(std::system(("/usr/bin/draco_transcoder -i " + helmet.string() + " -o " + dt.string() + " > /dev/null 2>&1").c_str()), 0);
    const Scene original = loadGltf(helmet.string());
    Camera cam = framingCamera(original.bounds);
    const FloatImage ref = renderDirect(original, cam, 128, 128);
    for (const fs::path& p : {gp, dt}) {
        const Scene s = loadGltf(p.string());
        EXPECT_EQ(s.triangleCount(), original.triangleCount()) << p;
        EXPECT_LT(glm::length(s.bounds.lo - original.bounds.lo), 2e-3f * original.bounds.radius()) << p;
        EXPECT_LT(glm::length(s.bounds.hi - original.bounds.hi), 2e-3f * original.bounds.radius()) << p;
        const double rel = relativeMeanAbs(ref, renderDirect(s, cam, 128, 128));
        std::printf("%s against the original: mean |difference| %.2f%% of the mean\n", p.filename().c_str(), 100 * rel);
        EXPECT_LT(rel, 0.01) << p;
    }
}

// Load progress (issue 10, big scenes): both loaders report stages with a fraction that never decreases and end
// at "done" 1, so a command can show how far a long load is.
TEST(SceneLoad, ProgressRisesToDone) {
    for (const std::string path : {kTestAssets + "/obj_room/room.obj", std::string(DEEPGI_ASSET_DIR) + "/hard/furnace/furnace.gltf"}) {
        std::vector<std::pair<std::string, double>> calls;
        GltfLoadOptions o;
        o.progress = [&](const char* stage, double f) { calls.emplace_back(stage, f); };
        const Scene s = loadScene(path, o);
        ASSERT_GE(calls.size(), 3u) << path;
        EXPECT_EQ(calls.front().first, "reading") << path;
        EXPECT_EQ(calls.front().second, 0.0) << path;
        EXPECT_EQ(calls.back().first, "done") << path;
        EXPECT_EQ(calls.back().second, 1.0) << path;
        for (size_t i = 1; i < calls.size(); ++i) EXPECT_GE(calls[i].second, calls[i - 1].second) << path << " call " << i;
        EXPECT_GT(s.triangleCount(), 0u);
    }
}

// ---- Real public files (assets/public: other producers' files, unchanged, with their licences) -------------------

namespace {

const std::string kPublicAssets = std::string(DEEPGI_ASSET_DIR) + "/public";

// The corner uvs of a quad of raw uvs [0, s]^2 under KHR_texture_transform: translation x rotation x scale, the
// rotation counter-clockwise in glTF's V-down uv space (u' = cos u + sin v, v' = -sin u + cos v). That is the
// direction the sample model's markers check, and Blender's, Babylon.js's and three.js's; the GLSL listing in the
// extension's text has the opposite sign (KhronosGroup/glTF issue 1563). Following that listing, deepgi's render
// of this file pointed the rotation quad's arrow at the red "opposite direction" marker.
std::vector<glm::vec2> specTransformedCorners(float s, glm::vec2 offset, float rotation, glm::vec2 scale) {
    std::vector<glm::vec2> out;
    for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(s, 0), glm::vec2(0, s), glm::vec2(s, s)}) {
        const glm::vec2 k = uv * scale;
        const float c = std::cos(rotation), n = std::sin(rotation);
        out.push_back(glm::vec2(c * k.x + n * k.y, -n * k.x + c * k.y) + offset);
    }
    return out;
}

}  // namespace

// Box_Draco.glb (Draco's own tools, KHR_draco_mesh_compression required) decodes to the box of the uncompressed
// Box.glb: the same 12 triangles, each vertex within Draco's quantization of one of the original's.
TEST(GltfExtensions, PublicAssetDracoBoxEqualsTheUncompressedBox) {
    const Scene plain = loadGltf(kPublicAssets + "/draco_box/Box.glb");
    const Scene draco = loadGltf(kPublicAssets + "/draco_box/Box_Draco.glb");
    ASSERT_EQ(plain.parts.size(), 1u);
    ASSERT_EQ(draco.parts.size(), 1u);
    EXPECT_EQ(plain.triangleCount(), 12u) << "the unit box";
    EXPECT_EQ(draco.triangleCount(), plain.triangleCount());
    // The box spans 1 m: 11-bit positions are within 1 mm, normals of a box's faces within 1 %.
    expectSameVertices(plain.parts[0], draco.parts[0], 1e-3f, 1e-2f, 1.0f);
    expectSameVertices(draco.parts[0], plain.parts[0], 1e-3f, 1e-2f, 1.0f);
    EXPECT_NEAR(triangleArea(draco.parts[0]), 6.0, 6e-3) << "six unit faces";
    EXPECT_NEAR(triangleArea(plain.parts[0]), 6.0, 1e-6);
}

// Microsoft's TextureTransformTest: each quad's uvs after load are its raw uvs under the transform its material
// names, computed with the specification's matrix from the values its README states (offsets (0.5, 0), (0, 0.5),
// (0.5, 0.5) on uvs [0, 0.5]^2; rotation 22.5 degrees, scale 1.5, and offset (-0.2, -0.1) + rotation 0.3 + scale
// 1.5 on uvs [0, 1]^2). No warning: the extension is supported, not ignored.
TEST(GltfExtensions, PublicAssetTextureTransformTestQuadsCarryTheSpecTransform) {
    const Scene s = loadGltf(kPublicAssets + "/texture_transform_test/TextureTransformTest.gltf");
    EXPECT_FALSE(hasWarning(s, "KHR_texture_transform"));
    const float r225 = 0.39269908169872414f;
    const std::map<std::string, std::vector<glm::vec2>> expected = {
        {"Offset U", specTransformedCorners(0.5f, {0.5f, 0.0f}, 0.0f, {1, 1})},
        {"Offset V", specTransformedCorners(0.5f, {0.0f, 0.5f}, 0.0f, {1, 1})},
        {"Offset UV", specTransformedCorners(0.5f, {0.5f, 0.5f}, 0.0f, {1, 1})},
        {"Rotation", specTransformedCorners(1.0f, {0, 0}, r225, {1, 1})},
        {"Scale", specTransformedCorners(1.0f, {0, 0}, 0.0f, {1.5f, 1.5f})},
        {"All", specTransformedCorners(1.0f, {-0.2f, -0.1f}, 0.3f, {1.5f, 1.5f})},
    };
    int checked = 0;
    for (const MeshPart& p : s.parts) {
        ASSERT_GE(p.material, 0);
        const auto it = expected.find(s.materials[size_t(p.material)].name);
        if (it == expected.end()) continue;  // the markers: untransformed
        ++checked;
        EXPECT_EQ(p.indices.size(), 6u) << it->first << ": two triangles";
        std::vector<bool> cornerSeen(4, false);
        for (const Vertex& v : p.vertices) {
            size_t best = 0;
            for (size_t k = 1; k < 4; ++k)
                if (glm::length(v.uv - it->second[k]) < glm::length(v.uv - it->second[best])) best = k;
            EXPECT_LT(glm::length(v.uv - it->second[best]), 1e-5f)
                << it->first << ": uv (" << v.uv.x << ", " << v.uv.y << ") is no corner of the spec's quad";
            cornerSeen[best] = true;
        }
        for (size_t k = 0; k < 4; ++k) EXPECT_TRUE(cornerSeen[k]) << it->first << ": corner " << k << " missing";
    }
    EXPECT_EQ(checked, 6) << "six transformed quads";
}

// gltfpack's own pirate.glb (meshoptimizer's demo: KHR_mesh_quantization and EXT_meshopt_compression, both
// required) against the OBJ it was packed from: the same triangles, each vertex within the quantization of one of
// the OBJ's (measured 0.1 mm; 1 mm allowed), the same surface area within 0.5 % (measured 0.04 %).
TEST(GltfExtensions, PublicAssetMeshoptPirateEqualsItsObj) {
    const Scene packed = loadScene(kPublicAssets + "/meshopt_pirate/pirate.glb");
    const Scene obj = loadScene(kPublicAssets + "/meshopt_pirate/pirate.obj");
    EXPECT_GT(obj.triangleCount(), 1000u);
    EXPECT_EQ(packed.triangleCount(), obj.triangleCount());
    std::vector<glm::vec3> objPositions;
    double objArea = 0.0, packedArea = 0.0;
    for (const MeshPart& p : obj.parts) {
        for (const Vertex& v : p.vertices) objPositions.push_back(v.position);  // loaded in world space
        objArea += triangleArea(p);
    }
    int unmatched = 0, vertices = 0;
    float worst = 0.0f;  // the largest distance of a packed vertex to its nearest OBJ vertex
    for (const MeshPart& p : packed.parts) {
        packedArea += triangleArea(p);
        for (const Vertex& v : p.vertices) {
            ++vertices;
            float nearest = 1e30f;
            for (const glm::vec3& q : objPositions) nearest = std::min(nearest, glm::length(v.position - q));
            worst = std::max(worst, nearest);
            unmatched += !(nearest <= 1e-3f);
        }
    }
    std::printf("pirate.glb: %zu triangles, %d vertices, farthest from the OBJ's %.2e m; area %.4f against %.4f m^2\n",
                packed.triangleCount(), vertices, double(worst), packedArea, objArea);
    EXPECT_EQ(unmatched, 0) << "of " << vertices << " vertices of the packed file";
    EXPECT_NEAR(packedArea, objArea, 5e-3 * objArea);
}
