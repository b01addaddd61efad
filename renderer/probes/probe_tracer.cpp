#include "renderer/probes/probe_tracer.h"

#include "renderer/core/image_io.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepgi {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

const std::array<float, 256>& srgbLut() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

int wrapTexel(int i, int n, WrapMode mode) {
    if (mode == WrapMode::ClampToEdge) return std::min(std::max(i, 0), n - 1);
    if (mode == WrapMode::MirroredRepeat) {
        int m = i % (2 * n);
        if (m < 0) m += 2 * n;
        return m < n ? m : 2 * n - 1 - m;
    }
    const int m = i % n;
    return m < 0 ? m + n : m;
}

// Keeps a coordinate small without changing the texel it selects under the wrap mode.
float foldCoord(float u, WrapMode mode) {
    if (!std::isfinite(u)) return 0.0f;
    if (mode == WrapMode::Repeat) return u - std::floor(u);
    if (mode == WrapMode::MirroredRepeat) return u - 2.0f * std::floor(0.5f * u);
    return std::min(std::max(u, -1.0f), 2.0f);
}

// Mip 0 of a texture, bilinear (nearest where the sampler asks), rgb sRGB-decoded and alpha linear: the path
// tracer's sampling.
struct TexelSource {
    const uint8_t* texels = nullptr;
    int width = 0, height = 0;
    WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
    bool nearest = false;

    bool valid() const { return texels != nullptr; }
    glm::vec4 fetch(int x, int y) const {
        const uint8_t* p = texels + (size_t(wrapTexel(y, height, wrapT)) * width + wrapTexel(x, width, wrapS)) * 4;
        const auto& lut = srgbLut();
        return glm::vec4(lut[p[0]], lut[p[1]], lut[p[2]], float(p[3]) * (1.0f / 255.0f));
    }
    glm::vec4 sample(glm::vec2 uv) const {
        const float x = foldCoord(uv.x, wrapS) * float(width), y = foldCoord(uv.y, wrapT) * float(height);
        if (nearest) return fetch(int(std::floor(x)), int(std::floor(y)));
        const float fx = x - 0.5f, fy = y - 0.5f, x0 = std::floor(fx), y0 = std::floor(fy);
        const float tx = fx - x0, ty = fy - y0;
        const int ix = int(x0), iy = int(y0);
        return (fetch(ix, iy) * (1.0f - tx) + fetch(ix + 1, iy) * tx) * (1.0f - ty) +
               (fetch(ix, iy + 1) * (1.0f - tx) + fetch(ix + 1, iy + 1) * tx) * ty;
    }
};

TexelSource texelSource(const Scene& scene, int textureIndex) {
    TexelSource t;
    if (textureIndex < 0 || textureIndex >= int(scene.textures.size())) return t;
    const Texture& tex = scene.textures[textureIndex];
    if (tex.image < 0 || tex.image >= int(scene.images.size())) return t;
    const Image& img = scene.images[tex.image];
    if (img.width <= 0 || img.height <= 0 || img.rgba8.size() < size_t(img.width) * img.height * 4) return t;
    t.texels = img.rgba8.data();
    t.width = img.width;
    t.height = img.height;
    t.wrapS = tex.wrapS;
    t.wrapT = tex.wrapT;
    t.nearest = tex.magFilter == FilterMode::Nearest;
    return t;
}

struct Geom {
    const MeshPart* part = nullptr;
    const Material* material = nullptr;
    TexelSource base, emissive;

    glm::uvec3 triangle(unsigned prim) const {
        const uint32_t* i = &part->indices[size_t(prim) * 3];
        return {i[0], i[1], i[2]};
    }
    glm::vec3 faceNormal(const glm::uvec3& t) const {  // counter-clockwise front, not normalised
        const glm::vec3& p0 = part->vertices[t.x].position;
        return glm::cross(part->vertices[t.y].position - p0, part->vertices[t.z].position - p0);
    }
    glm::vec2 uv(const glm::uvec3& t, float u, float v) const {
        return (1.0f - u - v) * part->vertices[t.x].uv + u * part->vertices[t.y].uv + v * part->vertices[t.z].uv;
    }
    bool cutOut(const glm::uvec3& t, float u, float v) const {
        float a = material->baseColorFactor.w;
        if (base.valid()) a *= base.sample(uv(t, u, v)).w;
        return a < material->alphaCutoff;
    }
};

