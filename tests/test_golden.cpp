// Golden images of the default scenes: the display image after 16 frames at 160x90 against a committed PNG.
// llvmpipe output is bit-identical for any thread count, so differences come from code changes. Regenerate with
// DEEPGI_UPDATE_GOLDEN=1 after an intended change, and look at the new images before committing them.
#include "gl_fixture.h"

#include "renderer/core/image_io.h"
#include "renderer/scene/gltf_loader.h"

#include <cstdlib>
#include <filesystem>

using namespace deepgi;
using namespace deepgi::test;

namespace {

void checkGolden(const std::string& scenePath, const std::string& camera, const std::string& golden) {
    auto scene = std::make_shared<Scene>(loadGltf(scenePath));
    Renderer r;
    r.setScene(scene);
    r.resize(160, 90);
    r.setCamera(selectCamera(*scene, camera));
    Settings s;
    for (int i = 0; i < 16; ++i) r.render(s);
    std::vector<unsigned char> px = r.readDisplay();
    const std::string path = std::string(DEEPGI_TEST_DATA) + "/../golden/" + golden;
    if (std::getenv("DEEPGI_UPDATE_GOLDEN")) {
        writePng8(path, 160, 90, 4, px);
        GTEST_SKIP() << "golden image rewritten: " << path;
    }
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing; run with DEEPGI_UPDATE_GOLDEN=1";
    FloatImage ref = readImage(path);
    ASSERT_EQ(ref.width, 160);
    ASSERT_EQ(ref.height, 90);
    // Tolerance: mean |difference| below 1/255 and at most 0.5% of pixels off by more than 8/255.
    double sum = 0.0;
    int outliers = 0;
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x) {
            float worst = 0.0f;
            for (int c = 0; c < 3; ++c) {
                float d = std::abs(px[(size_t(y) * 160 + x) * 4 + c] / 255.0f - ref.at(x, y, c));
                sum += d;
                worst = std::max(worst, d);
            }
            if (worst > 8.0f / 255.0f) ++outliers;
        }
    const double mean = sum / (160.0 * 90.0 * 3.0);
    EXPECT_LT(mean, 1.0 / 255.0) << golden;
    EXPECT_LE(outliers, int(0.005 * 160 * 90)) << golden;
}

}  // namespace

TEST_F(GLTest, GoldenAtriumCourtyard) {
    checkGolden(std::string(DEEPGI_ASSET_DIR) + "/atrium/atrium.gltf", "courtyard", "atrium_courtyard.png");
}

TEST_F(GLTest, GoldenCornellBoxFront) {
    checkGolden(std::string(DEEPGI_ASSET_DIR) + "/cornell_box/cornell_box.gltf", "front", "cornell_box_front.png");
}
