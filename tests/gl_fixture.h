#pragma once
// Headless GL fixture: one OSMesa context per test process (ctest runs each test in its own process).
#include "renderer/gl/headless_context.h"
#include "renderer/renderer.h"
#include "renderer/scene/procedural.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

namespace deepgi::test {

class GLTest : public ::testing::Test {
protected:
    void SetUp() override { context_ = std::make_unique<gl::HeadlessContext>(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<gl::HeadlessContext> context_;
};

inline bool allFinite(const FloatImage& img) {
    for (float v : img.pixels) if (!std::isfinite(v)) return false;
    return true;
}

inline double meanChannel(const FloatImage& img, int c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
    if (x1 < 0) x1 = img.width;
    if (y1 < 0) y1 = img.height;
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) { sum += img.at(x, y, c); ++n; }
    return n ? sum / n : 0.0;
}

// Layer 2 of the G-buffer as the last frame left it: the level it is drawn at (Renderer::lastLayer2Level) and, for a
// texel of that level's image (row 0 at the top, no guard band), the level-0 image pixel whose ray it sampled.
struct Layer2Image {
    FloatImage image;
    int level = 0;
    int fullHeight = 0;
    // Level-0 image pixel of texel (x, y): GL rows count up from the bottom, as the sample offset does.
    glm::ivec2 pixel(int x, int y) const {
        const glm::ivec2 c = tapSampleOffset(level);
        const int glY = image.height - 1 - y;
        return {(x << level) + c.x, fullHeight - 1 - ((glY << level) + c.y)};
    }
};
inline Layer2Image readLayer2(const Renderer& r, const std::string& name) {
    Layer2Image l;
    l.level = r.lastLayer2Level();
    l.image = r.readLayer(name, l.level);
    l.fullHeight = r.readLayer(name, 0).height;
    return l;
}

// Writes img to $DEEPGI_TEST_OUT/<name>.exr when that variable is set (for looking at test images).
void dumpIfRequested(const std::string& name, const FloatImage& img);

// Options of a renderer whose scene is edited live (the viewer's): Object ID and Motion written every frame.
inline RendererOptions sceneEditing() {
    RendererOptions o;
    o.sceneEditing = true;
    return o;
}

// A renderer over `scene` at w x h looking through the scene's camera `camera`.
inline std::unique_ptr<Renderer> rendererFor(std::shared_ptr<Scene> scene, int w, int h, const std::string& camera,
                                             RendererOptions options = {}) {
    auto r = std::make_unique<Renderer>(std::move(options));
    r->setScene(scene);
    r->resize(w, h);
    r->setCamera(selectCamera(*scene, camera));
    return r;
}

// A 2x2x2 m room (inward walls: red -X, green +X, white otherwise) with a square hole in the ceiling, a sun
// shining through it and a camera looking in from the front wall.
std::shared_ptr<Scene> cornellScene();

}  // namespace deepgi::test
