#pragma once
// World-space irradiance probes (DDGI: Majercik et al., "Dynamic Diffuse Global Illumination with Ray-Traced
// Irradiance Fields", JCGT 2019): the fallback for indirect light where the screen holds no data.
//
// A grid fit to the scene's bounds; each probe keeps an octahedral map of irradiance and one of depth moments
// (mean distance, mean squared distance), updated round-robin by rays traced on the CPU with Embree, a bounded
// number per frame. A ray's radiance is what the path tracer computes at its first hit with the probes standing
// in for the rest of the path: emission + albedo/pi * (direct irradiance with shadow rays + the probes' own
// irradiance at the hit), so each update adds a bounce. Sampling weighs the 8 surrounding probes by trilinear
// weight, a smooth back-face term and a Chebyshev visibility test on the depth moments (no light through walls).
//
// What is stored is irradiance E (W/m^2), linear: the indirect radiance of a Lambertian receiver is albedo/pi * E.
// The same sampling exists in C++ (irradiance()) and in GLSL (shaders/probe_volume.glsl, probeIrradiance()).
//
// Textures (CPU arrays laid out as GL textures, row 0 first; probe i owns tile (i % tilesPerRow, i / tilesPerRow)):
//   "Probe Irradiance"  GL_RGBA32F, (tilesPerRow * (I+2)) x (tileRows * (I+2)), I = probes.irradiance_texels:
//                       rgb irradiance per octahedral direction, a = 1; a 1-texel octahedral border per tile.
//   "Probe Depth"       GL_RG32F, (tilesPerRow * (D+2)) x (tileRows * (D+2)), D = probes.depth_texels:
//                       r = mean distance, g = mean squared distance to the first surface (scene units).
//   "Probe Data"        GL_RGBA32F, tilesPerRow x tileRows: xyz = the probe's offset from its grid position
//                       (scene units), w = ProbeState as a float (1 = sampled; 0, -1 = not).
//   "Probe Radiance"    GL_RGBA32F, (tilesPerRow * (R+2)) x (tileRows * (R+2)), R = probes.radiance_texels: the
//                       radiance arriving at each probe per octahedral direction (rgb; a = the mean distance to the
//                       surface those rays hit, unclamped, 2 x the grid's diagonal for a miss), the same rays binned
//                       by the texel they leave through; a 1-texel border per tile. The gather fills with it the
//                       directions whose surface the screen does not hold (radiance(); shaders/probe_volume.glsl
//                       probeRadianceDistanceAt()).
// RGBA16F also works for the irradiance (uploadTextures() sends floats, the driver converts) while it stays below
// 65504; the depth needs RG32F (squared distances pass 65504 at 256 scene units).
//
// The caller decides whether to use it (probes.enabled). Cost, 2 cores: ~1.7-2.3 us of CPU per probe ray with its
// shadow rays, texel updates and bounce lookups (16384 rays/frame ~ 30-38 ms CPU on the Cornell box and the atrium).
// One difference from the path tracer, on purpose: probe rays stop at back faces of single-sided surfaces (they
// count for depth and as votes that the probe is inside geometry, not for irradiance).
#include "renderer/core/settings.h"
#include "renderer/probes/probe_tracer.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/scene.h"

#include <glad/gl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace deepgi {

// Probes sit at cell centres: origin + (i + 0.5) * spacing covers the bounds, at least 2 per axis.
struct ProbeGrid {
    glm::ivec3 counts{2};
    glm::vec3 lo{0.0f};        // the corner of the covered box; probe (0,0,0) is at lo + spacing / 2
    glm::vec3 spacing{1.0f};   // per axis, scene units
    float requestedSpacing = 1.0f;  // what the settings asked for, scene units
    bool coarsened = false;    // spacing grew so that the count fits probes.max_count
    int count() const { return counts.x * counts.y * counts.z; }
    int index(const glm::ivec3& c) const { return c.x + counts.x * (c.y + counts.y * c.z); }
    glm::ivec3 coord(int i) const { return {i % counts.x, (i / counts.x) % counts.y, i / (counts.x * counts.y)}; }
    glm::vec3 gridPosition(const glm::ivec3& c) const { return lo + (glm::vec3(c) + 0.5f) * spacing; }
    float minSpacing() const { return std::min(spacing.x, std::min(spacing.y, spacing.z)); }
};

// Throws std::runtime_error when the bounds are invalid or not finite, or the spacing is not positive.
ProbeGrid fitProbeGrid(const Aabb& bounds, const Settings& settings);

enum class ProbeState : int8_t {
    Active = 1,   // updated and sampled
    Inside = 0,   // inside geometry (too many back faces even after moving it): never updated nor sampled
    Unused = -1,  // no surface within a cell diagonal: no receiver needs it, never updated nor sampled
};

