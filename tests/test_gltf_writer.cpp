// Save (issue 14): saveGltf then loadScene gives the same scene: nodes, transforms, triangles, materials, lights,
// cameras, animations, bounds, and the same rendered image.
#include "gl_fixture.h"

#include "renderer/core/image_compare.h"
#include "renderer/scene/animation.h"
#include "renderer/scene/gltf_writer.h"
#include "renderer/scene/scene_loader.h"

#include <glm/gtc/quaternion.hpp>

#include <filesystem>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

// The Cornell room with edits: the box moved, turned and scaled; a textured, emissive, masked material; a point
// light under a parent node; a hidden node; an animation.
std::shared_ptr<Scene> editedScene() {
    auto s = cornellScene();
    int box = -1;
    for (size_t i = 0; i < s->nodes.size(); ++i)
        if (s->nodes[i].name.rfind("box", 0) == 0) box = int(i);
    s->nodes[size_t(box)].local.translation = glm::vec3(0.5f, 0.0f, 0.1f);
    s->nodes[size_t(box)].local.rotation = glm::angleAxis(glm::radians(20.0f), glm::vec3(0, 1, 0));
    s->nodes[size_t(box)].local.scale = glm::vec3(1.0f, 0.8f, 1.0f);
    Image img;
    img.name = "checker";
    img.width = img.height = 4;
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c) img.rgba8.push_back(c == 3 ? 255 : (((i % 4) + i / 4) % 2 ? 230 : 40));
    s->images.push_back(img);
    Texture t;
    t.image = 0;
    t.magFilter = FilterMode::Nearest;
    t.wrapS = WrapMode::ClampToEdge;
    s->textures.push_back(t);
    s->materials[0].baseColorTexture = 0;
    s->materials[1].emissiveFactor = glm::vec3(3.0f, 0.5f, 0.0f);
    s->materials[2].alphaMode = AlphaMode::Mask;
    s->materials[2].alphaCutoff = 0.3f;
    s->materials[2].doubleSided = true;
    Light p;
    p.name = "lamp";
    p.type = LightType::Point;
    p.color = glm::vec3(1.0f, 0.9f, 0.7f);
    p.intensity = 2.0f;
    p.range = 5.0f;
    s->lights.push_back(p);
    Transform lt;
    lt.translation = glm::vec3(0.2f, 0.0f, 0.0f);
    const int lampNode = s->addNode("lamp", box, lt);
    s->lights.back().node = lampNode;
    s->nodes[size_t(s->parts[1].node)].visible = false;  // the back wall
    Animation a;
    a.name = "slide";
    AnimationChannel c;
    c.node = box;
    c.times = {0.0f, 1.0f};
    c.values = {0.5f, 0.0f, 0.1f, 0.2f, 0.0f, -0.3f};
    a.channels.push_back(c);
    s->animations.push_back(a);
    s->linkNodes();
    s->updateWorldTransforms();
    return s;
}

}  // namespace

