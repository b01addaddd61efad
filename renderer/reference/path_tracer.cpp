#include "renderer/reference/path_tracer.h"
#include "renderer/reference/traced_surface.h"

#include "renderer/scene/scene_validation.h"

#include "renderer/scene/lighting.h"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace deepgi {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kTile = 8;                // tile edge in pixels (the unit of work and of progress)
constexpr int kRouletteAfter = 3;       // bounces that are never terminated by Russian roulette

// ---- random numbers: PCG32 seeded by a hash of (seed, pixel, sample) ------------------------------------------

uint64_t splitmix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

class Pcg32 {
public:
    Pcg32(uint64_t seed, uint64_t pixel, uint64_t sample) {
        const uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ pixel) ^ sample);
        inc_ = (splitmix64(h ^ 0xDA3E39CB94B95BDBull) << 1) | 1u;
        state_ = 0;
        next();
        state_ += h;
        next();
    }
    uint32_t next() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }  // [0, 1)

private:
    uint64_t state_, inc_;
};

// Camera and bounce rays: back faces of single-sided materials and cut-out texels are not hit.
void intersectFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const TracedSurface*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::uvec3 tri = g->triangle(RTCHitN_primID(args->hit, args->N, i));
        if (!g->material->doubleSided) {
            const glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                                RTCRayN_dir_z(args->ray, args->N, i));
            if (!(glm::dot(g->faceNormal(tri), dir) < 0.0f)) {
                args->valid[i] = 0;
                continue;
            }
        }
        if (g->material->masked() &&
            g->alphaAt(tri, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)) <
                g->material->alphaCutoff)
            args->valid[i] = 0;
    }
}

// Shadow rays: both faces block; only cut-out texels let light through.
void occludedFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const TracedSurface*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::uvec3 tri = g->triangle(RTCHitN_primID(args->hit, args->N, i));
        if (g->alphaAt(tri, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)) <
            g->material->alphaCutoff)
            args->valid[i] = 0;
    }
}

struct DeviceDeleter {
    void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
    void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
};

void embreeError(void* userPtr, RTCError code, const char* message) {
    auto* sink = static_cast<std::string*>(userPtr);
    if (sink->empty()) *sink = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

// The shading frame at a hit, oriented towards the side the ray came from.
struct Surface {
    glm::vec3 position, geomNormal, normal;  // unit normals
    glm::vec3 albedo, emission;
};

glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& n) {
    const float scale = 1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return p + n * (1e-4f * scale);
}

// Cosine-weighted direction about unit n (Malley), via the branchless orthonormal basis of Duff et al. 2017.
glm::vec3 cosineHemisphere(const glm::vec3& n, float u1, float u2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const glm::vec3 bt(b, sign + n.y * n.y * a, -n.y);
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    return glm::normalize(t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - u1)));
}

float maxComponent(const glm::vec3& v) { return std::max({v.x, v.y, v.z}); }

