// glTF animation (issue 14): TRS channels sampled against analytic positions, LINEAR / STEP / CUBICSPLINE, through the
// loader, and the headless `deepgi render --time / --animate / --sequence`.
#include "renderer/scene/animation.h"
#include "renderer/scene/scene_loader.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace deepgi;

namespace {

// A glTF with four animated nodes (and a triangle on the first):
//   "linear":  translation LINEAR (0,0,0) at 0 s -> (2,0,0) at 2 s
//   "rotating": rotation LINEAR 0 -> 90 deg about +Y over 0..2 s
//   "cubic":   translation CUBICSPLINE 0 -> (1,0,0) over 0..1 s, out-tangent (2,0,0) at key 0, other tangents 0
//   "step":    translation STEP (0,0,0) at 0 s, (0,5,0) at 1 s
// and a skin, so the loader's one skin warning shows.
std::string writeAnimatedGltf(const std::string& dir) {
    std::filesystem::create_directories(dir);
    const float s45 = std::sin(glm::radians(45.0f)), c45 = std::cos(glm::radians(45.0f));
    std::vector<std::vector<float>> blocks = {
        {0, 0, 0, 1, 0, 0, 0, 1, 0},                   // 0 triangle
        {0, 2},                                        // 1 times 0..2
        {0, 0, 0, 2, 0, 0},                            // 2 linear translation
        {0, 0, 0, 1, 0, s45, 0, c45},                  // 3 rotation quaternions (x, y, z, w)
        {0, 1},                                        // 4 times 0..1
        {0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0},  // 5 cubic: in, value, out per key
        {0, 0, 0, 0, 5, 0},                            // 6 step translation
    };
    std::string bin;
    std::ostringstream views, accessors;
    const char* types[] = {"VEC3", "SCALAR", "VEC3", "VEC4", "SCALAR", "VEC3", "VEC3"};
    const int comps[] = {3, 1, 3, 4, 1, 3, 3};
    for (size_t i = 0; i < blocks.size(); ++i) {
        const size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(blocks[i].data()), blocks[i].size() * sizeof(float));
        views << (i ? "," : "") << R"({"buffer":0,"byteOffset":)" << offset << R"(,"byteLength":)" << blocks[i].size() * 4 << "}";
        accessors << (i ? "," : "") << R"({"bufferView":)" << i << R"(,"componentType":5126,"count":)" << blocks[i].size() / size_t(comps[i])
                  << R"(,"type":")" << types[i] << '"';
        if (i == 0) accessors << R"(,"min":[0,0,0],"max":[1,1,0])";
        if (i == 1) accessors << R"(,"min":[0],"max":[2])";
        if (i == 4) accessors << R"(,"min":[0],"max":[1])";
        accessors << "}";
    }
    std::ofstream(dir + "/anim.bin", std::ios::binary) << bin;
    std::ofstream(dir + "/anim.gltf") << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2,3]}],
      "nodes":[{"name":"linear","mesh":0},{"name":"rotating"},{"name":"cubic"},{"name":"step"}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
      "skins":[{"joints":[1]}],
      "animations":[{"name":"all","samplers":[
          {"input":1,"output":2,"interpolation":"LINEAR"},{"input":1,"output":3},
          {"input":4,"output":5,"interpolation":"CUBICSPLINE"},{"input":4,"output":6,"interpolation":"STEP"}],
        "channels":[{"sampler":0,"target":{"node":0,"path":"translation"}},{"sampler":1,"target":{"node":1,"path":"rotation"}},
                    {"sampler":2,"target":{"node":2,"path":"translation"}},{"sampler":3,"target":{"node":3,"path":"translation"}}]}],
      "accessors":[)" << accessors.str() << R"(],"bufferViews":[)" << views.str() << R"(],
      "buffers":[{"uri":"anim.bin","byteLength":)" << bin.size() << "}]}";
    return dir + "/anim.gltf";
}

glm::vec3 origin(const Scene& s, int node) { return glm::vec3(s.nodes[size_t(node)].world[3]); }

// The Hermite curve of the "cubic" node at u in [0, 1] (glTF 2.0 Appendix C, interval length 1).
float cubicX(float u) { return 2.0f * (u * u * u - 2 * u * u + u) + (-2 * u * u * u + 3 * u * u); }

}  // namespace