TEST_F(GLTest, SaveThenLoadGivesTheSameScene) {
    auto a = editedScene();
    const std::string dir = testing::TempDir() + "/gltf_writer";
    std::filesystem::create_directories(dir);
    for (const char* name : {"/saved.gltf", "/saved.glb"}) {
        const std::string path = dir + name;
        saveGltf(*a, path);
        auto b = std::make_shared<Scene>(loadScene(path));
        // The loader numbers nodes and lights in its walk of the tree: compare them by name.
        ASSERT_EQ(b->nodes.size(), a->nodes.size()) << name;
        auto nodeOf = [](const Scene& sc, const std::string& n) {
            for (size_t i = 0; i < sc.nodes.size(); ++i)
                if (sc.nodes[i].name == n) return int(i);
            return -1;
        };
        for (const SceneNode& na : a->nodes) {
            const int j = nodeOf(*b, na.name);
            ASSERT_GE(j, 0) << na.name;
            const SceneNode& nb = b->nodes[size_t(j)];
            EXPECT_EQ(nb.parent < 0 ? "" : b->nodes[size_t(nb.parent)].name, na.parent < 0 ? "" : a->nodes[size_t(na.parent)].name);
            EXPECT_EQ(nb.visible, na.visible) << na.name;
            EXPECT_EQ(nb.parts.size(), na.parts.size()) << na.name;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) EXPECT_NEAR(nb.world[c][r], na.world[c][r], 1e-5f) << name << " node " << na.name;
        }
        EXPECT_EQ(b->triangleCount(), a->triangleCount());
        ASSERT_EQ(b->materials.size(), a->materials.size());
        for (size_t i = 0; i < a->materials.size(); ++i) {
            const Material &ma = a->materials[i], &mb = b->materials[i];
            EXPECT_NEAR(glm::length(ma.baseColorFactor - mb.baseColorFactor), 0.0f, 1e-6f);
            EXPECT_NEAR(glm::length(ma.emissiveFactor - mb.emissiveFactor), 0.0f, 1e-5f);
            EXPECT_EQ(ma.baseColorTexture, mb.baseColorTexture);
            EXPECT_EQ(int(ma.alphaMode), int(mb.alphaMode));
            EXPECT_FLOAT_EQ(ma.alphaCutoff, mb.alphaCutoff);
            EXPECT_EQ(ma.doubleSided, mb.doubleSided);
        }
        ASSERT_EQ(b->images.size(), 1u);
        EXPECT_EQ(b->images[0].rgba8, a->images[0].rgba8);  // PNG is lossless
        EXPECT_EQ(b->textures[0].magFilter, FilterMode::Nearest);
        EXPECT_EQ(b->textures[0].wrapS, WrapMode::ClampToEdge);
        ASSERT_EQ(b->lights.size(), a->lights.size());
        for (const Light& la : a->lights) {
            const Light* lb = nullptr;
            for (const Light& l : b->lights) if (l.name == la.name) lb = &l;
            ASSERT_TRUE(lb) << la.name;
            EXPECT_EQ(int(lb->type), int(la.type));
            EXPECT_NEAR(glm::length(lb->position - la.position), 0.0f, 1e-5f) << la.name;
            EXPECT_NEAR(glm::length(lb->direction - la.direction), 0.0f, 1e-5f) << la.name;
            EXPECT_FLOAT_EQ(lb->intensity, la.intensity);
            EXPECT_FLOAT_EQ(lb->range, la.range);
        }
        ASSERT_EQ(b->cameras.size(), 1u);
        EXPECT_NEAR(b->cameras[0].yfov, a->cameras[0].yfov, 1e-6f);
        ASSERT_EQ(b->animations.size(), 1u);
        EXPECT_EQ(b->animations[0].channels[0].values, a->animations[0].channels[0].values);
        EXPECT_EQ(b->nodes[size_t(b->animations[0].channels[0].node)].name, a->nodes[size_t(a->animations[0].channels[0].node)].name);
        // Bounds of the world now (the loader's rest pose = the saved pose).
        const Aabb ba = a->currentBounds(), bb = b->bounds;
        EXPECT_NEAR(glm::length(ba.lo - bb.lo) + glm::length(ba.hi - bb.hi), 0.0f, 1e-4f);

        // The rendered image: the same within 1/255 mean and 2% of pixels over 4/255 (float roundoff of the
        // vertices going through the node-local space and back).
        std::vector<unsigned char> img[2];
        int k = 0;
        for (const auto& sc : {a, b}) {
            auto r = rendererFor(sc, 80, 60, "front");
            Settings s;
            s.probesEnabled = false;
            for (int f = 0; f < 3; ++f) r->render(s);
            img[k++] = r->readDisplay();
        }
        double sum = 0;
        int over = 0;
        for (size_t i = 0; i < img[0].size(); ++i) {
            const int d = std::abs(int(img[0][i]) - int(img[1][i]));
            sum += d;
            over += d > 4;
        }
        std::printf("save/load %s: mean |diff| %.3f /255, %.2f%% of channels over 4/255\n", name, sum / img[0].size(),
                    100.0 * over / img[0].size());
        EXPECT_LT(sum / img[0].size(), 1.0) << name;
        EXPECT_LT(double(over) / img[0].size(), 0.02) << name;
    }
    EXPECT_THROW(saveGltf(*a, dir + "/no/such/folder/x.gltf"), std::runtime_error);
}
