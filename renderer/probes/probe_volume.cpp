// The probe volume: placement, the update's rays and their vectorised accumulation, the lookups and the commit, in
// one file because they all work on the atlases' private layout (tiles, borders, SoA texel directions); the GL
// upload is apart (probe_volume_textures.cpp).
#include "renderer/probes/probe_volume.h"

#include "renderer/core/util.h"
#include "renderer/probes/octahedral.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/lighting.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include <sys/resource.h>
#include <unistd.h>

namespace deepgi {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kPlacementRays = 256;        // fixed directions that classify a probe when it is placed
constexpr int kPlacementIterations = 4;    // moves tried before a probe inside geometry is disabled
constexpr float kMinFrontDistance = 0.1f;  // x the smallest spacing: a probe is kept this far from surfaces
constexpr float kDepthSharpness = 50.0f;   // exponent of the depth maps' cosine lobe (DDGI)
constexpr float kDepthLobeCutoff = 0.8f;   // cos below which the lobe is ignored: 0.8^50 = 1.4e-5
constexpr float kRampUpdates = 4.0f;       // the k-th update blends with weight k/(k+4) (capped by hysteresis)

uint64_t splitmix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}
float unitFloat(uint64_t bits) { return float(bits >> 40) * (1.0f / 16777216.0f); }  // [0, 1)

