// The scene tree (issue 14): nodes kept at load, live transforms, visibility, the Object ID buffer and picking.
#include "gl_fixture.h"

#include "renderer/passes/buffer_view_pass.h"
#include "renderer/probes/probe_tracer.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/scene_loader.h"

#include <glm/gtc/matrix_transform.hpp>

#include <filesystem>
#include <fstream>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

// A floor (node 0) and a box (node 1), a sun, a camera looking down at them.
std::shared_ptr<Scene> floorAndBox(glm::vec3 sun = glm::vec3(-0.4f, -1.0f, -0.3f)) {
    auto s = std::make_shared<Scene>();
    const int white = addMaterial(*s, glm::vec3(0.7f)), red = addMaterial(*s, glm::vec3(0.8f, 0.1f, 0.1f));
    addFloor(*s, 3.0f, 0.0f, white);
    addBox(*s, {-0.3f, 0.0f, -0.3f}, {0.3f, 0.6f, 0.3f}, red, false);
    addSun(*s, sun, 3.0f);
    addCamera(*s, "top", {0.0f, 4.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 60.0f);
    s->computeBounds();
    return s;
}

int nodeNamed(const Scene& s, const std::string& prefix) {
    for (size_t i = 0; i < s.nodes.size(); ++i)
        if (s.nodes[i].name.rfind(prefix, 0) == 0) return int(i);
    return -1;
}

}  // namespace

TEST(SceneGraph, BuiltInScenesHaveOneNodePerObject) {
    auto s = floorAndBox();
    const int floorNode = s->parts[0].node, box = nodeNamed(*s, "box");
    ASSERT_GE(floorNode, 0);
    ASSERT_GE(box, 0);
    EXPECT_EQ(s->nodes[size_t(box)].parts.size(), 6u);  // the box's six quads: one object
    for (const auto& p : s->parts) EXPECT_GE(p.node, 0);
    ASSERT_EQ(s->lights.size(), 1u);
    EXPECT_GE(s->lights[0].node, 0);
    EXPECT_EQ(s->nodes[size_t(s->lights[0].node)].light, 0);
    EXPECT_EQ(s->partModel(1), glm::mat4(1.0f));  // unmoved: exactly the identity
}

TEST(SceneGraph, MovingANodeMovesItsPartsChildrenAndLights) {
    auto s = floorAndBox();
    const int box = nodeNamed(*s, "box");
    const Aabb before = s->nodeBounds(box);
    s->nodes[size_t(box)].local.translation = glm::vec3(1.0f, 0.0f, -0.5f);
    s->updateWorldTransforms();
    const Aabb after = s->nodeBounds(box);
    EXPECT_NEAR(after.lo.x - before.lo.x, 1.0f, 1e-6f);
    EXPECT_NEAR(after.hi.z - before.hi.z, -0.5f, 1e-6f);
    // A child follows its parent: the sun's node under the box, turned 90 degrees about Y by the parent.
    const int sun = s->lights[0].node;
    s->nodes[size_t(sun)].parent = box;
    s->nodes[size_t(sun)].local = Transform{};  // points down -Z in the box's frame
    s->nodes[size_t(box)].local.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    s->linkNodes();
    s->updateWorldTransforms();
    EXPECT_NEAR(s->lights[0].position.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s->lights[0].direction.x, -1.0f, 1e-5f);  // -Z turned +90 deg about Y = -X
    // Hidden parent: the light and the box are gone for everyone.
    s->nodes[size_t(box)].visible = false;
    EXPECT_FALSE(s->partVisible(s->nodes[size_t(box)].parts[0]));
    EXPECT_TRUE(effectiveLights(*s, Settings{}).empty());
}