std::string formatDuration(double s) {
    if (!std::isfinite(s) || s < 0.0) return "--";
    char buf[32];
    const long t = long(s + 0.5);
    if (t >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm%02lds", t / 3600, (t / 60) % 60, t % 60);
    else if (t >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    else std::snprintf(buf, sizeof buf, "%.1fs", s);
    return buf;
}

}  // namespace

// ---- the tracer ---------------------------------------------------------------------------------------------

struct ReferenceTracer::Impl {
    const Scene& scene;
    std::string error;  // first Embree error (written by the device callback)
    std::unique_ptr<RTCDeviceTy, DeviceDeleter> device;
    std::unique_ptr<RTCSceneTy, SceneDeleter> rtcScene;
    std::vector<TracedSurface> geoms;  // indexed by Embree geometry ID

    explicit Impl(const Scene& s) : scene(s) {
        device.reset(rtcNewDevice(nullptr));
        if (!device) throw std::runtime_error("reference: cannot create the Embree device (error " +
                                              std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        rtcSetDeviceErrorFunction(device.get(), embreeError, &error);
        rtcScene.reset(rtcNewScene(device.get()));
        rtcSetSceneFlags(rtcScene.get(), RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(rtcScene.get(), RTC_BUILD_QUALITY_HIGH);

        geoms.reserve(scene.parts.size());
        for (const MeshPart& part : scene.parts) {
            const size_t nTri = part.indices.size() / 3;
            if (nTri == 0 || part.vertices.empty()) continue;
            for (uint32_t idx : part.indices)
                if (idx >= part.vertices.size())
                    throw std::runtime_error("reference: mesh part '" + part.name + "' has index " +
                                             std::to_string(idx) + " past its " +
                                             std::to_string(part.vertices.size()) + " vertices");
            TracedSurface g(scene, part);

            RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
            if (!geom) throw std::runtime_error("reference: cannot create an Embree geometry: " + error);
            auto* pos = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                    RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                    part.vertices.size()));
            auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                                       RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nTri));
            if (!pos || !idx) {
                rtcReleaseGeometry(geom);
                throw std::runtime_error("reference: cannot allocate Embree buffers for '" + part.name + "': " + error);
            }
            g.writePositions(pos);  // moved where the part's node is now
            std::copy(part.indices.begin(), part.indices.begin() + nTri * 3, idx);
            geoms.push_back(g);  // reserved above: the user pointer stays valid
            const Material& m = *g.material;
            rtcSetGeometryUserData(geom, &geoms.back());
            if (!m.doubleSided || m.masked()) rtcSetGeometryIntersectFilterFunction(geom, intersectFilter);
            if (m.masked()) rtcSetGeometryOccludedFilterFunction(geom, occludedFilter);
            if (!scene.partVisible(int(&part - scene.parts.data()))) rtcDisableGeometry(geom);
            rtcCommitGeometry(geom);
            rtcAttachGeometryByID(rtcScene.get(), geom, unsigned(geoms.size() - 1));
            rtcReleaseGeometry(geom);
        }
        rtcCommitScene(rtcScene.get());
        if (!error.empty()) throw std::runtime_error("reference: building the Embree scene failed: " + error);
    }

    Surface shade(const RTCRayHit& rh, const glm::vec3& dir) const {
        const TracedSurface& g = geoms[rh.hit.geomID];
        const glm::uvec3 tri = g.triangle(rh.hit.primID);
        const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
        const Vertex &a = g.part->vertices[tri.x], &b = g.part->vertices[tri.y], &c = g.part->vertices[tri.z];
        Surface s;
        s.position = g.toWorld(w * a.position + u * b.position + v * c.position);
        glm::vec3 ng = g.faceNormal(tri);
        const float ngLen = glm::length(ng);
        ng = ngLen > 0.0f ? ng / ngLen : -dir;
        glm::vec3 n = g.toWorldNormal(w * a.normal + u * b.normal + v * c.normal);
        const float nLen = glm::length(n);
        n = (nLen > 1e-12f && std::isfinite(nLen)) ? n / nLen : ng;
        if (g.material->doubleSided && glm::dot(ng, dir) > 0.0f) {
            ng = -ng;
            n = -n;
        }
        s.geomNormal = ng;
        s.normal = n;
        const Material& m = *g.material;
        const glm::vec2 uv = w * a.uv + u * b.uv + v * c.uv;
        // Clamped like the renderer's RGBA8 albedo buffer (and validateMaterial at load), so the two agree.
        s.albedo = glm::clamp(glm::vec3(m.baseColorFactor), 0.0f, 1.0f);
        if (g.baseTexture.valid()) s.albedo *= glm::vec3(g.baseTexture.sample(uv));
        s.emission = m.emissiveFactor;
        if (g.emissiveTexture.valid() && m.emissive()) s.emission *= glm::vec3(g.emissiveTexture.sample(uv));
        return s;
    }

    bool intersect(const glm::vec3& o, const glm::vec3& d, RTCRayHit& rh, float tnear = 0.0f, float tfar = kInf) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
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
        rtcIntersect1(rtcScene.get(), &ctx, &rh);
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }

    bool occluded(const glm::vec3& o, const glm::vec3& d, float tfar) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay r;
        r.org_x = o.x; r.org_y = o.y; r.org_z = o.z;
        r.dir_x = d.x; r.dir_y = d.y; r.dir_z = d.z;
        r.tnear = 0.0f;
        r.tfar = tfar;
        r.time = 0.0f;
        r.mask = ~0u;
        r.id = 0;
        r.flags = 0;
        rtcOccluded1(rtcScene.get(), &ctx, &r);
        return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
    }

    // Irradiance at s from every light, with shadow rays (no albedo, no 1/pi).
    glm::vec3 directIrradiance(const Surface& s, const std::vector<Light>& lights, uint64_t& rays) const {
        glm::vec3 e(0.0f);
        const glm::vec3 origin = offsetOrigin(s.position, s.geomNormal);
        for (const Light& light : lights) {
            const LightSample ls = sampleLight(light, s.position);
            const float cosTheta = glm::dot(s.normal, ls.toLight);
            if (!(cosTheta > 0.0f) || maxComponent(ls.irradiance) <= 0.0f) continue;
            float tfar = kInf;
            if (std::isfinite(ls.distance)) {
                tfar = glm::length(light.position - origin) * (1.0f - 1e-4f);
                if (!(tfar > 0.0f)) continue;
            }
            ++rays;
            const glm::vec3 dir = std::isfinite(ls.distance) ? glm::normalize(light.position - origin) : ls.toLight;
            if (!occluded(origin, dir, tfar)) e += ls.irradiance * cosTheta;
        }
        return e;
    }

    // One path through the scene. Adds to direct (what the camera sees directly plus direct light at the first
    // hit) and indirect (everything after the first bounce).
    // The camera ray runs from the near to the far clip plane (clipNear/clipFar along it), as the rasterizer clips.
    void tracePath(glm::vec3 origin, glm::vec3 dir, float clipNear, float clipFar, Pcg32& rng,
                   const std::vector<Light>& lights, float background, int maxBounces, glm::vec3& direct,
                   glm::vec3& indirect, uint64_t& rays) const {
        glm::vec3 throughput(1.0f);
        for (int depth = 0;; ++depth) {
            RTCRayHit rh;
            ++rays;
            const bool hit = depth == 0 ? intersect(origin, dir, rh, clipNear, clipFar) : intersect(origin, dir, rh);
            if (!hit) {
                if (depth == 0) direct += glm::vec3(background);
                return;
            }
            const Surface s = shade(rh, dir);
            glm::vec3& acc = depth == 0 ? direct : indirect;
            const glm::vec3 e = directIrradiance(s, lights, rays);
            acc += throughput * (s.emission + s.albedo * kInvPi * e);
            if (depth >= maxBounces) return;

            const float u1 = rng.uniform(), u2 = rng.uniform();
            const glm::vec3 wi = cosineHemisphere(s.normal, u1, u2);
            // Directions below the geometric surface (possible with interpolated normals) end the path.
            if (!(glm::dot(wi, s.geomNormal) > 0.0f)) return;
            throughput *= s.albedo;  // f * cos / pdf = (albedo/pi) * cos / (cos/pi)
            if (depth + 1 > kRouletteAfter) {
                const float survive = std::min(0.95f, maxComponent(s.albedo));
                if (!(rng.uniform() < survive)) return;
                throughput /= survive;
            }
            if (!(maxComponent(throughput) > 0.0f)) return;
            origin = offsetOrigin(s.position, s.geomNormal);
            dir = wi;
        }
    }
};