// Direction i of n spread evenly over the sphere (spherical Fibonacci).
glm::vec3 fibonacciDirection(int i, int n) {
    const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = float(i) * kPi * (3.0f - std::sqrt(5.0f));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// A uniformly random rotation (Shoemake's quaternion), the same for every probe of one update.
glm::mat3 randomRotation(uint64_t seed, uint64_t update) {
    const uint64_t h = splitmix64(splitmix64(seed) ^ (update * 0xD1B54A32D192ED03ull));
    const float u1 = unitFloat(h), u2 = unitFloat(splitmix64(h + 1)), u3 = unitFloat(splitmix64(h + 2));
    const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
    const glm::quat q(b * std::cos(2.0f * kPi * u3), a * std::sin(2.0f * kPi * u2), a * std::cos(2.0f * kPi * u2),
                      b * std::sin(2.0f * kPi * u3));  // (w, x, y, z)
    return glm::mat3_cast(glm::normalize(q));
}

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Runs f(item) for item in [0, n) on up to `threads` threads; the first exception is rethrown after the join.
template <class F>
void parallelFor(int n, int threads, const F& f) {
    std::atomic<int> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto worker = [&] {
        try {
            for (int i; (i = next.fetch_add(1)) < n;) f(i);
        } catch (...) {
            std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
            next.store(n);
        }
    };
    const int t = std::max(1, std::min(threads, n));
    std::vector<std::thread> pool;
    for (int i = 1; i < t; ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    if (error) std::rethrow_exception(error);
}

// The calling thread gives way to the process's other threads: nice 19 (per thread on Linux). A helper that traces
// beside the frame's draws then takes only the CPU they leave; it cannot hold the frame up for long, as the thread
// that finishes the update traces at normal priority and waits only for each helper's current probe.
void yieldToOtherThreads() {
#ifdef __linux__
    setpriority(PRIO_PROCESS, id_t(gettid()), 19);
#endif
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Eight floats as one GCC/Clang vector (two SSE or one AVX register): the loops below are written with it because
// -O2 left them scalar. The operations are the scalar ones in the same order, so the sums are the same bits.
// Float8At reads and writes eight floats of an array in place (unaligned, aliasing the floats).
typedef float Float8 __attribute__((vector_size(32)));
typedef float Float8At __attribute__((vector_size(32), aligned(4), may_alias));
const Float8At& at8(const float* p) { return *reinterpret_cast<const Float8At*>(p); }
Float8At& at8(float* p) { return *reinterpret_cast<Float8At*>(p); }

// One ray's contribution to every irradiance texel: cosine-weighted radiance and the weight (SoA; n is a multiple
// of 8).
__attribute__((target_clones("avx2", "default")))
void accumulateIrradiance(size_t n, const float* x, const float* y, const float* z, const glm::vec3& d,
                          const glm::vec3& L, float* __restrict r, float* __restrict g, float* __restrict b,
                          float* __restrict w) {
    for (size_t i = 0; i < n; i += 8) {
        Float8 c = at8(x + i) * d.x + at8(y + i) * d.y + at8(z + i) * d.z;
        c = c > 0.0f ? c : Float8{};  // std::max(0, c), NaN to 0 as well
        at8(r + i) += c * L.x;
        at8(g + i) += c * L.y;
        at8(b + i) += c * L.z;
        at8(w + i) += c;
    }
}

// One ray's distance into the depth texels of its lobe with weight cos^50, cut at cos 0.8 (no denormals,
// 0.8^50 = 1.4e-5). `blocks` holds the first texel of every block of 8 that has a texel able to pass the cut; the
// others in a block are below it and add exactly 0, so the sums equal a loop over the whole map.
__attribute__((target_clones("avx2", "default")))
void accumulateDepth(const uint16_t* blocks, const uint16_t* blocksEnd, const float* x, const float* y, const float* z,
                     const glm::vec3& d, float dist, float* __restrict m1, float* __restrict m2, float* __restrict w) {
    static_assert(kDepthSharpness == 50.0f, "the power below is c^32 * c^16 * c^2");
    for (const uint16_t* block = blocks; block != blocksEnd; ++block) {
        const size_t i = *block;
        const Float8 dot = at8(x + i) * d.x + at8(y + i) * d.y + at8(z + i) * d.z;
        const Float8 c = dot > kDepthLobeCutoff ? dot : Float8{};
        const Float8 c2 = c * c, c4 = c2 * c2, c8 = c4 * c4, c16 = c8 * c8, c32 = c16 * c16;
        const Float8 wt = c32 * c16 * c2;
        at8(m1 + i) += wt * dist;
        at8(m2 + i) += wt * dist * dist;
        at8(w + i) += wt;
    }
}

typedef int Int8 __attribute__((vector_size(32)));
#define abs8(v) ((Float8)((Int8)(v) & 0x7fffffff))  // std::abs: the sign bit cleared (a macro: no vector ABI)

// The part of ProbeVolume::probeWeights that costs: for 8 probes at once (positions px, py, pz), the smooth
// back-face term and the Chebyshev visibility against each probe's depth moments (a bilinear fetch of its tile,
// whose first interior texel is (tileX, tileY) in an atlas `width` texels wide with 2 floats per texel), then the
// floor and the crush. The operations are the scalar code's, in its order, lane by lane: the same bits.
__attribute__((target_clones("avx2", "default")))
void probeVisibility8(const float* px, const float* py, const float* pz, const float* tileX, const float* tileY,
                      const glm::vec3& x, const glm::vec3& n, const glm::vec3& biased, const float* atlas, size_t width,
                      int texels, float* __restrict weightOut) {
    const Float8 ppx = at8(px), ppy = at8(py), ppz = at8(pz);
    // Smooth back-face term: probes behind the surface count less.
    const Float8 tx = ppx - x.x, ty = ppy - x.y, tz = ppz - x.z;
    const Float8 tt = (tx * tx + ty * ty) + tz * tz;
    Float8 len, dist2;
    const Float8 qx = biased.x - ppx, qy = biased.y - ppy, qz = biased.z - ppz;  // probe to the biased point
    dist2 = (qx * qx + qy * qy) + qz * qz;
    Float8 dist;
    for (int i = 0; i < 8; ++i) {
        len[i] = std::sqrt(tt[i]);
        dist[i] = std::sqrt(dist2[i]);
    }
    const Float8 cosine = ((tx / len) * n.x + (ty / len) * n.y) + (tz / len) * n.z;
    const Float8 wrap = len > 0.0f ? (cosine + 1.0f) * 0.5f : Float8{} + 1.0f;
    Float8 weight = wrap * wrap + 0.2f;
    // Chebyshev visibility against the probe's depth moments towards the (biased) receiver.
    const auto has = dist > 0.0f;
    const Float8 safe = has ? dist : Float8{} + 1.0f;  // lanes without a direction fetch texel (0, 0) of their tile
    const Float8 dx = has ? qx / safe : Float8{}, dy = has ? qy / safe : Float8{}, dz = has ? qz / safe : Float8{} + 1.0f;
    const Float8 l1 = (abs8(dx) + abs8(dy)) + abs8(dz);
    Float8 ox = dx / l1, oy = dy / l1;
    const Float8 one = Float8{} + 1.0f, minusOne = Float8{} - 1.0f;
    const Float8 fx = (1.0f - abs8(oy)) * (ox >= 0.0f ? one : minusOne), fy = (1.0f - abs8(ox)) * (oy >= 0.0f ? one : minusOne);
    ox = dz < 0.0f ? fx : ox;
    oy = dz < 0.0f ? fy : oy;
    const Float8 u = (at8(tileX) + (ox * 0.5f + 0.5f) * float(texels)) - 0.5f;
    const Float8 v = (at8(tileY) + (oy * 0.5f + 0.5f) * float(texels)) - 0.5f;
    Float8 c00x, c10x, c01x, c11x, c00y, c10y, c01y, c11y, u0, v0;
    for (int i = 0; i < 8; ++i) {
        u0[i] = std::floor(u[i]);
        v0[i] = std::floor(v[i]);
        const float* row0 = &atlas[(size_t(v0[i]) * width + size_t(u0[i])) * 2];
        const float* row1 = row0 + width * 2;
        c00x[i] = row0[0], c00y[i] = row0[1], c10x[i] = row0[2], c10y[i] = row0[3];
        c01x[i] = row1[0], c01y[i] = row1[1], c11x[i] = row1[2], c11y[i] = row1[3];
    }
    const Float8 au = u - u0, av = v - v0;
    const Float8 mx = (c00x * (1.0f - au) + c10x * au) * (1.0f - av) + (c01x * (1.0f - au) + c11x * au) * av;
    const Float8 my = (c00y * (1.0f - au) + c10y * au) * (1.0f - av) + (c01y * (1.0f - au) + c11y * au) * av;
    const Float8 variance = abs8(my - mx * mx);
    const Float8 d = dist - mx;
    const Float8 chebyshev = variance / (variance + d * d);
    const Float8 c3 = chebyshev * chebyshev * chebyshev;
    const Float8 visibility = c3 < 0.05f ? Float8{} + 0.05f : c3;
    weight = (has & (dist > mx)) ? weight * visibility : weight;
    weight = weight < 1e-6f ? Float8{} + 1e-6f : weight;
    constexpr float kCrush = 0.2f;  // weights below this fall off cubically (fewer leaks)
    weight = weight < kCrush ? weight * (weight * weight / (kCrush * kCrush)) : weight;
    at8(weightOut) = weight;
}

// ProbeVolume::sampleAtlas<4>'s bilinear fetch of r, g, b for 8 probes at once (first interior texels tileX, tileY,
// the same direction oct in every tile), in its operations and order: the same bits.
__attribute__((target_clones("avx2", "default")))
void atlasBilinear8(const float* tileX, const float* tileY, const glm::vec2& oct, const float* atlas, size_t width,
                    int texels, float* __restrict r, float* __restrict g, float* __restrict b) {
    const Float8 u = (at8(tileX) + (oct.x * 0.5f + 0.5f) * float(texels)) - 0.5f;
    const Float8 v = (at8(tileY) + (oct.y * 0.5f + 0.5f) * float(texels)) - 0.5f;
    Float8 u0, v0, c00[3], c10[3], c01[3], c11[3];
    for (int i = 0; i < 8; ++i) {
        u0[i] = std::floor(u[i]);
        v0[i] = std::floor(v[i]);
        const float* row0 = &atlas[(size_t(v0[i]) * width + size_t(u0[i])) * 4];
        const float* row1 = row0 + width * 4;
        for (int c = 0; c < 3; ++c) {
            c00[c][i] = row0[c], c10[c][i] = row0[4 + c];
            c01[c][i] = row1[c], c11[c][i] = row1[4 + c];
        }
    }
    const Float8 au = u - u0, av = v - v0;
    float* out[3] = {r, g, b};
    for (int c = 0; c < 3; ++c)
        at8(out[c]) = (c00[c] * (1.0f - au) + c10[c] * au) * (1.0f - av) + (c01[c] * (1.0f - au) + c11[c] * au) * av;
}

// The texel of an n x n octahedral map a direction leaves through.
size_t octTexel(const glm::vec3& d, int n) {
    const glm::vec2 p = octahedral::encode(d) * 0.5f + 0.5f;
    const int i = std::clamp(int(p.x * float(n)), 0, n - 1), j = std::clamp(int(p.y * float(n)), 0, n - 1);
    return size_t(j) * size_t(n) + size_t(i);
}

}  // namespace

ProbeGrid fitProbeGrid(const Aabb& bounds, const Settings& s) {
    if (!bounds.valid() || !finite3(bounds.lo) || !finite3(bounds.hi))
        throw std::runtime_error("probes: the scene has no finite geometry to place probes around");
    const glm::vec3 extent = bounds.extent();
    const float longest = std::max({extent.x, extent.y, extent.z});
    float spacing = s.probeSpacing > 0.0f ? s.probeSpacing : s.probeRelativeSpacing * longest;
    if (!(spacing > 0.0f) || !std::isfinite(spacing))
        throw std::runtime_error("probes: the probe spacing is " + std::to_string(spacing) +
                                 " (the scene's bounds have no size; set probes.spacing)");
    ProbeGrid g;
    g.requestedSpacing = spacing;
    const int maxCount = std::max(8, s.probeMaxCount);
    for (;;) {
        // At least 2 probes per axis; a flat axis gets the requested spacing around the bounds' centre.
        glm::ivec3 counts;
        for (int a = 0; a < 3; ++a) {
            const double n = std::ceil(double(extent[a]) / double(spacing) - 1e-4);
            counts[a] = int(std::max(2.0, std::min(n, 1e6)));
        }
        if (int64_t(counts.x) * counts.y * counts.z <= maxCount) {
            g.counts = counts;
            break;
        }
        spacing *= 1.02f;
        g.coarsened = true;
    }
    for (int a = 0; a < 3; ++a) {
        const float covered = std::max(extent[a], spacing * 0.5f * float(g.counts[a]));
        g.spacing[a] = covered / float(g.counts[a]);
        g.lo[a] = bounds.center()[a] - 0.5f * covered;
    }
    return g;
}

void ProbeVolume::setViewBias(const Settings& s) {
    finishUpdate();  // a pending update's lookups read it
    viewBias_ = s.probeViewBias * grid_.minSpacing();
}

bool ProbeVolume::layoutChanged(const Settings& a, const Settings& b) {
    return a.probeSpacing != b.probeSpacing || a.probeRelativeSpacing != b.probeRelativeSpacing ||
           a.probeMaxCount != b.probeMaxCount || a.probeIrradianceTexels != b.probeIrradianceTexels ||
           a.probeDepthTexels != b.probeDepthTexels || a.probeRadianceTexels != b.probeRadianceTexels ||
           a.probeInsideFraction != b.probeInsideFraction ||
           a.probeMaxRelocation != b.probeMaxRelocation || a.probeNormalBias != b.probeNormalBias;
}

ProbeVolume::ProbeVolume(const Scene& scene, const Settings& s, uint64_t seed, int threads)
    : scene_(scene), tracer_(scene), grid_(fitProbeGrid(scene.bounds, s)), seed_(seed) {
    threads_ = threads > 0 ? threads : std::max(1, int(std::thread::hardware_concurrency()));
    irrN_ = std::min(std::max(s.probeIrradianceTexels, 2), 64);
    depthN_ = std::min(std::max(s.probeDepthTexels, 2), 64);
    radN_ = std::min(std::max(s.probeRadianceTexels, 2), 64);
    normalBias_ = s.probeNormalBias * grid_.minSpacing();
    setViewBias(s);
    maxDistance_ = 1.5f * glm::length(grid_.spacing);
    missDistance_ = 2.0f * glm::length(glm::vec3(grid_.counts) * grid_.spacing);
    const int n = grid_.count();
    tilesPerRow_ = std::max(1, int(std::ceil(std::sqrt(double(n)))));
    tileRows_ = (n + tilesPerRow_ - 1) / tilesPerRow_;
    state_.assign(size_t(n), ProbeState::Active);
    offset_.assign(size_t(n), glm::vec3(0.0f));
    updates_.assign(size_t(n), 0);
    sinceChange_.assign(size_t(n), 0);
    const size_t irrW = size_t(tilesPerRow_) * (irrN_ + 2), irrH = size_t(tileRows_) * (irrN_ + 2);
    const size_t depW = size_t(tilesPerRow_) * (depthN_ + 2), depH = size_t(tileRows_) * (depthN_ + 2);
    irradiance_.assign(irrW * irrH * 4, 0.0f);
    for (size_t i = 3; i < irradiance_.size(); i += 4) irradiance_[i] = 1.0f;
    depth_.resize(depW * depH * 2);
    for (size_t i = 0; i < depth_.size(); i += 2) {  // nothing seen yet: everything visible
        depth_[i] = maxDistance_;
        depth_[i + 1] = maxDistance_ * maxDistance_;
    }
    data_.assign(size_t(tilesPerRow_) * tileRows_ * 4, 0.0f);
    radiance_.assign(size_t(tilesPerRow_) * (radN_ + 2) * size_t(tileRows_) * (radN_ + 2) * 4, 0.0f);
    radianceUpdates_.assign(radiance_.size() / 4, 0.0f);
    for (auto [dirs, n] : {std::pair{&irrDirs_, irrN_}, std::pair{&depthDirs_, depthN_}})
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::vec3 d = octahedral::texelDirection(i, j, n);
                dirs->x.push_back(d.x);
                dirs->y.push_back(d.y);
                dirs->z.push_back(d.z);
            }
    {
        // Each texel's reach: the lobe's half-angle plus the largest angle from a texel's centre to its corners (a
        // direction inside texel t is within that of t's centre: the corners are the farthest points, checked on a
        // 9 x 9 grid per texel at 16 and 32), plus 1e-3 rad against rounding.
        const int n = depthN_;
        float extent = 0.0f;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::vec3 c = octahedral::texelDirection(i, j, n);
                for (int k = 0; k < 4; ++k) {
                    const glm::vec2 p((float(i + (k & 1)) / float(n)) * 2.0f - 1.0f, (float(j + (k >> 1)) / float(n)) * 2.0f - 1.0f);
                    extent = std::max(extent, std::acos(std::clamp(glm::dot(c, octahedral::decode(p)), -1.0f, 1.0f)));
                }
            }
        const float reach = std::cos(std::min(std::acos(kDepthLobeCutoff) + extent + 1e-3f, kPi));
        depthLobeStart_.assign(1, 0u);
        depthLobeBlocks_.clear();
        for (size_t t = 0; t < size_t(n) * n; ++t) {
            const glm::vec3 a(depthDirs_.x[t], depthDirs_.y[t], depthDirs_.z[t]);
            for (size_t u = 0; u < size_t(n) * n; ++u)
                if (glm::dot(a, glm::vec3(depthDirs_.x[u], depthDirs_.y[u], depthDirs_.z[u])) >= reach &&
                    (depthLobeBlocks_.size() == depthLobeStart_.back() || depthLobeBlocks_.back() != u / 8 * 8))
                    depthLobeBlocks_.push_back(uint16_t(u / 8 * 8));  // u ascends: each block once
            depthLobeStart_.push_back(uint32_t(depthLobeBlocks_.size()));
        }
    }
    for (TexelDirections* dirs : {&irrDirs_, &depthDirs_}) {
        dirs->count = dirs->x.size();
        const size_t padded = (dirs->count + 7) / 8 * 8;
        dirs->x.resize(padded, 0.0f);
        dirs->y.resize(padded, 0.0f);
        dirs->z.resize(padded, 0.0f);
    }
    place(s);
    dirtyRowLo_ = 0;
    dirtyRowHi_ = tileRows_;
}

