#pragma once
// The environment light: what rays that leave the scene see, both shown as the backdrop and lighting the scene.
//
//   L_env(d) = environment.intensity x (environment.sky_radiance + map(d))      (W/m^2/sr, linear RGB)
//
// map(d) is an equirectangular (latitude-longitude) image read with OpenImageIO (--environment FILE: EXR, HDR or
// any format OIIO reads; 8-bit formats are decoded from sRGB). Convention, +Y up as glTF, for a unit direction d:
//   u = 0.5 + atan2(d.z, d.x) / (2 pi)     column, 0..1 left to right: u = 0.5 looks along +X, 0.75 along +Z,
//                                          0.25 along -Z, 0 and 1 along -X
//   t = acos(d.y) / pi                     row, 0..1 from the image's top row (the zenith) to its bottom (nadir)
// This is Blender/Cycles' equirectangular mapping (u = 0.5 - atan2(y, x) / 2pi, top = +Z, in Blender's z-up
// frame) carried through the glTF exporter's axis change (x, y, z)_Blender -> (x, z, -y)_glTF, and three.js's.
// Texel (i, j) covers u in [i/W, (i+1)/W), t in [j/H, (j+1)/H); lookups are bilinear between texel centres,
// wrapping in u and clamped in t.
// environment.rotation turns the map about +Y: L_env(d) = map(R_y(-angle) d), R_y counter-clockwise seen from above
// (R_y(90 deg) takes +Z to +X). OpenEXR's latitude-longitude maps put +Z at the centre and +X at u = 0.25
// (ImfEnvmap.h): -90 shows them as they were meant.
//
// A uniform sky (sky_radiance alone) needs no map. light.background stays what it was: a grey backdrop added to
// what camera rays that miss see, lighting nothing; the environment both shows and lights.
#include "renderer/core/settings.h"

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

namespace deepgi {

struct Scene;

struct EnvironmentMap {
    std::string path;              // the file, for messages
    int width = 0, height = 0;
    std::vector<float> rgb;        // width * height * 3, linear, row 0 = the top row (zenith), finite and >= 0
    std::vector<std::string> warnings;
};

// Largest map edge kept; a larger file is downscaled (with a warning) so the GL texture and the CPU copy agree.
inline constexpr int kMaxEnvironmentWidth = 8192;

// Throws std::runtime_error naming the file: unreadable or not an image, no pixels, a channel count other than
// 1-4 (or more: the first three are used), a non-finite or negative texel (its position and the count of such
// texels are named: such a map is refused, never clamped).
EnvironmentMap loadEnvironmentMap(const std::string& path);
// A map from pixels already in memory (tests, tools), checked like a file. rgb: width * height * 3.
EnvironmentMap makeEnvironmentMap(int width, int height, std::vector<float> rgb, const std::string& name);

// --environment FILE: loads the map into scene.environment and appends its warnings to scene.warnings; an empty
// path does nothing. Throws as loadEnvironmentMap.
void attachEnvironment(Scene& scene, const std::string& path);

glm::vec2 equirectFromDirection(const glm::vec3& unitDir);  // (u, t) as above
glm::vec3 directionFromEquirect(float u, float t);

// L_env for one frame's settings over the scene's map (null = none): radiance lookups, and for the path tracer
// importance sampling of the map (luminance x sin(theta), marginal over rows, conditional over columns).
class EnvironmentLight {
public:
    // withSampling: build the sampling tables (O(texels)); only the path tracer needs them.
    EnvironmentLight(const EnvironmentMap* map, const Settings& settings, bool withSampling = false);

    bool enabled() const { return enabled_; }           // some direction has radiance
    bool hasMap() const { return map_ != nullptr; }
    glm::vec3 radiance(const glm::vec3& unitDir) const;  // L_env(d)
    // True when sample()/pdf() exist: a map with radiance (a uniform sky alone is left to the BSDF's cosine
    // sampling, which samples it perfectly).
    bool sampled() const { return !marginalCdf_.empty(); }
    struct Sample {
        glm::vec3 direction{0.0f};
        float pdf = 0.0f;  // per unit solid angle
        glm::vec3 radiance{0.0f};
    };
    Sample sample(float u1, float u2) const;  // u1, u2 in [0, 1)
    float pdf(const glm::vec3& unitDir) const;  // density of sample() towards d (solid angle)

private:
    glm::vec3 texel(int x, int y) const;
    glm::vec3 toMap(const glm::vec3& d) const;    // R_y(-angle) d: the map's own direction
    glm::vec3 fromMap(const glm::vec3& m) const;  // R_y(angle) m
    const EnvironmentMap* map_ = nullptr;
    float sky_ = 0.0f, intensity_ = 1.0f;
    float cosRotation_ = 1.0f, sinRotation_ = 0.0f;
    bool enabled_ = false;
    // Sampling: per texel the weight max(its luminance, 1/4 of the largest in its 3x3 neighbourhood) x sin(theta of
    // its row): bilinear lookups reach the neighbours, so the density is positive wherever the radiance is.
    std::vector<float> marginalCdf_;     // height + 1 entries, 0 .. 1
    std::vector<float> conditionalCdf_;  // height rows of width + 1 entries, 0 .. 1
    std::vector<float> rowWeight_;       // the marginal probability of each row
    std::vector<float> texelProbability_;  // per texel, the probability of sampling it
};

// Whether settings + scene light anything through the environment (the pipeline models the sky only then).
bool environmentOn(const Scene& scene, const Settings& settings);

}  // namespace deepgi
