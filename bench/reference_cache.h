#pragma once
// Path-traced references for the bench, cached on disk as 9-channel EXRs (final, direct, indirect). The key hashes
// the scene file and the files beside it, the camera, size, spp, bounces, seed and the light settings.
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/scene/scene.h"

#include <cstdint>
#include <string>

namespace deepgi::bench {

// A reference from the cache, or rendered and stored there. The key hashes the scene file and the files beside it,
// the camera, size, spp, bounces, seed and the light settings.
struct CachedReference {
    FloatImage final, direct, indirect;
    bool cacheHit = false;
    std::string path;
    double seconds = 0.0;
};
std::string referenceKey(const Scene& scene, const Camera& camera, const Settings& s, int width, int height, int spp,
                         int bounces, uint64_t seed);
CachedReference cachedReference(const Scene& scene, const Camera& camera, const Settings& s, int width, int height,
                                int spp, int bounces, const std::string& cacheDir, bool quiet = true);

// A cached reference with its noise floor.
struct FloorReference {
    FloatImage final, direct, indirect;
    double floorFinal = 0, floorIndirect = 0;  // relL1 of two quarter-sample renders / sqrt(5)
    double seconds = 0;                        // render time (when it was made)
    bool cacheHit = false;
    std::string path;
};
// Renders (or loads from cacheDir) a reference as 4 chunks of spp/4 samples with seeds 1..4, averaged.
FloorReference floorReference(const Scene& scene, const Camera& camera, const Settings& s, int width, int height,
                              int spp, int bounces, const std::string& cacheDir, bool quiet);

}  // namespace deepgi::bench