// What one update traces with (read-only while its threads run) and the sums they fill per batch slot, from
// startUpdate() to the commit in finishUpdate().
struct ProbeVolume::Flight {
    std::chrono::steady_clock::time_point start;
    std::atomic<int64_t> cpuMicroseconds{0};  // CPU time of the threads that picked, traced and committed
    struct CpuShare {  // adds a thread's CPU time from `start` to the count when it goes out of scope
        Flight& f;
        double start;
        ~CpuShare() { f.cpuMicroseconds.fetch_add(int64_t((threadCpuMs() - start) * 1e3)); }
    };
    float feedback = 0.0f, hysteresis = 0.0f, insideFraction = 0.0f;
    std::vector<int> batch;  // the probes, one per slot
    std::vector<Light> lights;
    bool sky = false;
    glm::vec3 uniformSky{0.0f};
    int skySamples = 0;
    std::vector<glm::vec3> dirs;
    // Per slot, as arrays per texel: irradiance sums (r, g, b, weight), depth sums (d, d^2, weight), the uniform
    // sky's as newIrr, the map's (sum c L / pdf / n), and per radiance texel the sum of L (rgb), rays, sum of hit
    // distances (missDistance_ for a miss).
    std::vector<float> newIrr, newDepth, newSky, newSkyMap, newRad;
    std::vector<uint8_t> inside;
    std::atomic<uint64_t> shadowRays{0};
    std::atomic<int> next{0};  // the next slot to trace
    std::exception_ptr error;  // the first exception of a tracing thread, rethrown by finishUpdate()
    std::mutex errorMutex;
    std::vector<std::thread> helpers;
};

