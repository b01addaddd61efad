// The two-layer AO pass (ao.enabled): an open plane is unoccluded, an inside corner is occluded.
#include "gl_fixture.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

namespace {

constexpr int kW = 96, kH = 64;

FloatImage renderAO(const std::shared_ptr<Scene>& s, Renderer& r) {
    r.setScene(s);
    r.resize(kW, kH);
    r.setCamera(selectCamera(*s, "cam"));
    Settings st;
    st.aoEnabled = true;
    st.lengthUnit = 1.0f;  // the lengths below are in scene units
    st.radius = 1.0f;
    st.numSamples = 30;
    st.varyTaps = false;
    r.render(st);
    return r.readLayer("Ambient Occlusion");
}

// Pixel (row 0 at the top) where world point p lands.
glm::ivec2 project(const Renderer& r, const glm::vec3& p) {
    const Camera& c = r.camera();
    glm::vec4 clip = c.projection(float(kW) / kH) * c.view() * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int((ndc.x * 0.5f + 0.5f) * kW), int((0.5f - ndc.y * 0.5f) * kH)};
}

}  // namespace

TEST_F(GLTest, AmbientOcclusionOfOpenPlaneIsOne) {
    auto s = std::make_shared<Scene>();
    addFloor(*s, 50.0f, 0.0f, addMaterial(*s, glm::vec3(0.5f)));
    addCamera(*s, "cam", {0, 1, 0}, {0, 0, -3}, 60.0f);
    s->computeBounds();
    Renderer r;
    FloatImage ao = renderAO(s, r);
    ASSERT_EQ(ao.width, kW);
    EXPECT_TRUE(allFinite(ao));
    // readLayer gives R8 as RGB with G = B = 0: read channel 0.
    float lo = 1.0f;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) lo = std::min(lo, ao.at(x, y, 0));
    EXPECT_GE(lo, 254.0f / 255.0f);
}

TEST_F(GLTest, AmbientOcclusionOfInsideCornerIsBelowOne) {
    auto s = std::make_shared<Scene>();
    int m = addMaterial(*s, glm::vec3(0.5f));
    addFloor(*s, 50.0f, 0.0f, m);
    addQuad(*s, {-50, 0, -3}, {50, 0, -3}, {50, 20, -3}, {-50, 20, -3}, m);  // wall facing +Z
    addCamera(*s, "cam", {0, 1, 0}, {0, 0.3f, -3}, 60.0f);
    s->computeBounds();
    Renderer r;
    FloatImage ao = renderAO(s, r);
    EXPECT_TRUE(allFinite(ao));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            EXPECT_GE(ao.at(x, y, 0), 0.0f);
            EXPECT_LE(ao.at(x, y, 0), 1.0f);
        }
    // Floor just in front of the corner: the wall covers a large part of its hemisphere within the radius.
    glm::ivec2 corner = project(r, {0.0f, 0.0f, -2.95f});
    ASSERT_TRUE(corner.x >= 0 && corner.x < kW && corner.y >= 0 && corner.y < kH);
    const float aoCorner = ao.at(corner.x, corner.y, 0);
    EXPECT_LT(aoCorner, 0.6f);
    // Floor farther than the radius (1) from the wall is unoccluded.
    glm::ivec2 open = project(r, {0.0f, 0.0f, -1.5f});
    ASSERT_TRUE(open.y >= 0 && open.y < kH);
    EXPECT_GE(ao.at(open.x, open.y, 0), 254.0f / 255.0f);
    std::printf("AO at the inside corner %.3f, on the open floor %.3f\n", aoCorner, ao.at(open.x, open.y, 0));
}