TEST(Animation, ChannelsMatchAnalyticPositions) {
    Scene s = loadScene(writeAnimatedGltf(testing::TempDir() + "/anim_analytic"));
    ASSERT_EQ(s.nodes.size(), 4u);
    ASSERT_EQ(s.animations.size(), 1u);
    ASSERT_EQ(s.animations[0].channels.size(), 4u);
    EXPECT_FLOAT_EQ(s.animationDuration(), 2.0f);
    int skinWarnings = 0;
    for (const auto& w : s.warnings) skinWarnings += w.find("skin") != std::string::npos;
    EXPECT_EQ(skinWarnings, 1);

    for (float t : {0.0f, 0.25f, 0.5f, 0.999f, 1.0f, 1.5f, 2.0f, 3.0f}) {
        applyAnimation(s, t);
        const float tl = std::min(t, 2.0f), tc = std::min(t, 1.0f);
        EXPECT_NEAR(origin(s, 0).x, tl, 1e-5f) << "t " << t;  // LINEAR translation, clamped after the last key
        // LINEAR rotation: slerp at constant angular speed, 45 deg/s about +Y: (1,0,0) -> (cos a, 0, -sin a).
        const float a = glm::radians(45.0f * tl);
        const glm::vec3 x = glm::vec3(s.nodes[1].world * glm::vec4(1, 0, 0, 0));
        EXPECT_NEAR(x.x, std::cos(a), 1e-5f) << "t " << t;
        EXPECT_NEAR(x.z, -std::sin(a), 1e-5f) << "t " << t;
        EXPECT_NEAR(glm::length(s.nodes[1].local.rotation), 1.0f, 1e-6f);
        EXPECT_NEAR(origin(s, 2).x, cubicX(tc), 1e-5f) << "t " << t;      // CUBICSPLINE
        EXPECT_NEAR(origin(s, 3).y, t >= 1.0f ? 5.0f : 0.0f, 0.0f) << "t " << t;  // STEP: holds until the next key
    }
    // The mesh on the animated node moves with it (its part's model matrix).
    applyAnimation(s, 1.0f);
    const glm::vec3 v = glm::vec3(s.partModel(0) * glm::vec4(s.parts[0].vertices[1].position, 1.0f));
    EXPECT_NEAR(glm::length(v - glm::vec3(2.0f, 0.0f, 0.0f)), 0.0f, 1e-5f);  // (1,0,0) + (1,0,0)
}

TEST(Animation, SlerpTakesTheShorterArcAndCubicRotationsAreNormalised) {
    AnimationChannel c;
    c.path = AnimationPath::Rotation;
    c.times = {0.0f, 1.0f};
    // 0 deg and 270 deg about Z written with w < 0 (the same as -90 deg): the shorter arc goes through -45 deg.
    const glm::quat q1 = glm::angleAxis(glm::radians(270.0f), glm::vec3(0, 0, 1));
    c.values = {0, 0, 0, 1, q1.x, q1.y, q1.z, q1.w};
    const glm::vec4 m = sampleChannel(c, 0.5f);
    const glm::quat q(m.w, m.x, m.y, m.z);
    const glm::vec3 x = q * glm::vec3(1, 0, 0);
    EXPECT_NEAR(x.x, std::cos(glm::radians(-45.0f)), 1e-5f);
    EXPECT_NEAR(x.y, std::sin(glm::radians(-45.0f)), 1e-5f);
    c.interpolation = Interpolation::CubicSpline;
    c.values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,  0, 0, 0, 0, q1.x, q1.y, q1.z, q1.w, 0, 0, 0, 0};
    EXPECT_NEAR(glm::length(sampleChannel(c, 0.3f)), 1.0f, 1e-6f);
}

// `deepgi render --time`, `--animate FPS --frames N --sequence`: the frames exist, and a time past the scene's
// animations is accepted (clamped, as glTF defines).
TEST(Animation, HeadlessRenderAtATimeAndAsASequence) {
    const std::string dir = testing::TempDir() + "/anim_cli";
    const std::string file = writeAnimatedGltf(dir);
    const std::string out = dir + "/out";
    std::filesystem::remove_all(out);
    const std::string base = std::string(DEEPGI_BINARY) + " render " + file + " --size 32x24 --out " + out;
    ASSERT_EQ(std::system((base + " --time 0.5 --frames 1 > /dev/null 2>&1").c_str()), 0);
    EXPECT_TRUE(std::filesystem::exists(out + "/final.png"));
    ASSERT_EQ(std::system((base + " --animate 10 --frames 3 --sequence > /dev/null 2>&1").c_str()), 0);
    for (int f = 0; f < 3; ++f) {
        char name[32];
        std::snprintf(name, sizeof(name), "/frame_%05d.png", f);
        EXPECT_TRUE(std::filesystem::exists(out + name)) << name;
    }
    EXPECT_NE(std::system((base + " --time -1 > /dev/null 2>&1").c_str()), 0);  // a negative time is refused
}
