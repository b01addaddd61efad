// Materials through the pipeline: emission (seen and lighting its surroundings), alpha masking, double-sided.
#include "gl_fixture.h"

using namespace deepgi;
using namespace deepgi::test;
using namespace deepgi::procedural;

TEST_F(GLTest, EmissiveSurfaceIsSeenAndLightsTheFloor) {
    auto s = std::make_shared<Scene>();
    int floorM = addMaterial(*s, glm::vec3(0.8f));
    const glm::vec3 Le(2.0f, 1.0f, 0.5f);
    int lamp = addMaterial(*s, glm::vec3(0.0f), Le);
    addFloor(*s, 4.0f, 0.0f, floorM);
    addQuad(*s, {-1.0f, 0.0f, -1.0f}, {1.0f, 0.0f, -1.0f}, {1.0f, 1.0f, -1.0f}, {-1.0f, 1.0f, -1.0f}, lamp);  // faces +Z
    addCamera(*s, "cam", {0.0f, 1.5f, 2.5f}, {0.0f, 0.3f, -1.0f}, 60.0f);
    s->computeBounds();
    Renderer r;
    r.setScene(s);
    r.resize(96, 72);
    r.setCamera(selectCamera(*s, "cam"));
    Settings st;
    st.sunIntensity = 0.0f;  // the scene has no lights: the default sun is off
    for (int i = 0; i < 6; ++i) r.render(st);
    EXPECT_TRUE(r.textures().has("Emission"));
    FloatImage img = r.readFinalRadiance();
    dumpIfRequested("emission", img);
    ASSERT_TRUE(allFinite(img));
    // The lamp's pixels show exactly its emitted radiance (albedo 0, no reflected light).
    const float cx = img.at(48, 28, 0), cy = img.at(48, 28, 1), cz = img.at(48, 28, 2);
    EXPECT_NEAR(cx, Le.x, 0.02f * Le.x);
    EXPECT_NEAR(cy, Le.y, 0.02f * Le.y);
    EXPECT_NEAR(cz, Le.z, 0.02f * Le.z);
    // The floor in front of the lamp receives its (orange) light through the gather; the direct term is zero.
    const double red = meanChannel(img, 0, 30, 55, 66, 70), blue = meanChannel(img, 2, 30, 55, 66, 70);
    EXPECT_GT(red, 0.02);
    EXPECT_GT(red, 2.0 * blue);
    Settings noGi = st;
    noGi.indirect = false;
    r.render(noGi);
    FloatImage direct = r.readFinalRadiance();
    EXPECT_LT(meanChannel(direct, 0, 30, 55, 66, 70), 1e-6);
}

TEST_F(GLTest, AlphaMaskedMaterialIsCutOutAndCastsNoShadow) {
    for (float alpha : {0.2f, 0.9f}) {
        auto s = std::make_shared<Scene>();
        int floorM = addMaterial(*s, glm::vec3(0.5f));
        int maskM = addMaterial(*s, glm::vec3(1.0f, 0.0f, 0.0f));
        s->materials[maskM].baseColorFactor.w = alpha;
        s->materials[maskM].alphaMode = AlphaMode::Mask;
        s->materials[maskM].alphaCutoff = 0.5f;
        s->materials[maskM].doubleSided = true;
        addFloor(*s, 4.0f, 0.0f, floorM);
        addQuad(*s, {-1.0f, 1.0f, -1.0f}, {1.0f, 1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}, maskM);  // roof over the centre
        addSun(*s, glm::vec3(0.0f, -1.0f, 0.0f), 3.0f);
        addCamera(*s, "cam", {0.0f, 0.5f, 3.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
        s->computeBounds();
        Renderer r;
        r.setScene(s);
        r.resize(64, 48);
        r.setCamera(selectCamera(*s, "cam"));
        Settings st;
        st.indirect = false;
        r.render(st);
        FloatImage img = r.readFinalRadiance();
        // The floor under the roof (image centre) is lit when the roof is cut out, in shadow when it is opaque.
        const float centre = img.at(32, 24, 1);  // the ray through the centre hits the floor at the origin
        if (alpha < 0.5f) EXPECT_NEAR(centre, 0.5f / float(M_PI) * 3.0f, 0.02f) << "cut out";
        else EXPECT_LT(centre, 1e-4f) << "opaque roof shadows the floor";
    }
}
