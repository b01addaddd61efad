#pragma once
// A render pass: one class, one shader file. Its table (table()) is the single statement of every texture it reads
// and writes; the renderer allocates, binds, orders and checks the pipeline from the tables alone (pass_graph.h).
#include "renderer/core/settings.h"
#include "renderer/core/texture_registry.h"
#include "renderer/gl/gl.h"
#include "renderer/gl/program.h"
#include "renderer/gl/shader_library.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_gpu.h"

#include <glm/glm.hpp>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace deepgi {

class ProbeVolume;
struct EnvironmentMap;

// What this frame's pipeline contains, derived from the scene and the settings (model only what is needed).
struct PipelineConfig {
    bool layer2 = true;
    bool emission = false;
    bool specular = false;     // some material reflects specularly (and material.diffuse_only is off): Specular
    bool occlusion = false;    // some material has an occlusion texture: Occlusion
    bool normalMaps = false;   // some material has a normal texture: the G-buffer interpolates tangents
    bool objectIds = false;    // the client picks objects (RendererOptions::sceneEditing): Object ID
    bool objectMotion = false; // objects move (edited, animated) and gbuffer.object_motion is on: Motion
    bool indirect = true;
    bool seedComposite = false;
    bool blur = true;
    bool temporal = true;
    bool temporalFirst = false;
    bool depthPeel = false;
    bool layer2Prepass = false;  // gbuffer.layer2_prepass: layer 2's depth first, then its shading with depth EQUAL
    bool layeredVertex = false;  // gbuffer.layer_routing: gl_Layer from the vertex stage (instanced draws), no geometry shader
    // Software GL: the composite shades the sky's pixels with a draw of their own, the surfaces' draw skipping them by an
    // early depth test against layer 1's depth (llvmpipe runs both sides of the shader's sky test).
    bool compositeSkyDraw = false;
    bool ao = false;           // the ambient-occlusion pass runs
    bool probes = false;       // the world-space probe fallback runs (probes.enabled, indirect on)
    bool probeDirectionalFill = false;  // with probes: the gather fills per sector from Probe Radiance
    int probeIrradianceSize[2] = {0, 0}, probeDepthSize[2] = {0, 0}, probeDataSize[2] = {0, 0}, probeRadianceSize[2] = {0, 0};
    // The environment (renderer/scene/environment_map.h): sky = it lights the scene (the probe volume carries its
    // visibility: "Probe Sky Irradiance", same size as the probe irradiance); environmentMap = a map is shown and
    // sampled ("Environment Map", environmentMapSize).
    bool sky = false;
    bool environmentMap = false;
    int environmentMapSize[2] = {0, 0};
    int shadowMapLayers = 0;   // directional + spot lights
    int shadowCubeLayers = 0;  // point lights
    // The gather, blur and temporal filter run on a grid d times coarser (radiosity pixel p stands for the screen
    // pixel p * d + d / 2); the composite upsamples by depth and normal.
    int radiosityDownsample = 1;
    // radiosity.interleave: the gather runs on 1 in N blocks per frame, the others reuse the reprojected history.
    int gatherInterleave = 1;
    // The gather's finest tap level L (radiosity.min_mip with indirect light, else 0): its texels sample pixel
    // tapSampleOffset(L) of each 2^L block of level 0, and layer 2, where it is drawn alone, is drawn there.
    int tapLevel = 0;
    SizeRule radiositySize() const { return SizeRule::screen(1.0f / float(radiosityDownsample)); }
    bool operator==(const PipelineConfig& o) const;
};