TEST(SceneGraph, GltfLoadKeepsNodesNamesAndHierarchy) {
    // parent (translated, scaled) -> child (matrix: rotation 90 deg about Z + translation) with a triangle.
    const std::string dir = testing::TempDir() + "/scene_graph_gltf";
    std::filesystem::create_directories(dir);
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::string bin(reinterpret_cast<const char*>(tri), sizeof(tri));
    std::ofstream(dir + "/t.bin", std::ios::binary) << bin;
    std::ofstream(dir + "/t.gltf") << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
      "nodes":[{"name":"parent","translation":[1,2,3],"scale":[2,2,2],"children":[1]},
               {"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 0,0,5,1],"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
      "bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"uri":"t.bin","byteLength":36}]})";
    Scene s = loadScene(dir + "/t.gltf", GltfLoadOptions{});
    ASSERT_EQ(s.nodes.size(), 2u);
    EXPECT_EQ(s.nodes[0].name, "parent");
    EXPECT_EQ(s.nodes[1].name, "node[1]");
    EXPECT_EQ(s.nodes[1].parent, 0);
    ASSERT_EQ(s.roots.size(), 1u);
    EXPECT_NEAR(s.nodes[1].local.translation.z, 5.0f, 1e-6f);
    EXPECT_NEAR(std::abs(s.nodes[1].local.rotation.z), std::sqrt(0.5f), 1e-5f);  // 90 deg about Z
    ASSERT_EQ(s.parts.size(), 1u);
    EXPECT_EQ(s.parts[0].node, 1);
    // Vertex (1,0,0): rotated to (0,1,0), +(0,0,5), scaled by 2, +(1,2,3) = (1, 4, 13).
    EXPECT_NEAR(glm::length(s.parts[0].vertices[1].position - glm::vec3(1, 4, 13)), 0.0f, 1e-5f);
    EXPECT_EQ(s.partModel(0), glm::mat4(1.0f));
    // Moving the parent moves the triangle by the same amount in world space.
    s.nodes[0].local.translation += glm::vec3(0, 0, 1);
    s.updateWorldTransforms();
    const glm::vec3 moved = glm::vec3(s.partModel(0) * glm::vec4(s.parts[0].vertices[1].position, 1.0f));
    EXPECT_NEAR(glm::length(moved - glm::vec3(1, 4, 14)), 0.0f, 1e-5f);
}

// The Object ID buffer shows which node each pixel sees; moving and hiding the box change it, and the shadow
// maps and ray tracers follow.
TEST_F(GLTest, ObjectIdPickingFollowsMovesAndVisibility) {
    auto scene = floorAndBox();
    const int box = nodeNamed(*scene, "box"), floorNode = scene->parts[0].node;
    auto renderer = rendererFor(scene, 64, 64, "top", sceneEditing());
    Renderer& r = *renderer;
    Settings s;
    s.indirect = false;
    EXPECT_EQ(r.objectAt(32, 32), -1);  // no frame yet
    r.render(s);
    ASSERT_TRUE(r.textures().has("Object ID"));
    EXPECT_EQ(r.objectAt(32, 32), box);
    EXPECT_EQ(r.objectAt(2, 2), floorNode);
    EXPECT_EQ(r.objectAt(-1, 2), -1);
    const FloatImage ids = r.readLayer("Object ID 1");
    EXPECT_EQ(int(ids.at(32, 32, 0)), box + 1);

    // Box moved 1 m along +X: seen right of the centre (the camera looks down -Y with +X to the right).
    scene->nodes[size_t(box)].local.translation = glm::vec3(1.0f, 0.0f, 0.0f);
    scene->updateWorldTransforms();
    r.sceneChanged(SceneChange::Transforms);
    r.render(s);
    EXPECT_EQ(r.objectAt(32, 32), floorNode);
    const int px = 32 + int(std::round(1.0f / (2.0f * 4.0f * std::tan(glm::radians(30.0f))) * 64.0f));
    EXPECT_EQ(r.objectAt(px, 32), box);

    // Hidden: not drawn (the floor shows) and casts no shadow (the lit floor is as bright as anywhere).
    scene->nodes[size_t(box)].visible = false;
    r.sceneChanged(SceneChange::Visibility);
    r.render(s);
    EXPECT_EQ(r.objectAt(px, 32), floorNode);

    // The ray tracers see the moved box (visible again): a ray down through its new centre hits its top at y = 0.6.
    scene->nodes[size_t(box)].visible = true;
    ProbeTracer tracer(*scene);
    ProbeHit h = tracer.intersect({1.0f, 3.0f, 0.0f}, {0, -1, 0}, 0.0f, 10.0f);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.position.y, 0.6f, 1e-4f);
    // ... and follow a later edit through update().
    scene->nodes[size_t(box)].local.translation = glm::vec3(0.0f);
    scene->updateWorldTransforms();
    tracer.update(*scene);
    h = tracer.intersect({1.0f, 3.0f, 0.0f}, {0, -1, 0}, 0.0f, 10.0f);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.position.y, 0.0f, 1e-4f);  // the floor: the box went back to the origin
    scene->nodes[size_t(box)].visible = false;
    tracer.update(*scene);
    h = tracer.intersect({0.0f, 3.0f, 0.0f}, {0, -1, 0}, 0.0f, 10.0f);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.position.y, 0.0f, 1e-4f);  // hidden: traced through
}