ProbeVolume::~ProbeVolume() {
    if (!flight_) return;
    flight_->next.store(int(flight_->batch.size()));  // the helpers stop after their current probe
    for (std::thread& t : flight_->helpers) t.join();
}

glm::vec3 ProbeVolume::probePosition(int probe) const {
    return grid_.gridPosition(grid_.coord(probe)) + offset_[size_t(probe)];
}

void ProbeVolume::writeProbeData(int probe) {
    float* d = &data_[size_t(probe) * 4];
    d[0] = offset_[probe].x;
    d[1] = offset_[probe].y;
    d[2] = offset_[probe].z;
    d[3] = float(int(state_[probe]));
}

// Moves probes out of geometry (towards and past the nearest back face, at most probes.max_relocation x spacing
// per axis) and away from surfaces closer than kMinFrontDistance x spacing; disables those still inside, and marks
// unused those with no surface within a cell diagonal (no receiver interpolates them with any weight to speak of).
void ProbeVolume::place(const Settings& s) {
    const auto start = std::chrono::steady_clock::now();
    maxRelocation_ = s.probeMaxRelocation;
    insideFraction_ = s.probeInsideFraction;
    std::vector<int> all(size_t(grid_.count()));
    for (int i = 0; i < grid_.count(); ++i) all[size_t(i)] = i;
    placementRays_ = 0;
    placeProbes(all);
    partRestBounds_.assign(scene_.parts.size(), Aabb{});
    for (size_t p = 0; p < scene_.parts.size(); ++p) extendByVertices(partRestBounds_[p], scene_.parts[p]);
    recordPlacedParts();
    placementMs_ = msSince(start);
}

void ProbeVolume::recordPlacedParts() {
    placedModels_.resize(scene_.parts.size());
    placedVisible_.resize(scene_.parts.size());
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        placedModels_[p] = scene_.partModel(int(p));
        placedVisible_[p] = scene_.partVisible(int(p)) ? 1 : 0;
    }
}

std::vector<int> ProbeVolume::placeProbes(const std::vector<int>& probes) {
    const float minFront = kMinFrontDistance * grid_.minSpacing();
    const glm::vec3 maxOffset = maxRelocation_ * grid_.spacing;
    const float reach = glm::length(grid_.spacing);
    const float insideFraction = insideFraction_;
    std::vector<glm::vec3> dirs(kPlacementRays);
    for (int i = 0; i < kPlacementRays; ++i) dirs[i] = fibonacciDirection(i, kPlacementRays);
    std::atomic<uint64_t> rays{0};
    std::vector<char> changed(probes.size(), 0);
    parallelFor(int(probes.size()), threads_, [&](int slot) {
        const int probe = probes[size_t(slot)];
        const glm::vec3 home = grid_.gridPosition(grid_.coord(probe));
        glm::vec3 offset(0.0f);
        ProbeState st = ProbeState::Active;
        uint64_t traced = 0;
        for (int iter = 0;; ++iter) {
            int back = 0;
            float nearBack = kInf, nearFront = kInf, nearest = kInf;
            glm::vec3 nearBackDir(0.0f), nearFrontDir(0.0f);
            for (const glm::vec3& d : dirs) {
                const ProbeHit h = tracer_.intersect(home + offset, d, 0.0f, kInf);
                ++traced;
                if (!h.hit) continue;
                nearest = std::min(nearest, h.distance);
                if (h.backFace) {
                    ++back;
                    if (h.distance < nearBack) { nearBack = h.distance; nearBackDir = d; }
                } else if (h.distance < nearFront) {
                    nearFront = h.distance;
                    nearFrontDir = d;
                }
            }
            const bool inside = float(back) > insideFraction * float(kPlacementRays);
            glm::vec3 candidate = offset;
            if (inside) candidate = offset + nearBackDir * (nearBack + minFront);
            else if (nearFront < minFront) candidate = offset - nearFrontDir * (minFront - nearFront);
            const bool canMove = candidate != offset && glm::all(glm::lessThanEqual(glm::abs(candidate), maxOffset));
            if (iter + 1 < kPlacementIterations && canMove) {
                offset = candidate;
                continue;
            }
            st = inside ? ProbeState::Inside : (nearest <= reach ? ProbeState::Active : ProbeState::Unused);
            break;
        }
        changed[size_t(slot)] = offset_[probe] != offset || state_[probe] != st;
        offset_[probe] = offset;  // each probe writes only its own entries
        state_[probe] = st;
        rays.fetch_add(traced);
    });
    std::vector<int> moved;
    for (size_t slot = 0; slot < probes.size(); ++slot) {
        writeProbeData(probes[slot]);
        if (changed[slot]) moved.push_back(probes[slot]);
    }
    activeCount_ = 0;
    for (int i = 0; i < grid_.count(); ++i) activeCount_ += state_[i] == ProbeState::Active;
    placementRays_ += rays.load();
    return moved;
}

bool ProbeVolume::converging() const {
    for (size_t i = 0; i < state_.size(); ++i)
        if (state_[i] == ProbeState::Active && updates_[i] == 0) return true;
    return false;
}

// The rotations and the round-robin restart too: the volume then updates as a new one would under these lights,
// whatever came before (a capture re-rendered headless matches the viewer that changed its lights on the way).
void ProbeVolume::resetHistory() {
    finishUpdate();
    std::fill(updates_.begin(), updates_.end(), 0);
    std::fill(sinceChange_.begin(), sinceChange_.end(), 0);
    historyKept_ = false;
    // The bounce of the first updates reads the probes' own irradiance: none, as in a new volume (old light would
    // otherwise come back through it: a ghost of the old lighting, or multi-bounce light in a one-bounce run).
    for (size_t i = 0; i + 3 < irradiance_.size(); i += 4) irradiance_[i] = irradiance_[i + 1] = irradiance_[i + 2] = 0.0f;
    std::fill(radiance_.begin(), radiance_.end(), 0.0f);  // values and distances
    std::fill(radianceUpdates_.begin(), radianceUpdates_.end(), 0.0f);
    updateIndex_ = 0;
    cursor_ = 0;
    for (size_t i = 0; i + 3 < sky_.size(); i += 4) sky_[i] = sky_[i + 1] = sky_[i + 2] = 0.0f;
}