ReferenceTracer::ReferenceTracer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
ReferenceTracer::~ReferenceTracer() = default;
void ReferenceTracer::update() { refitTracedScene(impl_->rtcScene.get(), impl_->geoms, impl_->scene); }

namespace {

class Progress {
public:
    Progress(bool enabled, int total) : enabled_(enabled), total_(std::max(total, 1)) {
        tty_ = enabled_ && isatty(fileno(stderr));
    }
    // Called by the monitoring thread only: the bar is redrawn 4 times a second, the plain lines every 10%.
    void update(int done, double elapsed, bool final) {
        if (!enabled_) return;
        const double f = double(done) / total_;
        const double eta = f > 0.0 ? elapsed * (1.0 - f) / f : -1.0;
        if (tty_) {
            if (!final && elapsed - lastDraw_ < 0.25) return;
            lastDraw_ = elapsed;
            constexpr int kWidth = 30;
            const int filled = int(f * kWidth);
            std::string bar(size_t(filled), '#');
            bar.resize(kWidth, '.');
            std::fprintf(stderr, "\rreference [%s] %5.1f%%  elapsed %s  left %s   ", bar.c_str(), 100.0 * f,
                         formatDuration(elapsed).c_str(), final ? "0s" : formatDuration(eta).c_str());
            if (final) std::fputc('\n', stderr);
            std::fflush(stderr);
        } else {
            const int decile = int(f * 10.0 + 1e-9);
            if (decile > lastDecile_ || final) {
                if (decile == lastDecile_ && final) return;
                lastDecile_ = decile;
                std::fprintf(stderr, "reference: %3d%%  elapsed %s  left %s\n", decile * 10,
                             formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
                std::fflush(stderr);
            }
        }
    }

private:
    bool enabled_, tty_ = false;
    int total_;
    int lastDecile_ = 0;
    double lastDraw_ = -1.0;
};

}  // namespace

ReferenceResult ReferenceTracer::render(const Camera& camera, const Settings& settings,
                                        const ReferenceOptions& opt) const {
    if (opt.width <= 0 || opt.height <= 0 || opt.width > 65536 || opt.height > 65536)
        throw std::invalid_argument("reference: image size " + std::to_string(opt.width) + "x" +
                                    std::to_string(opt.height) + " is invalid (each side 1..65536)");
    if (opt.spp <= 0) throw std::invalid_argument("reference: spp must be at least 1, got " + std::to_string(opt.spp));
    if (opt.maxBounces < 0)
        throw std::invalid_argument("reference: bounces must be 0 or more, got " + std::to_string(opt.maxBounces));
    if (opt.threads < 0)
        throw std::invalid_argument("reference: threads must be 0 (all cores) or more, got " +
                                    std::to_string(opt.threads));

    // A degenerate camera would make Embree abort on its ray.valid() assertion; the renderer refuses the same ones.
    const std::string cameraIssue = cameraProblem(camera);
    if (!cameraIssue.empty())
        throw std::invalid_argument("reference: camera '" + camera.name + "' cannot be rendered: " + cameraIssue);
    const glm::vec3 forward = camera.forward();
    const std::vector<Light> lights = effectiveLights(impl_->scene, settings);
    const float background = settings.background;
    const int W = opt.width, H = opt.height;
    const int tilesX = (W + kTile - 1) / kTile, tilesY = (H + kTile - 1) / kTile, nTiles = tilesX * tilesY;
    int nThreads = opt.threads > 0 ? opt.threads : int(std::thread::hardware_concurrency());
    nThreads = std::max(1, std::min(nThreads, nTiles));

    ReferenceResult res;
    for (FloatImage* img : {&res.final, &res.direct, &res.indirect, &res.stdError}) {
        img->width = W;
        img->height = H;
        img->channels = 3;
        img->pixels.assign(size_t(W) * H * 3, 0.0f);
    }
    std::vector<float> relError(size_t(W) * H, -1.0f);  // per pixel, -1 = not counted (mean too dark)

    std::atomic<int> nextTile{0}, tilesDone{0};
    std::atomic<uint64_t> totalRays{0};
    std::mutex errorMutex;
    std::string workerError;

    auto worker = [&] {
        uint64_t rays = 0;
        try {
            for (int tile; (tile = nextTile.fetch_add(1)) < nTiles;) {
                const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
                for (int y = y0; y < std::min(y0 + kTile, H); ++y)
                    for (int x = x0; x < std::min(x0 + kTile, W); ++x) {
                        const uint64_t pixel = uint64_t(y) * W + x;
                        glm::dvec3 sumD(0.0), sumI(0.0), sumF(0.0), sumF2(0.0);
                        double sumG = 0.0, sumG2 = 0.0;
                        for (int s = 0; s < opt.spp; ++s) {
                            Pcg32 rng(opt.seed, pixel, uint64_t(s));
                            const float jx = rng.uniform(), jy = rng.uniform();
                            glm::vec3 o, d;
                            camera.primaryRay(float(x) + jx, float(y) + jy, W, H, o, d);
                            glm::vec3 direct(0.0f), indirect(0.0f);
                            const float along = std::max(glm::dot(d, forward), 1e-6f);  // 1 for orthographic
                            impl_->tracePath(o, d, camera.znear / along, camera.zfar / along, rng, lights, background,
                                             opt.maxBounces, direct, indirect, rays);
                            const glm::dvec3 f = glm::dvec3(direct) + glm::dvec3(indirect);
                            sumD += glm::dvec3(direct);
                            sumI += glm::dvec3(indirect);
                            sumF += f;
                            sumF2 += f * f;
                            const double grey = (f.x + f.y + f.z) / 3.0;
                            sumG += grey;
                            sumG2 += grey * grey;
                        }
                        const double n = double(opt.spp);
                        const glm::dvec3 meanF = sumF / n;
                        // Sample variance (n-1) -> standard error of the mean; 0 with a single sample.
                        const auto stdErr = [n](double sum, double sum2) {
                            if (n < 2.0) return 0.0;
                            const double mean = sum / n;
                            const double var = std::max(0.0, (sum2 - n * mean * mean) / (n - 1.0));
                            return std::sqrt(var / n);
                        };
                        for (int c = 0; c < 3; ++c) {
                            res.final.at(x, y, c) = float(meanF[c]);
                            res.direct.at(x, y, c) = float(sumD[c] / n);
                            res.indirect.at(x, y, c) = float(sumI[c] / n);
                            res.stdError.at(x, y, c) = float(stdErr(sumF[c], sumF2[c]));
                        }
                        const double meanG = sumG / n;
                        if (meanG > 1e-3) relError[pixel] = float(stdErr(sumG, sumG2) / meanG);
                    }
                tilesDone.fetch_add(1);
            }
        } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(errorMutex);
            if (workerError.empty()) workerError = e.what();
            nextTile.store(nTiles);
        }
        totalRays.fetch_add(rays);
    };

    Progress progress(opt.progress, nTiles);
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    std::vector<std::thread> threads;
    threads.reserve(size_t(nThreads));
    for (int i = 0; i < nThreads; ++i) threads.emplace_back(worker);
    if (opt.progress) {
        while (tilesDone.load() < nTiles) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            {
                std::lock_guard<std::mutex> lock(errorMutex);
                if (!workerError.empty()) break;
            }
            progress.update(tilesDone.load(), elapsed(), false);
        }
    }
    for (auto& t : threads) t.join();
    res.seconds = elapsed();
    if (!workerError.empty()) throw std::runtime_error("reference: " + workerError);
    progress.update(tilesDone.load(), res.seconds, true);

    double relSum = 0.0;
    size_t relCount = 0;
    for (float r : relError)
        if (r >= 0.0f) {
            relSum += r;
            ++relCount;
        }
    res.meanRelStdError = relCount ? relSum / double(relCount) : 0.0;
    res.rays = totalRays.load();
    return res;
}

ReferenceResult renderReference(const Scene& scene, const Camera& camera, const Settings& settings,
                                const ReferenceOptions& options) {
    ReferenceTracer tracer(scene);
    return tracer.render(camera, settings, options);
}

}  // namespace deepgi