// Every ray of the probes: only cut-out texels of masked materials are skipped (both faces are hit).
void cutOutFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const Geom*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (g->cutOut(g->triangle(RTCHitN_primID(args->hit, args->N, i)), RTCHitN_u(args->hit, args->N, i),
                      RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

void onEmbreeError(void* userPtr, RTCError code, const char* message) {
    auto* sink = static_cast<std::string*>(userPtr);
    if (sink->empty()) *sink = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

}  // namespace

struct ProbeTracer::Impl {
    std::string error;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Geom> geoms;  // by Embree geometry ID

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

ProbeTracer::ProbeTracer(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.device = rtcNewDevice(nullptr);
    if (!m.device)
        throw std::runtime_error("probes: cannot create the Embree device (error " +
                                 std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(m.device, onEmbreeError, &m.error);
    m.scene = rtcNewScene(m.device);
    rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
    m.geoms.reserve(scene.parts.size());  // user pointers into it must stay valid
    for (const MeshPart& part : scene.parts) {
        const size_t nTri = part.indices.size() / 3;
        if (nTri == 0 || part.vertices.empty()) continue;
        for (uint32_t idx : part.indices)
            if (idx >= part.vertices.size())
                throw std::runtime_error("probes: mesh part '" + part.name + "' has index " + std::to_string(idx) +
                                         " past its " + std::to_string(part.vertices.size()) + " vertices");
        Geom g;
        g.part = &part;
        g.material = &scene.material(part.material);
        g.base = texelSource(scene, g.material->baseColorTexture);
        g.emissive = texelSource(scene, g.material->emissiveTexture);
        RTCGeometry geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!geom) throw std::runtime_error("probes: cannot create an Embree geometry: " + m.error);
        auto* pos = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                3 * sizeof(float), part.vertices.size()));
        auto* idx = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nTri));
        if (!pos || !idx) {
            rtcReleaseGeometry(geom);
            throw std::runtime_error("probes: cannot allocate Embree buffers for '" + part.name + "': " + m.error);
        }
        for (size_t v = 0; v < part.vertices.size(); ++v)
            for (int c = 0; c < 3; ++c) pos[3 * v + c] = part.vertices[v].position[c];
        std::copy(part.indices.begin(), part.indices.begin() + nTri * 3, idx);
        m.geoms.push_back(g);
        rtcSetGeometryUserData(geom, &m.geoms.back());
        if (g.material->masked()) {
            rtcSetGeometryIntersectFilterFunction(geom, cutOutFilter);
            rtcSetGeometryOccludedFilterFunction(geom, cutOutFilter);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(m.scene, geom, unsigned(m.geoms.size() - 1));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(m.scene);
    if (!m.error.empty()) throw std::runtime_error("probes: building the Embree scene failed: " + m.error);
    // The bounds of finite vertices; the offset grows with the coordinates' size (float spacing) and the scene's.
    if (scene.bounds.valid()) {
        const glm::vec3 a = glm::max(glm::abs(scene.bounds.lo), glm::abs(scene.bounds.hi));
        epsilon_ = 1e-5f * (std::max({a.x, a.y, a.z}) + 2.0f * scene.bounds.radius());
        if (!(epsilon_ > 0.0f) || !std::isfinite(epsilon_)) epsilon_ = 1e-6f;
    }
}

ProbeTracer::~ProbeTracer() = default;

ProbeHit ProbeTracer::intersect(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = o.x; rh.ray.org_y = o.y; rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x; rh.ray.dir_y = d.y; rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &ctx, &rh);
    ProbeHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const Geom& g = impl_->geoms[rh.hit.geomID];
    const glm::uvec3 tri = g.triangle(rh.hit.primID);
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    const Vertex &a = g.part->vertices[tri.x], &b = g.part->vertices[tri.y], &c = g.part->vertices[tri.z];
    h.hit = true;
    h.distance = rh.ray.tfar;
    h.position = w * a.position + u * b.position + v * c.position;
    glm::vec3 ng = g.faceNormal(tri);
    const float ngLen = glm::length(ng);
    ng = ngLen > 0.0f ? ng / ngLen : -d;
    glm::vec3 n = w * a.normal + u * b.normal + v * c.normal;
    const float nLen = glm::length(n);
    n = (nLen > 1e-12f && std::isfinite(nLen)) ? n / nLen : ng;
    if (glm::dot(ng, d) > 0.0f) {
        if (!g.material->doubleSided) {
            h.backFace = true;
            return h;
        }
        ng = -ng;
        n = -n;
    }
    h.geomNormal = ng;
    h.normal = n;
    const Material& mat = *g.material;
    const glm::vec2 uv = w * a.uv + u * b.uv + v * c.uv;
    h.albedo = glm::vec3(mat.baseColorFactor);
    if (g.base.valid()) h.albedo *= glm::vec3(g.base.sample(uv));
    h.emission = mat.emissiveFactor;
    if (g.emissive.valid() && mat.emissive()) h.emission *= glm::vec3(g.emissive.sample(uv));
    return h;
}

glm::vec3 ProbeTracer::directIrradiance(const ProbeHit& s, const std::vector<Light>& lights, uint64_t& rays) const {
    glm::vec3 e(0.0f);
    const glm::vec3 origin = s.position + s.geomNormal * epsilon_;
    for (const Light& light : lights) {
        const LightSample ls = sampleLight(light, s.position);
        const float cosTheta = glm::dot(s.normal, ls.toLight);
        if (!(cosTheta > 0.0f) || std::max({ls.irradiance.x, ls.irradiance.y, ls.irradiance.z}) <= 0.0f) continue;
        float tfar = kInf;
        glm::vec3 dir = ls.toLight;
        if (std::isfinite(ls.distance)) {
            const glm::vec3 toLight = light.position - origin;
            tfar = glm::length(toLight) * (1.0f - 1e-4f);
            if (!(tfar > 0.0f)) continue;
            dir = toLight / glm::length(toLight);
        }
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay r;
        r.org_x = origin.x; r.org_y = origin.y; r.org_z = origin.z;
        r.dir_x = dir.x; r.dir_y = dir.y; r.dir_z = dir.z;
        r.tnear = 0.0f;
        r.tfar = tfar;
        r.time = 0.0f;
        r.mask = ~0u;
        r.id = 0;
        r.flags = 0;
        ++rays;
        rtcOccluded1(impl_->scene, &ctx, &r);
        if (!(r.tfar < 0.0f)) e += ls.irradiance * cosTheta;  // Embree sets tfar to -inf when blocked
    }
    return e;
}

}  // namespace deepgi
