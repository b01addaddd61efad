#include "bench/reference_cache.h"

#include "bench/gi_figures.h"
#include "bench/metrics.h"
#include "renderer/core/util.h"
#include "renderer/reference/path_tracer.h"
#include "renderer/scene/environment_map.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <vector>

namespace deepgi::bench {

namespace fs = std::filesystem;

namespace {

uint64_t hashFile(uint64_t h, const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::vector<char> buf(1 << 16);
    while (f) {
        f.read(buf.data(), std::streamsize(buf.size()));
        h = fnv1a(h, buf.data(), size_t(f.gcount()));
    }
    return h;
}

std::string hex(uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", (unsigned long long)v);
    return b;
}

FloatImage average(const std::vector<FloatImage>& imgs) {
    FloatImage out = imgs.at(0);
    for (size_t k = 1; k < imgs.size(); ++k)
        for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] += imgs[k].pixels[i];
    for (float& v : out.pixels) v /= float(imgs.size());
    return out;
}

}  // namespace

std::string referenceKey(const Scene& scene, const Camera& camera, const Settings& s, int width, int height, int spp,
                         int bounces, uint64_t seed) {
    uint64_t h = kFnvOffset;
    if (!scene.sourcePath.empty() && fs::exists(scene.sourcePath)) {
        const fs::path src = fs::absolute(scene.sourcePath);
        h = hashFile(h, src);
        // Buffers and textures beside the scene file (a .gltf's .bin and images).
        std::vector<fs::path> side;
        for (const auto& e : fs::directory_iterator(src.parent_path()))
            if (e.is_regular_file() && e.path() != src && e.file_size() < (64u << 20)) side.push_back(e.path());
        std::sort(side.begin(), side.end());
        for (const auto& p : side) {
            const std::string name = p.filename().string();
            h = fnv1a(h, name.data(), name.size());
            h = hashFile(h, p);
        }
    } else {
        h = fnv1aValue(h, scene.triangleCount());
    }
    h = fnv1a(h, &camera.cameraToWorld[0][0], sizeof(float) * 16);
    h = fnv1aValue(h, camera.perspective);
    for (float v : {camera.yfov, camera.orthoHalfHeight, camera.znear, camera.zfar}) h = fnv1aValue(h, v);
    for (int v : {width, height, spp, bounces}) h = fnv1aValue(h, v);
    h = fnv1aValue(h, seed);
    for (float v : {s.sunAzimuth, s.sunElevation, s.sunIntensity, s.lightScale, s.background}) h = fnv1aValue(h, v);
    if (environmentOn(scene, s)) {  // the environment: its settings and the map's pixels
        for (float v : {s.skyRadiance, s.environmentIntensity}) h = fnv1aValue(h, v);
        if (scene.environment) {
            if (s.environmentRotation != 0.0f) h = fnv1aValue(h, s.environmentRotation);  // unturned keys stay as they were
            h = fnv1aValue(h, scene.environment->width);
            h = fnv1aValue(h, scene.environment->height);
            h = fnv1a(h, scene.environment->rgb.data(), scene.environment->rgb.size() * sizeof(float));
        }
    }
    // The metallic-roughness BRDF (GGX, F0 0.04 on dielectrics) changed the references cached before it; diffuse_only
    // is the old Lambertian transport (albedo = base colour), whose keys stay as they were.
    if (!s.diffuseOnly) h = fnv1aValue(h, uint32_t(0x4d525631));  // "MRV1"
    return hex(h);
}

CachedReference cachedReference(const Scene& scene, const Camera& camera, const Settings& s, int width, int height,
                                int spp, int bounces, const std::string& cacheDir, bool quiet) {
    CachedReference r;
    const uint64_t seed = 1;
    r.path = (fs::path(cacheDir) / (referenceKey(scene, camera, s, width, height, spp, bounces, seed) + ".exr")).string();
    auto split = [&](const FloatImage& all) {
        r.final = channelRange(all, 0);
        r.direct = channelRange(all, 3);
        r.indirect = channelRange(all, 6);
    };
    if (fs::exists(r.path)) {
        FloatImage all = readImage(r.path);
        if (all.width == width && all.height == height && all.channels == 9) {
            split(all);
            r.cacheHit = true;
            return r;
        }
    }
    ReferenceOptions o;
    o.width = width;
    o.height = height;
    o.spp = spp;
    o.maxBounces = bounces;
    o.seed = seed;
    o.progress = !quiet;
    const ReferenceResult res = renderReference(scene, camera, s, o);
    r.seconds = res.seconds;
    const FloatImage all = stackRgb({&res.final, &res.direct, &res.indirect});
    fs::create_directories(cacheDir);
    const std::string tmp = r.path + ".tmp.exr";
    writeExr(tmp, all);
    fs::rename(tmp, r.path);
    split(all);
    return r;
}