template <int C>
glm::vec<C, float> ProbeVolume::sampleAtlas(const std::vector<float>& atlas, int n, int probe,
                                            const glm::vec2& oct) const {
    const int tile = n + 2;
    const size_t width = size_t(tilesPerRow_) * tile;
    const float fx = float((probe % tilesPerRow_) * tile + 1) + (oct.x * 0.5f + 0.5f) * float(n) - 0.5f;
    const float fy = float((probe / tilesPerRow_) * tile + 1) + (oct.y * 0.5f + 0.5f) * float(n) - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy), tx = fx - x0, ty = fy - y0;
    const float* row0 = &atlas[(size_t(y0) * width + size_t(x0)) * C];
    const float* row1 = row0 + width * C;
    glm::vec<C, float> r;
    for (int c = 0; c < C; ++c)
        r[c] = (row0[c] * (1.0f - tx) + row0[C + c] * tx) * (1.0f - ty) + (row1[c] * (1.0f - tx) + row1[C + c] * tx) * ty;
    return r;
}

float ProbeVolume::probeWeights(const glm::vec3& x, const glm::vec3& n, int probes[8], float weights[8],
                                 const glm::vec3& view) const {
    for (int i = 0; i < 8; ++i) {
        probes[i] = -1;
        weights[i] = 0.0f;
    }
    if (!finite3(x) || !finite3(n) || !(glm::dot(n, n) > 1e-12f)) return 0.0f;
    const glm::vec3 biased = x + n * normalBias_ + (finite3(view) ? view * viewBias_ : glm::vec3(0.0f));
    const glm::ivec3 last = grid_.counts - 1;
    const glm::vec3 g = glm::clamp((biased - grid_.lo) / grid_.spacing - 0.5f, glm::vec3(-1.0f), glm::vec3(last));
    const glm::ivec3 base = glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), last - 1);
    const glm::vec3 alpha = glm::clamp(g - glm::vec3(base), 0.0f, 1.0f);
    // The 8 probes as lanes (an inactive one computed and dropped), then their weights summed in order.
    alignas(32) float px[8], py[8], pz[8], tileX[8], tileY[8], visibility[8];
    const int tile = depthN_ + 2;
    for (int i = 0; i < 8; ++i) {
        const glm::ivec3 o(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        const int probe = grid_.index(base + o);
        const glm::vec3 probePos = grid_.gridPosition(base + o) + offset_[probe];
        px[i] = probePos.x, py[i] = probePos.y, pz[i] = probePos.z;
        tileX[i] = float((probe % tilesPerRow_) * tile + 1);
        tileY[i] = float((probe / tilesPerRow_) * tile + 1);
    }
    probeVisibility8(px, py, pz, tileX, tileY, x, n, biased, depth_.data(), size_t(tilesPerRow_) * tile, depthN_, visibility);
    float total = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::ivec3 o(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        const int probe = grid_.index(base + o);
        if (state_[probe] != ProbeState::Active) continue;
        const glm::vec3 tri3 = glm::mix(1.0f - alpha, alpha, glm::vec3(o));
        const float trilinear = std::max(0.001f, tri3.x * tri3.y * tri3.z);
        const float weight = visibility[i] * trilinear;
        probes[i] = probe;
        weights[i] = weight;
        total += weight;
    }
    if (total > 0.0f)
        for (int i = 0; i < 8; ++i) weights[i] /= total;
    return total;
}

glm::vec3 ProbeVolume::irradiance(const glm::vec3& x, const glm::vec3& n, float* weightSum, const glm::vec3& view) const {
    return weightedAtlasIrradiance(irradiance_, x, n, weightSum, view);
}

glm::vec3 ProbeVolume::radiance(const glm::vec3& x, const glm::vec3& n, const glm::vec3& dir) const {
    int probes[8];
    float weights[8];
    probeWeights(x, n, probes, weights);
    const glm::vec2 p = octahedral::encode(glm::dot(dir, dir) > 1e-12f ? dir : glm::vec3(0, 0, 1)) * 0.5f + 0.5f;
    const int ti = std::clamp(int(p.x * float(radN_)), 0, radN_ - 1), tj = std::clamp(int(p.y * float(radN_)), 0, radN_ - 1);
    const size_t width = size_t(tilesPerRow_) * (radN_ + 2);
    glm::vec3 sum(0.0f);
    for (int i = 0; i < 8; ++i) {
        if (probes[i] < 0) continue;
        const size_t x = size_t(probes[i] % tilesPerRow_) * (radN_ + 2) + 1 + ti;
        const size_t y = size_t(probes[i] / tilesPerRow_) * (radN_ + 2) + 1 + tj;
        const float* t = &radiance_[(y * width + x) * 4];
        sum += weights[i] * glm::vec3(t[0], t[1], t[2]);
    }
    return sum;
}

ProbeUpdateStats ProbeVolume::update(const Settings& s) {
    startUpdate(s, threads_ - 1, false);
    return finishUpdate();
}

void ProbeVolume::startUpdate(const Settings& s, int helpers, bool background) {
    if (flight_) finishUpdate();  // one in flight at a time: the earlier one commits first, as in sequence
    auto flight = std::make_unique<Flight>();
    Flight& f = *flight;
    f.start = std::chrono::steady_clock::now();
    const double cpuStart = threadCpuMs();
    f.hysteresis = std::min(std::max(s.probeHysteresis, 0.0f), 0.999f);
    f.feedback = 1.0f - std::clamp(s.damping, 0.0f, 1.0f);
    const int count = grid_.count();
    const int raysPerProbe = std::max(1, std::min(s.probeRaysPerProbe, std::max(1, s.probeRaysPerFrame)));
    const int budget = std::max(1, s.probeRaysPerFrame / raysPerProbe);
    // The next active probes, round-robin over the grid (probes disabled during updates drop out).
    std::vector<int>& batch = f.batch;
    for (int scanned = 0; scanned < count && int(batch.size()) < budget; ++scanned) {
        const int p = int(cursor_ % size_t(count));
        cursor_ = (cursor_ + 1) % size_t(count);
        if (state_[p] == ProbeState::Active) batch.push_back(p);
    }
    if (batch.empty()) {  // finishUpdate() only counts it
        flight_ = std::move(flight);
        return;
    }
    const Flight::CpuShare share{f, cpuStart};  // this thread's, however startUpdate() ends
    f.lights = effectiveLights(scene_, s);
    // The sky: allocated while the environment lights, freed when it stops.
    if (!environmentOn(scene_, s)) sky_.clear();  // as the pipeline's config.sky (an all-black map: zeros)
    else if (sky_.empty()) {
        sky_.assign(irradiance_.size(), 0.0f);
        for (size_t i = 3; i < sky_.size(); i += 4) sky_[i] = 1.0f;
    }
    f.sky = hasSky();
    // The uniform sky through the rays that miss (a ratio estimate: exact for an open hemisphere); the map by
    // importance-sampled rays of its own (an absolute estimate: c x L / pdf), skySamples of them per probe.
    f.uniformSky = glm::vec3(std::max(0.0f, s.skyRadiance) * std::max(0.0f, s.environmentIntensity));
    const bool skyMap = f.sky && scene_.environment != nullptr;
    if (skyMap && (skyMapKey_ != scene_.environment.get() || skyMapIntensity_ != s.environmentIntensity ||
                   skyMapRotation_ != s.environmentRotation)) {
        Settings mapOnly = s;
        mapOnly.skyRadiance = 0.0f;
        skyMapSampler_ = std::make_shared<EnvironmentLight>(scene_.environment.get(), mapOnly, true);
        skyMapKey_ = scene_.environment.get();
        skyMapIntensity_ = s.environmentIntensity;
        skyMapRotation_ = s.environmentRotation;
    }
    f.skySamples = skyMap && skyMapSampler_->sampled() ? std::max(16, raysPerProbe / 4) : 0;
    const glm::mat3 rotation = randomRotation(seed_, updateIndex_);
    f.dirs.resize(static_cast<size_t>(raysPerProbe));
    for (int i = 0; i < raysPerProbe; ++i) f.dirs[i] = rotation * fibonacciDirection(i, raysPerProbe);
    f.insideFraction = s.probeInsideFraction;

    const size_t irrTexels = irrDirs_.size(), depthTexels = depthDirs_.size(), radTexels = size_t(radN_) * radN_;
    f.newIrr.assign(batch.size() * irrTexels * 4, 0.0f);
    f.newDepth.assign(batch.size() * depthTexels * 3, 0.0f);
    f.newSky.assign(f.sky ? batch.size() * irrTexels * 4 : 0, 0.0f);
    f.newSkyMap.assign(f.skySamples ? batch.size() * irrTexels * 4 : 0, 0.0f);
    f.newRad.assign(batch.size() * radTexels * 5, 0.0f);
    f.inside.assign(batch.size(), 0);
    flight_ = std::move(flight);
    // The helpers trace slots until none is left; finishUpdate()'s thread joins them. The volume's state is only
    // read until the commit, which happens after the join, on that thread.
    const int threads = std::max(0, std::min(helpers, int(batch.size()) - 1));
    for (int i = 0; i < threads; ++i)
        f.helpers.emplace_back([this, &f, background] {
            if (background) yieldToOtherThreads();
            traceSlots(f);
        });
}