// A moved box's shadow moves with it: the shadow maps are re-rendered after sceneChanged.
TEST_F(GLTest, ShadowFollowsAMovedObject) {
    // Light travelling along (-1, -1, 0): the box (|x| < 0.3, height 0.6) shades the floor over x in [-0.9, -0.3].
    auto scene = floorAndBox(glm::vec3(-1.0f, -1.0f, 0.0f));
    const int box = nodeNamed(*scene, "box");
    auto renderer = rendererFor(scene, 64, 64, "top", sceneEditing());
    Renderer& r = *renderer;
    Settings s;
    s.indirect = false;
    // Floor point (-0.6, 0, 0): pixel 32 - 0.6 / (2 * 4 * tan 30 deg) * 64 = 23.7 (the camera is 4 above, 60 deg fov).
    const int x = 24, y = 32;
    r.render(s);
    const float shadowed = r.readLayer("Final Radiance").at(x, y, 0), lit = r.readLayer("Final Radiance").at(4, y, 0);
    EXPECT_LT(shadowed, 0.2f * lit);
    scene->nodes[size_t(box)].local.translation = glm::vec3(1.5f, 0.0f, 0.0f);  // shadow now over x in [0.6, 1.2]
    scene->updateWorldTransforms();
    r.sceneChanged(SceneChange::Transforms);
    r.render(s);
    const FloatImage after = r.readLayer("Final Radiance");
    EXPECT_NEAR(after.at(x, y, 0), after.at(4, y, 0), 0.05f * after.at(4, y, 0));  // the old shadow is gone
    EXPECT_LT(after.at(32 + 12, y, 0), 0.2f * after.at(4, y, 0));  // x = 0.87: in the new shadow
    EXPECT_EQ(r.objectAt(32 + 12, y), scene->parts[0].node);       // ... on the floor
}