FloorReference floorReference(const Scene& scene, const Camera& camera, const Settings& s, int width, int height, int spp,
                              int bounces, const std::string& cacheDir, bool quiet) {
    if (spp < 4) throw std::invalid_argument("bench: a reference with a noise floor needs at least 4 spp, got " + std::to_string(spp));
    FloorReference r;
    const uint64_t seedTag = 0x4c4f4f52;  // "FLOR": 4 chunks, seeds 1..4; never the same key as cachedReference
    const std::string key = referenceKey(scene, camera, s, width, height, spp, bounces, seedTag);
    r.path = (fs::path(cacheDir) / (key + ".exr")).string();
    const std::string side = (fs::path(cacheDir) / (key + ".json")).string();
    auto split = [&](const FloatImage& all) {
        r.final = channelRange(all, 0);
        r.direct = channelRange(all, 3);
        r.indirect = channelRange(all, 6);
    };
    if (fs::exists(r.path) && fs::exists(side)) {
        FloatImage all = readImage(r.path);
        std::ifstream f(side);
        nlohmann::json j;
        try {
            f >> j;
            if (all.width == width && all.height == height && all.channels == 9) {
                split(all);
                // -1 in the file: undefined (a reference without light)
                r.floorFinal = j.at("floor_final").get<double>();
                r.floorIndirect = j.at("floor_indirect").get<double>();
                if (r.floorFinal < 0.0) r.floorFinal = std::numeric_limits<double>::quiet_NaN();
                if (r.floorIndirect < 0.0) r.floorIndirect = std::numeric_limits<double>::quiet_NaN();
                r.seconds = j.at("seconds").get<double>();
                r.cacheHit = true;
                return r;
            }
        } catch (const std::exception&) {
            // a broken side file: render again
        }
    }
    ReferenceTracer tracer(scene);
    std::vector<FloatImage> finals, directs, indirects;
    const auto t0 = std::chrono::steady_clock::now();
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        ReferenceOptions opt;
        opt.width = width;
        opt.height = height;
        opt.spp = spp / 4;
        opt.maxBounces = bounces;
        opt.seed = seed;
        opt.progress = false;
        const ReferenceResult res = tracer.render(camera, s, opt);
        finals.push_back(rgb(res.final));
        directs.push_back(rgb(res.direct));
        indirects.push_back(rgb(res.indirect));
        if (!quiet) std::fprintf(stderr, "bench hard:   reference chunk %d/4 (%d spp) %.1f s\n", int(seed), opt.spp, res.seconds);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.floorFinal = noiseFloor(finals[0], finals[1]);
    r.floorIndirect = noiseFloor(indirects[0], indirects[1]);
    r.final = average(finals);
    r.direct = average(directs);
    r.indirect = average(indirects);
    const FloatImage all = stackRgb({&r.final, &r.direct, &r.indirect});
    fs::create_directories(cacheDir);
    const std::string tmp = r.path + ".tmp.exr";
    writeExr(tmp, all);
    fs::rename(tmp, r.path);
    nlohmann::json j = {{"spp", spp},           {"bounces", bounces},   {"chunks", 4},
                        {"seeds", {1, 2, 3, 4}}, {"seconds", r.seconds}, {"floor_final", std::isfinite(r.floorFinal) ? r.floorFinal : -1.0},
                        {"floor_indirect", std::isfinite(r.floorIndirect) ? r.floorIndirect : -1.0},
                        {"floor_note", "relative L1 (4x4 block means of luminance) of chunks 1 and 2 (spp/4 each) / sqrt(5)"}};
    std::ofstream(side) << j.dump(1) << "\n";
    return r;
}

}  // namespace deepgi::bench