struct ProbeUpdateStats {
    int probesUpdated = 0;
    uint64_t probeRays = 0;   // rays cast from probes (bounded by probes.rays_per_frame)
    uint64_t shadowRays = 0;  // shadow rays cast from their hits towards the lights
    double milliseconds = 0.0;     // wall time from its start to its commit (beside other work when started apart)
    double cpuMilliseconds = 0.0;  // CPU time of the threads that picked, traced and committed the probes
};

// std140 mirror of the GLSL block ProbeVolumeUniforms (shaders/probe_volume.glsl).
struct ProbeVolumeUniforms {
    float lo[4];          // xyz grid corner; w unused
    float spacing[4];     // xyz per-axis spacing; w = 1 once every active probe has been updated, else 0
    int32_t counts[4];    // xyz probe counts; w = tiles per atlas row
    int32_t texels[4];    // x = irradiance interior texels, y = depth, z = active probes, w = radiance texels
    float bias[4];        // x = normal bias, y = view bias (scene units), zw unused
};
static_assert(sizeof(ProbeVolumeUniforms) == 80, "std140 layout");

struct ProbeTextureDesc {
    std::string name;       // "Probe Irradiance", "Probe Depth", "Probe Data"
    GLenum internalFormat;  // GL_RGBA32F, GL_RG32F, GL_RGBA32F
    GLenum uploadFormat;    // GL_RGBA, GL_RG, GL_RGBA (type GL_FLOAT)
    int width, height, channels;
    const float* data;      // width * height * channels floats, row 0 first; valid until the volume changes
    std::string description;
};

class ProbeVolume {
public:
    // Builds the Embree scene, fits the grid and places the probes (moves or disables those inside geometry),
    // tracing a fixed set of rays from each. The Scene must outlive the volume. threads: 0 = all cores. Results
    // depend on the seed only, never on the thread count. Throws std::runtime_error on an empty or non-finite
    // scene or an Embree failure.
    ProbeVolume(const Scene& scene, const Settings& settings, uint64_t seed = 1, int threads = 0);
    ~ProbeVolume();
    ProbeVolume(const ProbeVolume&) = delete;
    ProbeVolume& operator=(const ProbeVolume&) = delete;

    // True when a settings change needs a new ProbeVolume (grid, texel counts, placement); the other probes.*
    // settings and the lights are read by every update().
    static bool layoutChanged(const Settings& a, const Settings& b);

    // One frame's work: the next active probes round-robin, probes.rays_per_frame / probes.rays_per_probe of
    // them (at least one; a probe's rays are capped at probes.rays_per_frame), each with probes.rays_per_probe
    // rays in a direction set rotated at random every update. Lights come from effectiveLights(scene, settings).
    ProbeUpdateStats update(const Settings& settings);
    // update() in two halves, for a caller with other work meanwhile (the renderer's G-buffer draws): startUpdate()
    // picks the probes and starts `helpers` threads tracing their rays (background: at the lowest priority, so that
    // they take only the CPU the caller's other threads leave); finishUpdate() traces what is left on its own
    // thread, joins them and commits, with the result of update() to the bit. In between the volume's state is
    // only read, so the const lookups stay safe; resetHistory(), sceneChanged(), setViewBias() and another
    // startUpdate() finish a pending update first, as if it had run at once.
    void startUpdate(const Settings& settings, int helpers, bool background);
    ProbeUpdateStats finishUpdate();  // nothing pending: zeros
    bool updatePending() const { return flight_ != nullptr; }
    const ProbeUpdateStats& lastUpdate() const { return lastUpdate_; }  // the last finished update's figures
    int threads() const { return threads_; }  // tracing threads of update(), the calling one included
    // Restarts every probe's history (e.g. after the lights moved): the next update of a probe replaces it, and the
    // updates from then on (rotations, round-robin order) are those of a new volume.
    void resetHistory();
    // After a scene edit (issue 14): the tracer follows moved/hidden parts; restart = every probe's history restarts
    // too (lights or visibility changed). Moves alone keep it: restarting every frame of an animation would leave
    // the probes dark, and their hysteresis bounds the lag. Either way the settle count starts again (settled()),
    // and the probes near a part that moved or was hidden or shown (its bounds before and after, within a cell
    // diagonal plus the relocation limit) are placed again; one whose offset or state changes starts over.
    void sceneChanged(bool restart);
    // The probes have converged for the scene as it is: every active probe has had probes.settle_updates updates
    // since the last scene change or restart (0 = never settled) and, after a change that kept the history, at
    // least as many as the hysteresis needs to blend the scene before it out to 1% (151 at 0.97).
    bool settled(const Settings& settings) const;
    // Probes placed again by the last sceneChanged() (tests, the status line).
    int lastReplacedCount() const { return lastReplaced_; }