// The inspector's view of the Object ID buffer (an integer texture): one colour per node, black for the sky; its
// texel readout gives the ids.
TEST_F(GLTest, ObjectIdBufferIsShownByTheBufferView) {
    auto scene = floorAndBox();
    const int box = nodeNamed(*scene, "box"), floorNode = scene->parts[0].node;
    // The camera sees sky above the horizon: look along the floor.
    scene->cameras[0].cameraToWorld = glm::inverse(glm::lookAt(glm::vec3(0, 0.5f, 2.5f), glm::vec3(0, 0.3f, 0), glm::vec3(0, 1, 0)));
    auto renderer = rendererFor(scene, 64, 48, "top", sceneEditing());
    Settings s;
    s.indirect = false;
    renderer->render(s);
    const BufferSource src = bufferSource(renderer->textures(), "Object ID 1");
    ASSERT_TRUE(src.valid());
    EXPECT_EQ(src.vis, Visualize::ObjectId);
    BufferViewPass view;
    view.draw(renderer->shaders(), src, nullptr, BufferViewParams{}, 64, 48);
    std::vector<unsigned char> px(64 * 48 * 4);
    glGetTextureImage(view.texture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    auto colour = [&](int x, int yTop) { const unsigned char* p = &px[(size_t(47 - yTop) * 64 + x) * 4]; return glm::ivec3(p[0], p[1], p[2]); };
    const int boxY = 24, floorY = 46, skyY = 1;
    ASSERT_EQ(renderer->objectAt(32, boxY), box);
    ASSERT_EQ(renderer->objectAt(32, floorY), floorNode);
    ASSERT_EQ(renderer->objectAt(32, skyY), -1);
    EXPECT_EQ(colour(32, skyY), glm::ivec3(0));
    EXPECT_NE(colour(32, boxY), colour(32, floorY));
    EXPECT_NE(colour(32, boxY), glm::ivec3(0));
    const TexelBlock t = BufferViewPass::readTexels(src, 32, 47 - boxY, 1, 1);
    ASSERT_EQ(t.channels, 1);
    EXPECT_EQ(int(t.values[0]), box + 1);
}

// A still scene pays for neither editing target: without RendererOptions::sceneEditing no Object ID is written, and
// in no renderer Motion while nothing moves; the image is bit for bit the editing renderer's (the targets change what
// is written, never what is seen). A frame in which an object moved adds Motion, the next still frame drops it, and
// both keep the temporal history.
TEST_F(GLTest, StillSceneWritesNoEditingTargets) {
    auto scene = floorAndBox();
    auto plain = rendererFor(scene, 48, 48, "top"), editing = rendererFor(scene, 48, 48, "top", sceneEditing());
    Settings s;
    for (int f = 0; f < 3; ++f) {
        plain->render(s);
        editing->render(s);
    }
    EXPECT_FALSE(plain->textures().has("Object ID"));
    EXPECT_FALSE(plain->textures().has("Motion"));
    EXPECT_EQ(plain->objectAt(24, 24), -1) << "no picking without the Object ID target";
    EXPECT_TRUE(editing->textures().has("Object ID"));
    EXPECT_FALSE(editing->textures().has("Motion")) << "nothing moved: every surface moves with the camera";
    for (const char* layer : {"Final Radiance", "Output Radiance", "Depth 2"}) {
        const int level = std::string(layer) == "Depth 2" ? plain->lastLayer2Level() : 0;  // where layer 2 is drawn
        const FloatImage a = plain->readLayer(layer, level), b = editing->readLayer(layer, level);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
        EXPECT_EQ(differ, 0u) << layer;
    }
    const int box = nodeNamed(*scene, "box");
    scene->nodes[size_t(box)].local.translation += glm::vec3(0.05f, 0.0f, 0.0f);
    scene->updateWorldTransforms();
    for (auto* r : {plain.get(), editing.get()}) {
        r->sceneChanged(SceneChange::Transforms);
        r->render(s);
        EXPECT_TRUE(r->textures().has("Motion")) << "an object moved: its motion is written";
        EXPECT_TRUE(r->historyValid()) << "the first move keeps the temporal history";
        r->render(s);
        EXPECT_FALSE(r->textures().has("Motion")) << "still again";
        EXPECT_TRUE(r->historyValid()) << "the stop keeps the temporal history";
    }
    EXPECT_FALSE(plain->textures().has("Object ID"));
}

// A light moved live: after sceneChanged(Lights) the next frame equals a fresh renderer's first frame of the new
// lighting (no ghost of the old one: shadows redrawn, history and probes restarted); announced as a transform only,
// the temporal history keeps the old indirect light.
TEST_F(GLTest, MovedLightLeavesNoGhost) {
    double err[2] = {0, 0};
    for (int restart : {1, 0}) {
        auto scene = floorAndBox();
        auto renderer = rendererFor(scene, 48, 48, "top");
        Settings s;
        s.varyTaps = false;  // the same taps and fill directions on the live renderer's frame 7 as on the fresh one's 1st
        for (int f = 0; f < 6; ++f) renderer->render(s);
        const int sun = scene->lights[0].node;
        scene->nodes[size_t(sun)].local.rotation =
            glm::angleAxis(glm::radians(50.0f), glm::vec3(0, 0, 1)) * scene->nodes[size_t(sun)].local.rotation;
        scene->updateWorldTransforms();
        renderer->sceneChanged(restart ? SceneChange::Lights : SceneChange::Transforms);
        renderer->render(s);
        auto fresh = rendererFor(scene, 48, 48, "top");
        fresh->render(s);
        for (const char* layer : {"Final Radiance", "Output Radiance"}) {
            const FloatImage live = renderer->readLayer(layer), ref = fresh->readLayer(layer);
            double diff = 0.0, total = 0.0;
            for (size_t i = 0; i < ref.pixels.size(); ++i) {
                diff += std::abs(double(live.pixels[i]) - ref.pixels[i]);
                total += ref.pixels[i];
            }
            std::printf("moved light, history %s: %s |live - fresh| / fresh = %.4f%%\n", restart ? "restarted" : "kept     ", layer,
                        100.0 * diff / total);
            if (std::string(layer) == "Output Radiance") err[restart] = diff / total;
            // Restarted: only the stochastic rounding's dither differs (it follows the frame index): under one R11G11B10
            // step (1/64) on the indirect light, far less on the final image.
            if (restart) EXPECT_LT(diff / total, std::string(layer) == "Output Radiance" ? 1.0 / 64.0 : 1e-3) << layer;
        }
    }
    EXPECT_GT(err[0], 0.2);  // kept: the indirect light still shows the old sun
}
