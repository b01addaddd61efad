// The viewer's and inspector's buffer view (renderer/passes/buffer_view_pass.h) against colours computed here from
// the texel values: each mapping (raw, radiance with exposure and sRGB, linearised depth, decoded normals, object
// ids), channels, the value range, the NaN/Inf/negative highlight, the texel grid, the background outside the
// texture and the A/B split. The view is compiled as a variant per choice (buffer_view.frag): every choice below
// runs its own program.
#include "gl_fixture.h"

#include "renderer/passes/buffer_view_pass.h"

#include <cmath>
#include <limits>

using namespace deepgi;
using namespace deepgi::test;

namespace {

int srgbByte(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return int(std::lround(s * 255.0f));
}
int unitByte(float c) { return int(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); }

// 8-bit colours, within the one step a float's conversion may round either way.
void expectColour(const glm::ivec3& got, const glm::ivec3& want, const std::string& what = "") {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1) << what << " channel " << c;
}

struct Output {
    int w = 0, h = 0;
    std::vector<unsigned char> px;
    glm::ivec3 at(int x, int y) const {  // GL rows: y = 0 at the bottom
        const unsigned char* p = &px[(size_t(y) * w + x) * 4];
        return {p[0], p[1], p[2]};
    }
};

class BufferViewTest : public GLTest {
protected:
    void SetUp() override {
        GLTest::SetUp();
        shaders_ = std::make_unique<gl::ShaderLibrary>(DEEPGI_SHADER_DIR);
        view_ = std::make_unique<BufferViewPass>();
    }
    void TearDown() override {
        textures_.clear();
        view_.reset();
        shaders_.reset();
        GLTest::TearDown();
    }
    Output draw(const BufferSource& a, const BufferViewParams& p, int w, int h, const BufferSource* b = nullptr) {
        view_->draw(*shaders_, a, b, p, w, h);
        Output o{w, h, std::vector<unsigned char>(size_t(w) * h * 4)};
        glGetTextureImage(view_->texture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(o.px.size()), o.px.data());
        return o;
    }
    // A w x 1 2D texture of the given float texels (RGBA each).
    BufferSource floats(const std::vector<glm::vec4>& texels, GLenum format = GL_RGBA32F, Visualize vis = Visualize::Radiance) {
        textures_.push_back(gl::createTexture(GL_TEXTURE_2D, "buffer view test"));
        const GLuint t = textures_.back().id();
        glTextureStorage2D(t, 1, format, GLsizei(texels.size()), 1);
        glTextureSubImage2D(t, 0, 0, 0, GLsizei(texels.size()), 1, GL_RGBA, GL_FLOAT, texels.data());
        BufferSource s;
        s.texture = t;
        s.format = format;
        s.width = int(texels.size());
        s.height = 1;
        s.vis = vis;
        return s;
    }
    // A w x 1 array texture of `layers` layers, filled from `data` (pixel format and type as glTextureSubImage3D's).
    BufferSource array(GLenum format, int w, int layers, GLenum pixelFormat, GLenum type, const void* data, Visualize vis) {
        textures_.push_back(gl::createTexture(GL_TEXTURE_2D_ARRAY, "buffer view test array"));
        const GLuint t = textures_.back().id();
        glTextureStorage3D(t, 1, format, w, 1, layers);
        glTextureSubImage3D(t, 0, 0, 0, 0, w, 1, layers, pixelFormat, type, data);
        BufferSource s;
        s.texture = t;
        s.target = GL_TEXTURE_2D_ARRAY;
        s.format = format;
        s.width = w;
        s.height = 1;
        s.vis = vis;
        return s;
    }
    std::unique_ptr<gl::ShaderLibrary> shaders_;
    std::unique_ptr<BufferViewPass> view_;
    std::vector<gl::TextureHandle> textures_;
};

BufferViewParams oneToOne() {
    BufferViewParams p;
    p.grid = false;
    return p;
}

}  // namespace

TEST_F(BufferViewTest, RadianceIsExposedThenSrgbEncodedAndNonFiniteValuesAreMarked) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const BufferSource s = floats({{0.1f, 0.02f, 0.3f, 1.0f}, {nan, 0.5f, 0.5f, 1.0f}, {inf, 0.1f, 0.1f, 1.0f}, {-0.2f, 0.2f, 0.2f, 1.0f}});
    BufferViewParams p = oneToOne();
    p.exposureEV = 1.0f;  // x 2
    const Output o = draw(s, p, 4, 1);
    expectColour(o.at(0, 0), glm::ivec3(srgbByte(0.2f), srgbByte(0.04f), srgbByte(0.6f)));
    expectColour(o.at(1, 0), glm::ivec3(255, 0, 255), "NaN: magenta");
    expectColour(o.at(2, 0), glm::ivec3(255, 255, 0), "+Inf: yellow");
    // Negative: the colour (red clamped to 0) three quarters towards blue (0.1, 0.3, 1).
    const glm::vec3 neg = glm::mix(glm::vec3(0.0f, float(srgbByte(0.4f)) / 255.0f, float(srgbByte(0.4f)) / 255.0f) * 255.0f,
                                   glm::vec3(0.1f, 0.3f, 1.0f) * 255.0f, 0.75f) / 255.0f;
    const glm::ivec3 got = o.at(3, 0), want(unitByte(neg.x), unitByte(neg.y), unitByte(neg.z));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1) << c;
    p.highlight = false;
    expectColour(draw(s, p, 4, 1).at(3, 0), glm::ivec3(0, srgbByte(0.4f), srgbByte(0.4f)), "no highlight: the colour alone");
}