// The mip levels the gather reads (0..kMaxTapLevel); and the level-0 pixel of each 2^L block that level L samples:
// the pixel right and below the block's centre (itself at level 0).
constexpr int kMaxTapLevel = 5;
// The finest level a tap reads in an image `height` rows tall (radiosity.min_mip, radiosity.min_mip_height): minMip,
// one level coarser per doubling of the height above minMipHeight (0: minMip at every height), at most kMaxTapLevel.
inline int finestTapLevel(int minMip, int minMipHeight, int height) {
    int level = minMip;
    if (minMipHeight > 0)
        for (long long rows = 2LL * minMipHeight; rows <= height && level < kMaxTapLevel; rows *= 2) ++level;
    return level;
}
// The radiosity grid's divisor d (radiosity.resolution): full 1, half 2, quarter 4, eighth 8; auto is full on a GPU
// and, on software GL, half below 360 image rows and quarter from 360, so the grid keeps at least 90 rows, what the
// hard suite measures at 320x180 (half); the image's height, not the guard band's frame. Auto never takes eighth: at
// 1280x720 (90 grid rows) its one-bounce figures rose to 1.13 x full resolution's (BENCHMARKS session 30).
constexpr int kQuarterRadiosityRows = 360;
inline int radiosityDownsample(RadiosityResolution r, bool softwareGl, int height) {
    switch (r) {
    case RadiosityResolution::Full: return 1;
    case RadiosityResolution::Half: return 2;
    case RadiosityResolution::Quarter: return 4;
    case RadiosityResolution::Eighth: return 8;
    case RadiosityResolution::Auto: break;
    }
    return !softwareGl ? 1 : height >= kQuarterRadiosityRows ? 4 : 2;
}
inline glm::ivec2 tapSampleOffset(int level) { return glm::ivec2((1 << level) >> 1); }

// ---- The pass table ---------------------------------------------------------------------------------------

enum class Access {
    Read,     // this frame's content, written by an earlier pass
    History,  // last frame's content: this pass runs before this frame's writers of the texture
    Write,    // creates this frame's content; the pass allocates the texture (one writer per texture and frame)
    Update,   // read-modify-write in place after the writer (mip levels from level 0, a filter); several updates
              // of one texture are ordered with after()
    Scratch,  // content lives only inside this pass; passes that all declare it scratch may share it
};
// Which mip levels a channel touches: reads depend only on writers of the levels they read.
enum class Levels { Base, Mips, All };

const char* accessName(Access a);

struct Channel {
    std::string texture;             // registry name ("Depth")
    Access access = Access::Read;
    Levels levels = Levels::All;
    std::string sampler;             // GLSL sampler uniform that reads it ("" = attached as a target or copied only)
    bool isOptional = false;         // Read/History: the pass works without it (not written this frame, or absent)
    std::string afterPass;           // Update: applied after that pass's update of the same texture, if it runs
    std::optional<TextureDecl> decl; // Write/Scratch: the texture's declaration (this pass allocates it)

    Channel& optional(bool yes = true) { isOptional = yes; return *this; }
    Channel& after(const std::string& pass) { afterPass = pass; return *this; }
    Channel& level(Levels l) { levels = l; return *this; }
};

class PassTable {
public:
    Channel& read(const std::string& texture, const std::string& sampler = "") { return add(texture, Access::Read, sampler); }
    Channel& history(const std::string& texture, const std::string& sampler = "") { return add(texture, Access::History, sampler); }
    Channel& update(const std::string& texture, const std::string& sampler = "") { return add(texture, Access::Update, sampler); }
    Channel& write(const TextureDecl& decl, const std::string& sampler = "");
    Channel& scratch(const TextureDecl& decl, const std::string& sampler = "");
    const std::vector<Channel>& channels() const { return channels_; }
    bool uses(const std::string& texture) const;

private:
    Channel& add(const std::string& texture, Access a, const std::string& sampler);
    std::vector<Channel> channels_;
};

// A texture unit the renderer assigned to one channel of a pass.
struct TextureBinding {
    std::string texture, sampler;
    int unit;
    GLuint id;  // 0 when an optional texture is absent
};

// ---- What a pass sees while it runs -----------------------------------------------------------------------

// Framebuffers keyed by their attachments; cleared whenever the registry re-creates textures.
class FramebufferCache {
public:
    struct Attachment {
        GLenum point;
        GLuint texture;
        int level = 0;
        int layer = -1;  // -1 = attach all layers (layered rendering)
    };
    GLuint get(const std::vector<Attachment>& attachments, const std::string& label);
    void clear() { fbos_.clear(); }

private:
    std::map<std::vector<int64_t>, gl::FramebufferHandle> fbos_;
};

struct ShadowCaster {
    int light;           // index into the frame's lights
    glm::mat4 viewProj;  // one per face
    int layer;           // layer of "Shadow Maps", or face index (layer*6+face) of "Shadow Cubes"
    bool cube;
    glm::vec3 position;
    float far;
};

class RenderPass;