    // Irradiance at world position x on a surface of unit normal n, as shaders/probe_volume.glsl computes it.
    // Safe from many threads, not during update().
    // weightSum (optional) receives the total weight of the probes used (0 = no probe could answer). view: the
    // unit direction from x towards the camera that sees it, 0 = none: the receiver is moved probes.view_bias x
    // spacing along it before the visibility test (DDGI's view bias, against leaks through thin walls; the probes'
    // own bounce at their rays' hits uses none: with it, the sun patch's multi-bounce ratio rose 1.055 -> 1.126).
    glm::vec3 irradiance(const glm::vec3& x, const glm::vec3& n, float* weightSum = nullptr,
                         const glm::vec3& view = glm::vec3(0.0f)) const;
    // probes.view_bias is a lookup's parameter, not the probes' state (their own bounce uses none): a new value
    // applies at once, without a new volume (layoutChanged() ignores it).
    void setViewBias(const Settings& s);

    // ---- The sky (renderer/scene/environment_map.h) ----------------------------------------------------------
    // With an environment that lights (environmentOn), each probe also keeps the irradiance the environment brings
    // it (the uniform sky through its rays that leave the scene; the map through rays_per_probe / 4, at least 16,
    // rays of its own drawn from the map's importance sampling): "Probe Sky Irradiance", laid out as "Probe Irradiance" (RGBA32F, a = 1),
    // updated by the same rays with the same hysteresis, sampled with the same weights and Chebyshev visibility
    // (skyIrradiance(), shaders/environment.glsl): direct sky light with visibility, never through closed walls.
    // It is kept apart from the probe irradiance because it lights every pixel, where the probe irradiance only
    // fills what the screen's gather misses. The probes' own bounce includes sky-lit surfaces (undamped: sky light
    // at a hit is direct light there). Without an environment nothing of it is allocated or computed.
    bool hasSky() const { return !sky_.empty(); }
    glm::vec3 skyIrradiance(const glm::vec3& x, const glm::vec3& n, float* weightSum = nullptr,
                            const glm::vec3& view = glm::vec3(0.0f)) const;
    ProbeTextureDesc skyTexture() const;  // valid while hasSky()
    // Uploads the tile rows the last updates changed (everything with all); call before uploadTextures().
    void uploadSkyTexture(GLuint skyTex, bool all = false) const;
    const std::vector<float>& skyAtlas() const { return sky_; }  // RGBA, as irradianceAtlas()

    const ProbeGrid& grid() const { return grid_; }
    int probeCount() const { return grid_.count(); }
    int activeProbeCount() const { return activeCount_; }
    ProbeState state(int probe) const { return state_[probe]; }
    glm::vec3 probePosition(int probe) const;  // grid position + relocation offset
    glm::vec3 probeOffset(int probe) const { return offset_[probe]; }
    int updatesOf(int probe) const { return updates_[probe]; }  // since the last restart (the blend's ramp)
    int updatesSinceChangeOf(int probe) const { return sinceChange_[probe]; }  // since the last scene change
    uint64_t updateCount() const { return updateIndex_; }
    bool converging() const;  // some active probe has not been updated yet
    float normalBias() const { return normalBias_; }
    // Rays cast while placing the probes, and how long it took.
    uint64_t placementRays() const { return placementRays_; }
    double placementMilliseconds() const { return placementMs_; }

    // The three textures, as described at the top of this file.
    std::vector<ProbeTextureDesc> textures() const;
    ProbeVolumeUniforms uniforms() const;
    // glTextureSubImage2D into textures allocated with (at least) the sizes of textures(): the tile rows the
    // updates since the last upload changed (everything with all = true or on the first call). 0 = skip.
    void uploadTextures(GLuint irradianceTex, GLuint depthTex, GLuint dataTex, bool all = false) {
        uploadTextures(irradianceTex, depthTex, dataTex, 0, all);
    }
    void uploadTextures(GLuint irradianceTex, GLuint depthTex, GLuint dataTex, GLuint radianceTex, bool all);
    // glNamedBufferSubData of uniforms() into a uniform buffer of at least sizeof(ProbeVolumeUniforms).
    void uploadUniforms(GLuint uniformBuffer) const;