TEST_F(BufferViewTest, RawChannelsAndRange) {
    const BufferSource s = floats({{0.25f, 0.5f, 0.75f, 0.125f}, {1.5f, -1.0f, 0.0f, 1.0f}}, GL_RGBA16F, Visualize::Display);
    BufferViewParams p = oneToOne();
    p.highlight = false;
    expectColour(draw(s, p, 2, 1).at(0, 0), glm::ivec3(64, 128, 191), "raw: no exposure, no sRGB");
    expectColour(draw(s, p, 2, 1).at(1, 0), glm::ivec3(255, 0, 0), "clamped");
    p.channel = ViewChannel::B;
    expectColour(draw(s, p, 2, 1).at(0, 0), glm::ivec3(191));
    p.channel = ViewChannel::A;
    expectColour(draw(s, p, 2, 1).at(0, 0), glm::ivec3(32));
    p.channel = ViewChannel::Luminance;
    const int lum = unitByte(0.2126f * 0.25f + 0.7152f * 0.5f + 0.0722f * 0.75f);
    expectColour(draw(s, p, 2, 1).at(0, 0), glm::ivec3(lum));
    p.channel = ViewChannel::RGB;
    p.useRange = true;
    p.rangeMin = 0.25f;
    p.rangeMax = 0.75f;
    expectColour(draw(s, p, 2, 1).at(0, 0), glm::ivec3(0, 128, 255), "[0.25, 0.75] -> [0, 1]");
}

TEST_F(BufferViewTest, DepthIsLinearisedNormalsDecodedIdsColoured) {
    // Depth: a 2-layer DEPTH32F array, layer 1 shown; perspective depth of view distance z: near = white, far = black.
    const float n = 0.5f, f = 10.0f, z = 3.0f;
    const float ndc = (f + n - 2.0f * n * f / z) / (f - n), d = ndc * 0.5f + 0.5f;
    const float depths[2] = {1.0f, d};
    BufferSource depth = array(GL_DEPTH_COMPONENT32F, 1, 2, GL_DEPTH_COMPONENT, GL_FLOAT, depths, Visualize::Depth);
    depth.layer = 1;
    BufferViewParams p = oneToOne();
    p.znear = n;
    p.zfar = f;
    EXPECT_NEAR(draw(depth, p, 1, 1).at(0, 0).x, unitByte(1.0f - (z - n) / (f - n)), 1);
    // Normals: octahedral RG of (0.6, 0, 0.8).
    const BufferSource normal = floats({{0.6f / 1.4f, 0.0f, 0.0f, 0.0f}}, GL_RG16F, Visualize::Normal);
    const glm::ivec3 nc = draw(normal, p, 1, 1).at(0, 0);
    EXPECT_NEAR(nc.x, unitByte(0.8f), 1);
    EXPECT_NEAR(nc.y, unitByte(0.5f), 1);
    EXPECT_NEAR(nc.z, unitByte(0.9f), 1);
    // Object ids: black for 0, a colour from the id's hash otherwise.
    const uint32_t ids[2] = {0u, 7u};
    const Output o = draw(array(GL_R32UI, 2, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, ids, Visualize::ObjectId), p, 2, 1);
    expectColour(o.at(0, 0), glm::ivec3(0));
    const uint32_t hash = 7u * 2654435761u;
    auto comp = [](uint32_t v) { return unitByte(float(v & 255u) / 255.0f * 0.8f + 0.2f); };
    expectColour(o.at(1, 0), glm::ivec3(comp(hash >> 8), comp(hash >> 16), comp(hash >> 24)));
}

TEST_F(BufferViewTest, ZoomGridBackgroundAndSplit) {
    const BufferSource a = floats({{0.5f, 0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.5f, 1.0f}}, GL_RGBA16F, Visualize::Display);
    const BufferSource b = floats({{0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}}, GL_RGBA16F, Visualize::Display);
    BufferViewParams p;
    p.texelsPerPixel = 1.0f / 16.0f;  // a texel is 16 x 16 pixels
    p.origin = glm::vec2(-0.5f, 0.0f);  // 8 pixels of background on the left
    p.background = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
    p.splitX = 2.0f;  // no split without B
    Output o = draw(a, p, 40, 16);
    expectColour(o.at(3, 8), glm::ivec3(unitByte(0.2f), unitByte(0.4f), unitByte(0.6f)), "outside the texture");
    expectColour(o.at(12, 8), glm::ivec3(128), "inside a texel");
    const int grid = unitByte(0.5f * 0.4f + 0.35f * 0.6f);
    expectColour(o.at(8, 8), glm::ivec3(grid), "a texel's first pixel column: the grid");
    p.grid = false;
    expectColour(draw(a, p, 40, 16).at(8, 8), glm::ivec3(128));
    p.splitX = 0.5f;  // B right of pixel 20
    o = draw(a, p, 40, 16, &b);
    expectColour(o.at(12, 8), glm::ivec3(128), "A left of the split");
    expectColour(o.at(20, 8), glm::ivec3(255), "the split line");
    expectColour(o.at(30, 8), glm::ivec3(0, 255, 0), "B right of it");
}