void ProbeVolume::traceSlots(Flight& f) const {
    const Flight::CpuShare share{f, threadCpuMs()};
    try {
        for (int slot; (slot = f.next.fetch_add(1)) < int(f.batch.size());) traceSlot(f, slot);
    } catch (...) {
        std::lock_guard<std::mutex> lock(f.errorMutex);
        if (!f.error) f.error = std::current_exception();
        f.next.store(int(f.batch.size()));
    }
}

void ProbeVolume::traceSlot(Flight& f, int slot) const {
    const std::vector<glm::vec3>& dirs = f.dirs;
    const std::vector<Light>& lights = f.lights;
    const bool sky = f.sky;
    const glm::vec3& uniformSky = f.uniformSky;
    const int skySamples = f.skySamples;
    const float feedback = f.feedback, insideFraction = f.insideFraction;
    const size_t irrTexels = irrDirs_.size(), depthTexels = depthDirs_.size(), radTexels = size_t(radN_) * radN_;
    const int probe = f.batch[slot];
    const glm::vec3 origin = probePosition(probe);
    float* irr = &f.newIrr[size_t(slot) * irrTexels * 4];
    float* dep = &f.newDepth[size_t(slot) * depthTexels * 3];
    uint64_t shadow = 0;
    int back = 0;
    for (const glm::vec3& d : dirs) {
        const ProbeHit h = tracer_.intersect(origin, d, 0.0f, kInf);
        const float distance = h.hit ? std::min(h.distance, maxDistance_) : maxDistance_;
        bool hasRadiance = !h.backFace;
        glm::vec3 radiance(0.0f);  // a miss sees nothing (the background lights nothing)
        if (h.hit && !h.backFace) {
            // The probes read last update's state only (commit comes after the join): deterministic.
            // Multi-bounce through the probes themselves, damped as the screen's feedback is (1 = one bounce).
            glm::vec3 e = tracer_.directIrradiance(h, lights, shadow) + feedback * irradiance(h.position, h.normal);
            if (sky) e += skyIrradiance(h.position, h.normal);  // the sky's direct light at the hit
            radiance = h.emission + h.albedo * (1.0f / kPi) * e;
            if (!finite3(radiance)) hasRadiance = false;
        }
        back += h.backFace ? 1 : 0;
        if (sky && hasRadiance) {  // a ray that leaves the scene brings the environment's radiance
            float* sk = &f.newSky[size_t(slot) * irrTexels * 4];
            accumulateIrradiance(irrTexels, irrDirs_.x.data(), irrDirs_.y.data(), irrDirs_.z.data(), d,
                                 h.hit ? glm::vec3(0.0f) : uniformSky, sk, sk + irrTexels,
                                 sk + 2 * irrTexels, sk + 3 * irrTexels);
        }
        if (hasRadiance) {  // binned by direction: the texel of the octahedral map the ray leaves through
            float* rad = &f.newRad[(size_t(slot) * radTexels + octTexel(d, radN_)) * 5];
            for (int c = 0; c < 3; ++c) rad[c] += radiance[c];
            rad[3] += 1.0f;
            rad[4] += h.hit ? std::min(h.distance, missDistance_) : missDistance_;
        }
        if (hasRadiance)
            accumulateIrradiance(irrTexels, irrDirs_.x.data(), irrDirs_.y.data(), irrDirs_.z.data(), d, radiance,
                                 irr, irr + irrTexels, irr + 2 * irrTexels, irr + 3 * irrTexels);
        const size_t lobe = octTexel(d, depthN_);
        accumulateDepth(&depthLobeBlocks_[0] + depthLobeStart_[lobe], &depthLobeBlocks_[0] + depthLobeStart_[lobe + 1],
                        depthDirs_.x.data(), depthDirs_.y.data(), depthDirs_.z.data(), d, distance, dep,
                        dep + depthTexels, dep + 2 * depthTexels);
    }
    if (skySamples) {  // the map's share: its own rays, drawn from its density, blocked by either face
        float* sk = &f.newSkyMap[size_t(slot) * irrTexels * 4];
        const uint64_t base = splitmix64(seed_ ^ (uint64_t(probe) * 0x9E3779B97F4A7C15ull) ^ (updateIndex_ << 20));
        for (int j = 0; j < skySamples; ++j) {
            const uint64_t h1 = splitmix64(base + uint64_t(j));
            const EnvironmentLight::Sample es = skyMapSampler_->sample(unitFloat(h1), unitFloat(splitmix64(h1)));
            if (!(es.pdf > 0.0f)) continue;
            if (tracer_.intersect(origin, es.direction, 0.0f, kInf).hit) continue;
            const glm::vec3 L = es.radiance / (es.pdf * float(skySamples));
            if (!finite3(L)) continue;
            accumulateIrradiance(irrTexels, irrDirs_.x.data(), irrDirs_.y.data(), irrDirs_.z.data(), es.direction, L,
                                 sk, sk + irrTexels, sk + 2 * irrTexels, sk + 3 * irrTexels);
        }
    }
    f.inside[slot] = float(back) > insideFraction * float(dirs.size()) ? 1 : 0;
    f.shadowRays.fetch_add(shadow);
}

