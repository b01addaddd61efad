#include "renderer/reference/traced_surface.h"

#include "renderer/core/image_io.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace deepgi {
namespace {

const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

int wrapIndex(int i, int n, WrapMode mode) {
    if (mode == WrapMode::ClampToEdge) return std::min(std::max(i, 0), n - 1);
    if (mode == WrapMode::MirroredRepeat) {
        int m = i % (2 * n);
        if (m < 0) m += 2 * n;
        return m < n ? m : 2 * n - 1 - m;
    }
    const int m = i % n;
    return m < 0 ? m + n : m;
}

// Brings a coordinate into a small range with the same texel under the wrap mode (no int overflow).
float reduceCoord(float u, WrapMode mode) {
    if (!std::isfinite(u)) return 0.0f;
    if (mode == WrapMode::Repeat) return u - std::floor(u);
    if (mode == WrapMode::MirroredRepeat) return u - 2.0f * std::floor(0.5f * u);
    return std::min(std::max(u, -1.0f), 2.0f);
}

glm::vec4 texel(const TextureView& t, int x, int y) {
    x = wrapIndex(x, t.width, t.wrapS);
    y = wrapIndex(y, t.height, t.wrapT);  // row 0 = top = v 0 (glTF)
    const uint8_t* p = t.texels + (size_t(y) * t.width + x) * 4;
    const auto& lut = srgbTable();
    return glm::vec4(lut[p[0]], lut[p[1]], lut[p[2]], float(p[3]) * (1.0f / 255.0f));
}

}  // namespace

glm::vec4 TextureView::sample(glm::vec2 uv) const {
    const float x = reduceCoord(uv.x, wrapS) * float(width), y = reduceCoord(uv.y, wrapT) * float(height);
    if (nearest) return texel(*this, int(std::floor(x)), int(std::floor(y)));
    const float fx = x - 0.5f, fy = y - 0.5f, x0 = std::floor(fx), y0 = std::floor(fy);
    const float tx = fx - x0, ty = fy - y0;
    const int ix = int(x0), iy = int(y0);
    return (texel(*this, ix, iy) * (1.0f - tx) + texel(*this, ix + 1, iy) * tx) * (1.0f - ty) +
           (texel(*this, ix, iy + 1) * (1.0f - tx) + texel(*this, ix + 1, iy + 1) * tx) * ty;
}

TextureView makeTextureView(const Scene& scene, int textureIndex) {
    TextureView v;
    if (textureIndex < 0 || textureIndex >= int(scene.textures.size())) return v;
    const Texture& t = scene.textures[textureIndex];
    if (t.image < 0 || t.image >= int(scene.images.size())) return v;
    const Image& img = scene.images[t.image];
    if (img.width <= 0 || img.height <= 0 || img.rgba8.size() < size_t(img.width) * img.height * 4) return v;
    v.texels = img.rgba8.data();
    v.width = img.width;
    v.height = img.height;
    v.wrapS = t.wrapS;
    v.wrapT = t.wrapT;
    v.nearest = t.magFilter == FilterMode::Nearest;
    return v;
}

}  // namespace deepgi

namespace deepgi {

TracedSurface::TracedSurface(const Scene& scene, const MeshPart& p)
    : part(&p), material(&scene.material(p.material)), baseTexture(makeTextureView(scene, material->baseColorTexture)),
      emissiveTexture(makeTextureView(scene, material->emissiveTexture)) {
    setModel(scene.partModel(int(&p - scene.parts.data())));
}

void TracedSurface::setModel(const glm::mat4& m) {
    model = m;
    moved = m != glm::mat4(1.0f);
    const glm::mat3 m3(m);
    normalMatrix = glm::mat3(glm::cross(m3[1], m3[2]), glm::cross(m3[2], m3[0]), glm::cross(m3[0], m3[1]));
    if (glm::determinant(m3) < 0.0f) normalMatrix = -normalMatrix;
}

void TracedSurface::writePositions(float* xyz) const {
    for (size_t v = 0; v < part->vertices.size(); ++v) {
        const glm::vec3 p = toWorld(part->vertices[v].position);
        for (int c = 0; c < 3; ++c) xyz[3 * v + size_t(c)] = p[c];
    }
}

// Vertex buffers rewritten (instances would refit nothing cheaper for the few-object scenes edited by hand, and
// would change both tracers' hit code); only the geometries whose placement changed are touched.
void refitTracedScene(void* rtcScenePtr, std::vector<TracedSurface>& geoms, const Scene& scene) {
    RTCScene rs = static_cast<RTCScene>(rtcScenePtr);
    for (size_t i = 0; i < geoms.size(); ++i) {
        TracedSurface& g = geoms[i];
        RTCGeometry geom = rtcGetGeometry(rs, unsigned(i));
        if (!geom) continue;
        const int pi = int(g.part - scene.parts.data());
        const glm::mat4 m = scene.partModel(pi);
        if (m != g.model) {
            g.setModel(m);
            if (auto* pos = static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0))) {
                g.writePositions(pos);
                rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
                rtcCommitGeometry(geom);
            }
        }
        if (scene.partVisible(pi)) rtcEnableGeometry(geom);
        else rtcDisableGeometry(geom);
    }
    rtcCommitScene(rs);
}

}  // namespace deepgi