    // Atlas geometry (texel units).
    int tilesPerRow() const { return tilesPerRow_; }
    int tileRows() const { return tileRows_; }
    int irradianceTexels() const { return irrN_; }
    int depthTexels() const { return depthN_; }
    int radianceTexels() const { return radN_; }
    const std::vector<float>& irradianceAtlas() const { return irradiance_; }  // RGBA
    const std::vector<float>& depthAtlas() const { return depth_; }            // RG
    const std::vector<float>& probeData() const { return data_; }              // RGBA
    const std::vector<float>& radianceAtlas() const { return radiance_; }      // RGBA, as the irradiance atlas
    // Radiance arriving at world position x from direction dir (unit, pointing away from x): the texel dir leaves
    // through in the radiance atlas of each probe around x (unfiltered), weighted as irradiance() weighs them for
    // a surface of normal n.
    glm::vec3 radiance(const glm::vec3& x, const glm::vec3& n, const glm::vec3& dir) const;

private:
    struct Flight;  // an update between startUpdate() and finishUpdate()
    void traceSlots(Flight& f) const;  // traces the flight's next slots until none is left
    void traceSlot(Flight& f, int slot) const;
    void place(const Settings& settings);
    // Places the given probes (offset and state) against the tracer's geometry as it is now; returns those whose
    // offset or state changed.
    std::vector<int> placeProbes(const std::vector<int>& probes);
    void recordPlacedParts();  // each part's model matrix and visibility as the placement saw them
    // The irradiance of the given atlas (laid out as the irradiance atlas) at x, n with irradiance()'s weights.
    glm::vec3 weightedAtlasIrradiance(const std::vector<float>& atlas, const glm::vec3& x, const glm::vec3& n,
                                      float* weightSum, const glm::vec3& view = glm::vec3(0.0f)) const;
    void writeBorders(std::vector<float>& atlas, int n, int channels, int probe);
    void writeProbeData(int probe);
    // Bilinear sample (as GL_LINEAR) of probe's tile at octahedral coordinate oct in [-1,1]^2.
    // The normalised weights irradiance() gives the 8 probes around x (probe -1: none), and their sum before that.
    float probeWeights(const glm::vec3& x, const glm::vec3& n, int probes[8], float weights[8],
                       const glm::vec3& view = glm::vec3(0.0f)) const;
    template <int Channels>
    glm::vec<Channels, float> sampleAtlas(const std::vector<float>& atlas, int n, int probe, const glm::vec2& oct) const;

    const Scene& scene_;
    ProbeTracer tracer_;
    ProbeGrid grid_;
    uint64_t seed_;
    int threads_;
    int irrN_, depthN_, radN_;
    float normalBias_, viewBias_ = 0.0f, maxDistance_, missDistance_;  // depth moments clamp at maxDistance_; a radiance texel's miss counts missDistance_
    int tilesPerRow_ = 1, tileRows_ = 1;
    std::vector<ProbeState> state_;
    std::vector<glm::vec3> offset_;
    std::vector<int> updates_;
    std::vector<int> sinceChange_;  // updates since the last sceneChanged() or resetHistory(): the settle count
    bool historyKept_ = false;      // a sceneChanged(false) since the last restart: the old scene must blend out
    float maxRelocation_ = 0.0f, insideFraction_ = 0.5f;  // placement settings (layout: fixed for the volume)
    std::vector<Aabb> partRestBounds_;        // each part's vertices' bounds as loaded
    std::vector<glm::mat4> placedModels_;     // each part's model matrix when its probes were last placed
    std::vector<char> placedVisible_;         // and its visibility
    int lastReplaced_ = 0;
    int activeCount_ = 0;
    size_t cursor_ = 0;  // round-robin position over the grid
    uint64_t updateIndex_ = 0;
    std::vector<float> irradiance_, depth_, data_, radiance_;
    std::vector<float> radianceUpdates_;  // per radiance atlas texel: updates with a ray through it (its own blend)
    std::vector<float> sky_;  // the sky irradiance atlas (RGBA), empty without an environment
    // The map's share of the sky, importance-sampled (a small sun is caught by few of the probe rays): built when
    // the map or environment.intensity changes.
    std::shared_ptr<const EnvironmentLight> skyMapSampler_;
    const void* skyMapKey_ = nullptr;
    float skyMapIntensity_ = -1.0f;
    float skyMapRotation_ = 0.0f;
    struct TexelDirections {  // interior texel directions, row-major per tile, as arrays for SIMD loops
        std::vector<float> x, y, z;  // padded with zero vectors to a multiple of 8
        size_t count = 0;            // real texels
        size_t size() const { return x.size(); }
    };
    TexelDirections irrDirs_, depthDirs_;
    // Per depth texel t, the blocks of 8 texels holding one within the depth lobe's reach of any direction inside t
    // (the cos 0.8 cutoff plus the texel's own extent): a ray updates only those of the texel it leaves through.
    std::vector<uint32_t> depthLobeStart_;  // depthN_^2 + 1 offsets into depthLobeBlocks_
    std::vector<uint16_t> depthLobeBlocks_;  // each block's first texel (a multiple of 8)
    int dirtyRowLo_ = 0, dirtyRowHi_ = 0;         // tile rows [lo, hi) changed since the last upload
    bool uploadedOnce_ = false;
    uint64_t placementRays_ = 0;
    double placementMs_ = 0.0;
    std::unique_ptr<Flight> flight_;  // the pending update, if any
    ProbeUpdateStats lastUpdate_;
};

}  // namespace deepgi