struct FrameContext {
    const Settings& settings;  // passes read their stage's group: `const BlurSettings& b = ctx.settings;`
    const PipelineConfig& config;
    TextureRegistry& textures;
    gl::ShaderLibrary& shaders;
    FramebufferCache& fbos;
    const SceneGpu& scene;
    GLuint fullscreenVao;
    GLuint lightBuffer;  // SSBO of GpuLight (lighting.glsl), bound at 1
    int lightCount;
    const std::vector<ShadowCaster>& shadowCasters;
    uint64_t shadowKey;  // changes when the shadow maps must be re-rendered
    int width, height;
    bool historyValid;   // false on the first frame and after a camera cut
    float time;          // seconds of animation for temporally varying taps
    ProbeVolume* probes; // the world-space fallback (null when config.probes is false)
    GLuint probeUniforms;  // its uniform block (probe_volume.glsl), bound at 2
    const EnvironmentMap* environment = nullptr;  // the scene's environment map (null = none)
    const std::vector<int>* lightTypes = nullptr;  // per light of the light buffer, its LightType (null = unknown)
    uint64_t frameIndex = 0;  // frames rendered before this one (the interleaved gather's turn)
    // Set by the renderer for the pass that runs.
    const RenderPass* pass = nullptr;
    const PassTable* table = nullptr;
    const std::vector<TextureBinding>* bindings = nullptr;

    // A texture of the running pass's table; any other name is an error naming the pass (an undeclared use).
    GLuint texture(const std::string& name) const;
    const TextureRegistry::Entry& entry(const std::string& name) const;
    // Changes when a texture the running pass writes (its table's Write channels) is allocated anew, and only
    // then: a pass that fills its textures once and keeps them (shadow maps, probe atlases, the environment map)
    // compares it with the value of its last fill. A new frame size keeps it where those textures keep their size.
    uint64_t writtenTexturesKey() const;
    // Sets every sampler the program uses to the unit of its table entry; `overrides` point a sampler at another
    // texture of the table for the next draw ({"uSource", "Radiosity Scratch"}). A sampler the table does not
    // declare is an error (an undeclared read).
    void bindSamplers(const gl::Program& program,
                      std::initializer_list<std::pair<const char*, const char*>> overrides = {}) const;
    // Draws a full-screen triangle into fbo with a viewport of w x h.
    void drawFullscreen(GLuint program, GLuint fbo, int w, int h) const;
    // The same against fbo's depth attachment: depth test `depthFunc` (the triangle lies at `depth`), depth writes
    // or not; afterwards depth test off, writes on, GL_LESS, depth range [0, 1] (the state the other passes expect).
    void drawFullscreenDepthTested(GLuint program, GLuint fbo, int w, int h, GLenum depthFunc, bool depthWrite,
                                   float depth = 0.5f) const;
    // Size of the radiosity grid (config.radiositySize() of this screen).
    int radiosityWidth() const;
    int radiosityHeight() const;
};

// Uniforms of lighting.glsl (its shadow samplers come from the table: "Shadow Maps", "Shadow Cubes").
struct LightingUniforms {
    explicit LightingUniforms(gl::Program& p) : count(p, "uLightCount"), shadowBias(p, "uShadowBias") {}
    void set(const FrameContext& ctx) const;  // also binds the light buffer
    gl::OptionalUniform<int> count;  // absent where the count is a define (addLightingDefines)
    gl::Uniform<float> shadowBias;
};

// The defines of a pass that includes lighting.glsl, from this frame's light count: DEEPGI_BLOCK_LIGHTS_ONLY where
// every light is in the uniform block, and DEEPGI_LIGHT_COUNT n where there are at most kUnrolledLights of them,
// with DEEPGI_LIGHT_TYPES, their types.
void addLightingDefines(const FrameContext& ctx, std::vector<std::string>& defines);

// The optional shadow-map reads of a pass that includes lighting.glsl.
void readShadowMaps(PassTable& t);

class RenderPass {
public:
    virtual ~RenderPass() = default;
    virtual const char* name() const = 0;
    // Every texture this pass reads and writes in a pipeline of config c (its single declaration).
    virtual void table(const PipelineConfig& c, PassTable& t) const = 0;
    virtual bool enabled(const PipelineConfig&) const { return true; }
    // Called for every enabled pass before the frame's first pass runs: CPU work a pass may start on other threads
    // and finish in its execute(), beside the draws of the passes ordered before it. Must not issue GL commands.
    virtual void begin(FrameContext&) {}
    virtual void execute(FrameContext& ctx) = 0;
};

}  // namespace deepgi