ProbeUpdateStats ProbeVolume::finishUpdate() {
    ProbeUpdateStats stats;
    if (!flight_) return stats;
    Flight& f = *flight_;
    traceSlots(f);  // this thread helps with what is left
    for (std::thread& t : f.helpers) t.join();
    f.helpers.clear();
    const std::unique_ptr<Flight> done = std::move(flight_);
    if (f.error) std::rethrow_exception(f.error);
    const std::vector<int>& batch = f.batch;
    if (batch.empty()) {
        ++updateIndex_;
        stats.milliseconds = msSince(f.start);
        lastUpdate_ = stats;
        return stats;
    }
    const double cpuStart = threadCpuMs();
    const bool sky = f.sky;
    const int skySamples = f.skySamples;
    const float hysteresis = f.hysteresis;
    const size_t irrTexels = irrDirs_.size(), depthTexels = depthDirs_.size(), radTexels = size_t(radN_) * radN_;
    const std::vector<float>&newIrr = f.newIrr, &newDepth = f.newDepth, &newSky = f.newSky, &newSkyMap = f.newSkyMap, &newRad = f.newRad;
    const std::vector<uint8_t>& inside = f.inside;
    // Commit: hysteresis blend into the atlases, borders, dirty rows.
    for (size_t slot = 0; slot < batch.size(); ++slot) {
        const int probe = batch[slot];
        if (inside[slot]) {  // the update's rays say it is inside geometry after all
            state_[probe] = ProbeState::Inside;
            --activeCount_;
            writeProbeData(probe);
        }
        const float k = float(updates_[probe]);
        const float alpha = std::min(hysteresis, k / (k + kRampUpdates));
        const int tile = probe % tilesPerRow_, row = probe / tilesPerRow_;
        const float* irr = &newIrr[slot * irrTexels * 4];
        const size_t irrW = size_t(tilesPerRow_) * (irrN_ + 2);
        for (int j = 0; j < irrN_; ++j)
            for (int i = 0; i < irrN_; ++i) {
                const size_t t = size_t(j) * irrN_ + i;
                const float weight = irr[3 * irrTexels + t];
                if (!(weight > 0.0f)) continue;  // no ray in this hemisphere: keep the history
                float* dst = &irradiance_[4 * ((size_t(row) * (irrN_ + 2) + 1 + j) * irrW + size_t(tile) * (irrN_ + 2) + 1 + i)];
                for (int c = 0; c < 3; ++c) {
                    const float v = kPi * irr[c * irrTexels + t] / weight;
                    if (std::isfinite(v)) dst[c] = alpha * dst[c] + (1.0f - alpha) * v;
                }
            }
        const float* dep = &newDepth[slot * depthTexels * 3];
        const size_t depW = size_t(tilesPerRow_) * (depthN_ + 2);
        for (int j = 0; j < depthN_; ++j)
            for (int i = 0; i < depthN_; ++i) {
                const size_t t = size_t(j) * depthN_ + i;
                const float weight = dep[2 * depthTexels + t];
                if (!(weight > 0.0f)) continue;
                float* dst = &depth_[2 * ((size_t(row) * (depthN_ + 2) + 1 + j) * depW + size_t(tile) * (depthN_ + 2) + 1 + i)];
                const float mean = dep[t] / weight, meanSq = dep[depthTexels + t] / weight;
                if (std::isfinite(mean) && std::isfinite(meanSq)) {
                    dst[0] = alpha * dst[0] + (1.0f - alpha) * mean;
                    dst[1] = alpha * dst[1] + (1.0f - alpha) * meanSq;
                }
            }
        if (sky) {  // the same blend as the irradiance above
            const float* sk = &newSky[slot * irrTexels * 4];
            const float* skm = skySamples ? &newSkyMap[slot * irrTexels * 4] : nullptr;
            for (int j = 0; j < irrN_; ++j)
                for (int i = 0; i < irrN_; ++i) {
                    const size_t t = size_t(j) * irrN_ + i;
                    const float weight = sk[3 * irrTexels + t];
                    if (!(weight > 0.0f)) continue;
                    float* dst = &sky_[4 * ((size_t(row) * (irrN_ + 2) + 1 + j) * irrW + size_t(tile) * (irrN_ + 2) + 1 + i)];
                    for (int c = 0; c < 3; ++c) {
                        const float v = kPi * sk[c * irrTexels + t] / weight + (skm ? skm[c * irrTexels + t] : 0.0f);
                        if (std::isfinite(v)) dst[c] = alpha * dst[c] + (1.0f - alpha) * v;
                    }
                }
            writeBorders(sky_, irrN_, 4, probe);
        }
        // The radiance per direction: each texel blends at its own pace (alpha = its count of updates with a ray
        // through it), so a texel no ray crossed in the first updates does not stay at the first update's zero.
        const float* rad = &newRad[slot * radTexels * 5];
        const size_t radW = size_t(tilesPerRow_) * (radN_ + 2);
        for (int j = 0; j < radN_; ++j)
            for (int i = 0; i < radN_; ++i) {
                const float* src = &rad[(size_t(j) * radN_ + i) * 5];
                if (!(src[3] > 0.0f)) continue;
                const size_t texel = (size_t(row) * (radN_ + 2) + 1 + j) * radW + size_t(tile) * (radN_ + 2) + 1 + i;
                float* dst = &radiance_[4 * texel];
                const float kt = radianceUpdates_[texel], at = std::min(hysteresis, kt / (kt + kRampUpdates));
                for (int c = 0; c < 3; ++c) {
                    const float v = src[c] / src[3];
                    if (std::isfinite(v)) dst[c] = at * dst[c] + (1.0f - at) * v;
                }
                dst[3] = at * dst[3] + (1.0f - at) * (src[4] / src[3]);
                radianceUpdates_[texel] = kt + 1.0f;
            }
        writeBorders(radiance_, radN_, 4, probe);
        writeBorders(irradiance_, irrN_, 4, probe);
        writeBorders(depth_, depthN_, 2, probe);
        ++updates_[probe];
        ++sinceChange_[probe];
        if (dirtyRowLo_ >= dirtyRowHi_) {
            dirtyRowLo_ = row;
            dirtyRowHi_ = row + 1;
        } else {
            dirtyRowLo_ = std::min(dirtyRowLo_, row);
            dirtyRowHi_ = std::max(dirtyRowHi_, row + 1);
        }
    }
    ++updateIndex_;
    stats.probesUpdated = int(batch.size());
    stats.probeRays = uint64_t(batch.size()) * f.dirs.size();
    stats.shadowRays = f.shadowRays.load();
    stats.milliseconds = msSince(f.start);
    stats.cpuMilliseconds = double(f.cpuMicroseconds.load()) * 1e-3 + (threadCpuMs() - cpuStart);
    lastUpdate_ = stats;
    return stats;
}

