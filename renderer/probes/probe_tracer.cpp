#include "renderer/probes/probe_tracer.h"

#include "renderer/reference/traced_surface.h"

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

// Every ray of the probes: only cut-out texels of masked materials are skipped (both faces are hit).
void cutOutFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const TracedSurface*>(args->geometryUserPtr);
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
    std::vector<TracedSurface> geoms;  // by Embree geometry ID

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
        TracedSurface g(scene, part);
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
        g.writePositions(pos);  // moved where the part's node is now
        std::copy(part.indices.begin(), part.indices.begin() + nTri * 3, idx);
        m.geoms.push_back(g);
        rtcSetGeometryUserData(geom, &m.geoms.back());
        if (g.material->masked()) {
            rtcSetGeometryIntersectFilterFunction(geom, cutOutFilter);
            rtcSetGeometryOccludedFilterFunction(geom, cutOutFilter);
        }
        if (!scene.partVisible(int(&part - scene.parts.data()))) rtcDisableGeometry(geom);
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

void ProbeTracer::update(const Scene& scene) { refitTracedScene(impl_->scene, impl_->geoms, scene); }

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
    const TracedSurface& g = impl_->geoms[rh.hit.geomID];
    const glm::uvec3 tri = g.triangle(rh.hit.primID);
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    const Vertex &a = g.part->vertices[tri.x], &b = g.part->vertices[tri.y], &c = g.part->vertices[tri.z];
    h.hit = true;
    h.distance = rh.ray.tfar;
    h.position = g.toWorld(w * a.position + u * b.position + v * c.position);
    glm::vec3 ng = g.faceNormal(tri);
    const float ngLen = glm::length(ng);
    ng = ngLen > 0.0f ? ng / ngLen : -d;
    glm::vec3 n = g.toWorldNormal(w * a.normal + u * b.normal + v * c.normal);
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
    if (g.baseTexture.valid()) h.albedo *= glm::vec3(g.baseTexture.sample(uv));
    h.emission = mat.emissiveFactor;
    if (g.emissiveTexture.valid() && mat.emissive()) h.emission *= glm::vec3(g.emissiveTexture.sample(uv));
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