glm::vec3 ProbeVolume::skyIrradiance(const glm::vec3& x, const glm::vec3& n, float* weightSum, const glm::vec3& view) const {
    if (sky_.empty()) {
        if (weightSum) *weightSum = 0.0f;
        return glm::vec3(0.0f);
    }
    return weightedAtlasIrradiance(sky_, x, n, weightSum, view);
}

// An irradiance-layout atlas (the bounce's or the sky's) at x, n, weighted by probeWeights (trilinear, back-face,
// Chebyshev visibility, crush); shaders/probe_volume.glsl and environment.glsl are the GLSL side.
glm::vec3 ProbeVolume::weightedAtlasIrradiance(const std::vector<float>& atlas, const glm::vec3& x, const glm::vec3& n,
                                               float* weightSum, const glm::vec3& view) const {
    int probes[8];
    float weights[8];
    const float total = probeWeights(x, n, probes, weights, view);
    if (weightSum) *weightSum = total;
    const glm::vec2 octN = octahedral::encode(glm::dot(n, n) > 1e-12f ? n : glm::vec3(0, 0, 1));
    // The 8 tiles' bilinear fetches as lanes (an unused probe's lane reads tile 0), summed in order.
    alignas(32) float tileX[8], tileY[8], r[8], g[8], b[8];
    const int tile = irrN_ + 2;
    for (int i = 0; i < 8; ++i) {
        const int probe = std::max(probes[i], 0);
        tileX[i] = float((probe % tilesPerRow_) * tile + 1);
        tileY[i] = float((probe / tilesPerRow_) * tile + 1);
    }
    atlasBilinear8(tileX, tileY, octN, atlas.data(), size_t(tilesPerRow_) * tile, irrN_, r, g, b);
    glm::vec3 sum(0.0f);
    for (int i = 0; i < 8; ++i)
        if (probes[i] >= 0) sum += weights[i] * glm::vec3(r[i], g[i], b[i]);
    return sum;
}

// The octahedral border: each edge folds onto itself mirrored, each corner is the opposite interior corner, so
// bilinear filtering across a tile's edge reads the neighbouring directions.
void ProbeVolume::writeBorders(std::vector<float>& atlas, int n, int ch, int probe) {
    const size_t width = size_t(tilesPerRow_) * (n + 2);
    const size_t ox = size_t(probe % tilesPerRow_) * (n + 2), oy = size_t(probe / tilesPerRow_) * (n + 2);
    auto at = [&](size_t x, size_t y) { return &atlas[(y * width + x) * ch]; };
    auto interior = [&](int i, int j) { return at(ox + 1 + i, oy + 1 + j); };
    auto copy = [&](float* dst, const float* src) { std::copy(src, src + ch, dst); };
    for (int i = 0; i < n; ++i) {
        copy(at(ox + 1 + i, oy), interior(n - 1 - i, 0));
        copy(at(ox + 1 + i, oy + n + 1), interior(n - 1 - i, n - 1));
        copy(at(ox, oy + 1 + i), interior(0, n - 1 - i));
        copy(at(ox + n + 1, oy + 1 + i), interior(n - 1, n - 1 - i));
    }
    copy(at(ox, oy), interior(n - 1, n - 1));
    copy(at(ox + n + 1, oy), interior(0, n - 1));
    copy(at(ox, oy + n + 1), interior(n - 1, 0));
    copy(at(ox + n + 1, oy + n + 1), interior(0, 0));
}

}  // namespace deepgi

namespace deepgi {

void ProbeVolume::sceneChanged(bool restart) {
    finishUpdate();  // its rays saw the scene before the change
    tracer_.update(scene_);
    // The probes around each part that moved, or was hidden or shown: its bounds before and after, grown by what
    // placement looks at (a cell diagonal, and the relocation limit).
    std::vector<Aabb> regions;
    const glm::vec3 margin = glm::vec3(glm::length(grid_.spacing)) + maxRelocation_ * grid_.spacing;
    for (size_t p = 0; p < scene_.parts.size() && p < placedModels_.size(); ++p) {
        const glm::mat4 model = scene_.partModel(int(p));
        const char visible = scene_.partVisible(int(p)) ? 1 : 0;
        if (model == placedModels_[p] && visible == placedVisible_[p]) continue;
        if (!partRestBounds_[p].valid()) continue;
        for (const glm::mat4* m : {static_cast<const glm::mat4*>(&placedModels_[p]), &model}) {
            Aabb b;
            for (int c = 0; c < 8; ++c) {
                const glm::vec3 corner((c & 1) ? partRestBounds_[p].hi.x : partRestBounds_[p].lo.x,
                                       (c & 2) ? partRestBounds_[p].hi.y : partRestBounds_[p].lo.y,
                                       (c & 4) ? partRestBounds_[p].hi.z : partRestBounds_[p].lo.z);
                b.extend(glm::vec3(*m * glm::vec4(corner, 1.0f)));
            }
            if (!b.valid()) continue;
            b.lo -= margin;
            b.hi += margin;
            regions.push_back(b);
        }
    }
    std::vector<int> near;
    for (int i = 0; i < grid_.count() && !regions.empty(); ++i) {
        const glm::vec3 home = grid_.gridPosition(grid_.coord(i));
        for (const Aabb& b : regions)
            if (glm::all(glm::greaterThanEqual(home, b.lo)) && glm::all(glm::lessThanEqual(home, b.hi))) {
                near.push_back(i);
                break;
            }
    }
    lastReplaced_ = 0;
    if (!near.empty()) {
        // A probe placed elsewhere, or active again, sees other surfaces: its history is not its own.
        for (int probe : placeProbes(near)) {
            updates_[size_t(probe)] = 0;
            const int row = probe / tilesPerRow_, tile = probe % tilesPerRow_;
            const size_t radW = size_t(tilesPerRow_) * (radN_ + 2);
            for (int j = 0; j < radN_ + 2; ++j)  // its radiance texels' update counts: the next ray replaces each
                for (int i = 0; i < radN_ + 2; ++i)
                    radianceUpdates_[(size_t(row) * (radN_ + 2) + j) * radW + size_t(tile) * (radN_ + 2) + i] = 0.0f;
            dirtyRowLo_ = dirtyRowLo_ < dirtyRowHi_ ? std::min(dirtyRowLo_, row) : row;
            dirtyRowHi_ = std::max(dirtyRowHi_, row + 1);
            ++lastReplaced_;
        }
    }
    recordPlacedParts();
    // A kept history still holds the scene before the edit: the probes must go on until it has been blended out.
    std::fill(sinceChange_.begin(), sinceChange_.end(), 0);
    historyKept_ = true;
    if (restart) resetHistory();
}

bool ProbeVolume::settled(const Settings& s) const {
    int need = s.probeSettleUpdates;
    if (need <= 0 || activeCount_ <= 0) return false;
    const float h = std::min(std::max(s.probeHysteresis, 0.0f), 0.999f);
    if (historyKept_ && h > 0.0f) need = std::max(need, int(std::ceil(std::log(0.01) / std::log(double(h)))));
    for (size_t i = 0; i < state_.size(); ++i)
        if (state_[i] == ProbeState::Active && sinceChange_[i] < need) return false;
    return true;
}

}  // namespace deepgi
