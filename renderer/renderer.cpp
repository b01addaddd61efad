#include "renderer/renderer.h"

#include "renderer/core/util.h"
#include "renderer/core/gbuffer_codec.h"
#include "renderer/passes/ambient_occlusion_pass.h"
#include "renderer/passes/bilateral_blur_pass.h"
#include "renderer/passes/composite_pass.h"
#include "renderer/passes/deep_gbuffer_pass.h"
#include "renderer/passes/environment_pass.h"
#include "renderer/passes/input_radiance_pass.h"
#include "renderer/passes/pass_graph.h"
#include "renderer/passes/gather_select_pass.h"
#include "renderer/passes/radiosity_gather_pass.h"
#include "renderer/passes/reproject_radiance_pass.h"
#include "renderer/passes/probe_update_pass.h"
#include "renderer/passes/shadow_map_pass.h"
#include "renderer/probes/probe_volume.h"
#include "renderer/passes/temporal_blend_pass.h"
#include "renderer/scene/environment_map.h"
#include "renderer/scene/lighting.h"
#include "renderer/scene/scene_gpu.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace deepgi {

namespace {

// std140 mirror of FrameUniforms in shaders/common.glsl.
struct FrameUniformsStd140 {
    glm::mat4 view, proj, viewProj, invViewProj, prevViewProj, prevInvViewProj;
    glm::vec4 cameraPos, cameraForward, prevCameraPos, prevCameraForward, viewport, clip, prevClip, background;
    glm::vec4 radiosityGrid;
    glm::vec4 tapSample;
};

// std430 mirror of GpuLight in shaders/lighting.glsl.
struct GpuLight {
    glm::vec4 radiance, position, direction, params;
    glm::mat4 shadowMatrix;
};
static_assert(sizeof(GpuLight) == kGpuLightBytes, "GpuLight must match shaders/lighting.glsl");

double steadyMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

float projScale(const Camera& c, int height) {
    return c.perspective ? float(height) / (2.0f * std::tan(0.5f * c.yfov)) : float(height) / (2.0f * c.orthoHalfHeight);
}

}  // namespace

// Texture units 0..4 belong to SceneGpu's material textures (material.glsl); the pass tables get the rest.
static constexpr int kFirstTableUnit = 5;

std::vector<std::unique_ptr<RenderPass>> Renderer::standardPasses() {
    // The order of this list only breaks ties: the tables decide what must run before what.
    std::vector<std::unique_ptr<RenderPass>> p;
    p.push_back(std::make_unique<ShadowMapPass>());
    p.push_back(std::make_unique<EnvironmentPass>());
    p.push_back(std::make_unique<DeepGBufferPass>());
    p.push_back(std::make_unique<ReprojectRadiancePass>());
    p.push_back(std::make_unique<ProbeUpdatePass>());  // as late as it can: its rays are traced beside the draws above
    p.push_back(std::make_unique<InputRadiancePass>());
    p.push_back(std::make_unique<GatherSelectPass>());
    p.push_back(std::make_unique<RadiosityGatherPass>());
    p.push_back(std::make_unique<AmbientOcclusionPass>());
    p.push_back(std::make_unique<BilateralBlurPass>());
    p.push_back(std::make_unique<TemporalBlendPass>());
    p.push_back(std::make_unique<CompositePass>());
    return p;
}

Renderer::Renderer(RendererOptions options) : Renderer(std::move(options), standardPasses()) {}

Renderer::Renderer(RendererOptions options, std::vector<std::unique_ptr<RenderPass>> passes)
    : options_(std::move(options)), passes_(std::move(passes)) {
    shaders_ = std::make_unique<gl::ShaderLibrary>(options_.shaderDir);
    fullscreenVao_ = gl::createVertexArray("fullscreen triangle");
    frameUbo_ = gl::createBuffer("frame uniforms");
    glNamedBufferData(frameUbo_.id(), sizeof(FrameUniformsStd140), nullptr, GL_DYNAMIC_DRAW);
    lightSsbo_ = gl::createBuffer("lights");
    probeUbo_ = gl::createBuffer("probe volume uniforms");
    glNamedBufferData(probeUbo_.id(), sizeof(ProbeVolumeUniforms), nullptr, GL_DYNAMIC_DRAW);
    scene_ = std::make_shared<Scene>();
    sceneGpu_ = std::make_unique<SceneGpu>(*scene_);
    GLint extensions = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    for (GLint i = 0; i < extensions; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, "GL_ARB_shader_viewport_layer_array") == 0) hasVertexLayer_ = true;
    }
    softwareGl_ = gl::currentContextIsSoftware();
}

Renderer::~Renderer() = default;

void Renderer::setScene(std::shared_ptr<const Scene> scene) {
    scene_ = scene ? std::move(scene) : std::make_shared<Scene>();
    sceneGpu_ = std::make_unique<SceneGpu>(*scene_);
    lightBounds_ = scene_->bounds;
    probes_.reset();  // the volume traces the old scene
    shadowKey_ = 0;
    configValid_ = false;
    historyValid_ = false;
}

void Renderer::sceneChanged(unsigned changes) {
    const bool geometry = changes & (unsigned(SceneChange::Transforms) | unsigned(SceneChange::Visibility));
    if (changes & unsigned(SceneChange::Materials)) {
        sceneGpu_ = std::make_unique<SceneGpu>(*scene_);  // materials are copied into it; previous matrices restart
        historyValid_ = false;
    } else if (geometry) {
        sceneGpu_->updateObjects(*scene_);
    }
    if (geometry) {
        const Aabb now = scene_->currentBounds();
        lightBounds_ = now.valid() ? now : scene_->bounds;
    }
    // The shadow key hashes the lights and the scene version: it changes by itself.
    if (changes & unsigned(SceneChange::Lights)) historyValid_ = false;  // old lighting must not linger
    if (probes_ && (geometry || (changes & (unsigned(SceneChange::Lights) | unsigned(SceneChange::Materials))))) {
        if (changes & unsigned(SceneChange::Materials)) probes_.reset();  // its tracer holds the old materials
        else probes_->sceneChanged((changes & (unsigned(SceneChange::Lights) | unsigned(SceneChange::Visibility))) != 0);
    }
    configValid_ = configValid_ && !(changes & unsigned(SceneChange::Materials));  // emission may come or go
}

int Renderer::objectAt(int x, int y) const {
    if (!textures_.has("Object ID") || frameIndex_ == 0) return -1;
    const auto& e = textures_.entry("Object ID");
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
    x += guard_;  // image pixel -> frame texel
    y += guard_;
    if (x >= e.width || y >= e.height) return -1;
    GLuint id = 0;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(e.texture.id(), 0, x, e.height - 1 - y, 0, 1, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, sizeof(id), &id);
    return int(id) - 1;
}

void Renderer::resize(int w, int h) {
    if (w < 0 || h < 0) throw std::runtime_error("invalid size " + std::to_string(w) + "x" + std::to_string(h));
    if (w != width_ || h != height_) historyValid_ = false;
    width_ = w;
    height_ = h;
}

Camera Renderer::guardedCamera(const Camera& c, int guard) const {
    if (guard <= 0 || height_ <= 0) return c;
    Camera g = c;
    const double grow = double(height_ + 2 * guard) / double(height_);  // the same size of pixel, more of them
    if (c.perspective) g.yfov = float(2.0 * std::atan(std::tan(0.5 * double(c.yfov)) * grow));
    else g.orthoHalfHeight = float(double(c.orthoHalfHeight) * grow);
    return g;
}

int Renderer::guardTexels(const TextureRegistry::Entry& e, int level) const {
    if (guard_ <= 0 || e.decl.size.base != SizeRule::Base::Screen) return 0;
    int iw = 0, ih = 0;  // the image's own size at this texture's rule
    e.decl.size.resolve(width_, height_, 0, iw, ih);
    return std::max(0, ((e.height >> level) - std::max(1, ih >> level)) / 2);
}

int Renderer::lastGeometryPasses() const {
    for (const auto& p : passes_)
        if (auto* g = dynamic_cast<const DeepGBufferPass*>(p.get())) return g->lastGeometryPasses();
    return 0;
}

int Renderer::lastLayer2Level() const {
    for (const auto& p : passes_)
        if (auto* g = dynamic_cast<const DeepGBufferPass*>(p.get())) return g->lastLayer2Level();
    return 0;
}

PipelineConfig Renderer::makeConfig(const Settings& s) const {
    PipelineConfig c;
    c.layer2 = s.layer2 && (s.indirect || s.aoEnabled);  // only the gather and the AO read layer 2
    c.emission = scene_->hasEmission();
    c.specular = scene_->hasSpecular() && !s.diffuseOnly;
    c.occlusion = scene_->hasOcclusion();
    c.normalMaps = scene_->hasNormalMaps();
    c.objectIds = options_.sceneEditing;
    // Motion only in frames where a part moved since the last one: otherwise every surface moves with the camera,
    // which the reprojection follows without it (a still scene in the viewer: Sponza's frame 0.91 x).
    c.objectMotion = s.objectMotion && sceneGpu_ && sceneGpu_->objectsMoved();
    c.indirect = s.indirect;
    c.seedComposite = s.compositeMode == CompositeMode::Seed;
    c.blur = s.blur;
    c.temporal = s.temporal;
    c.temporalFirst = s.filterOrder == FilterOrder::TemporalFirst && s.temporal;
    c.depthPeel = s.generation == GBufferGeneration::DepthPeel && c.layer2;
    c.layeredVertex = s.layerRouting != LayerRouting::Geometry && hasVertexLayer_;
    const bool software = softwareGl_;
    c.ao = s.aoEnabled;
    c.compositeSkyDraw = software;
    // The gather's finest tap level: its radiance, depth and normal are evaluated or drawn there, not finer. It
    // follows the image's height (radiosity.min_mip_height), not the guard band's. A frame too small for that level
    // takes its coarsest (the textures' levels stop at one texel).
    if (c.indirect) {
        const int coarsest = int(std::log2(double(std::max({frameWidth(), frameHeight(), 1}))));
        c.tapLevel = std::clamp(finestTapLevel(s.minMip, s.minMipHeight, height_), 0, std::min(kMaxTapLevel, coarsest));
    }
    // Software GL splits the layers where it costs less. Layer 2 alone at a tap level L > 0 is one draw of few
    // fragments, and through the vertex route the split draws each triangle twice as the instanced single pass does:
    // no more vertex work at any triangle count (heavy scene G-buffer 0.78 x, Sponza at 320x180 0.90 x). At level 0
    // the prepass pays a third geometry pass, worth it only while fragments cost more than vertices; through the
    // geometry shader, the single pass runs it once where the split runs it twice (heavy scene 1.18 x).
    const bool fragmentBound = double(scene_->triangleCount()) < 2.0 * double(frameWidth()) * double(frameHeight());
    const bool coarseLayer2Draw = c.layeredVertex && c.tapLevel > 0;
    c.layer2Prepass = c.layer2 && (s.layer2Prepass == Layer2Prepass::On ||
                                   (s.layer2Prepass == Layer2Prepass::Auto && software && (fragmentBound || coarseLayer2Draw)));
    if (c.indirect) {
        c.radiosityDownsample = radiosityDownsample(s.radiosityResolution, software, height_);
        // The interleaved gather reuses the temporal filter's history: without the filter there is none.
        const RadiosityInterleave il = s.interleave == RadiosityInterleave::Auto
                                           ? (software ? RadiosityInterleave::Four : RadiosityInterleave::Off)
                                           : s.interleave;
        c.gatherInterleave = !s.temporal ? 1 : il == RadiosityInterleave::Two ? 2 : il == RadiosityInterleave::Four ? 4 : 1;
    }
    if (probes_) {
        c.probes = s.probesEnabled && s.indirect;  // the indirect fallback; the volume may exist for the sky alone
        c.probeDirectionalFill = c.probes && s.probeDirectionalFill;
        c.sky = environmentOn(*scene_, s);
        for (const auto& t : probes_->textures()) {
            int* size = t.name == "Probe Irradiance" ? c.probeIrradianceSize
                        : t.name == "Probe Depth"    ? c.probeDepthSize
                        : t.name == "Probe Radiance" ? c.probeRadianceSize
                                                     : c.probeDataSize;
            size[0] = t.width;
            size[1] = t.height;
        }
    }
    if (scene_->environment && s.environmentIntensity > 0.0f) {
        c.environmentMap = true;
        c.environmentMapSize[0] = scene_->environment->width;
        c.environmentMapSize[1] = scene_->environment->height;
    }
    for (const auto& l : effectiveLights(*scene_, s)) {
        if (l.type == LightType::Point) ++c.shadowCubeLayers;
        else ++c.shadowMapLayers;
    }
    return c;
}

void Renderer::setupLights(const Settings& s) {
    const std::vector<Light> lights = effectiveLights(*scene_, s);
    if (lights.size() > size_t(kMaxGpuLights))
        throw std::runtime_error((scene_->sourcePath.empty() ? std::string("scene") : scene_->sourcePath) + ": " + std::to_string(lights.size()) + " lights, more than the " +
                                 std::to_string(kMaxGpuLights) + " the renderer draws (shaders/lighting.glsl MAX_LIGHTS)");
    const Aabb& b = lightBounds_;
    const glm::vec3 center = b.valid() ? b.center() : glm::vec3(0.0f);
    const float R = std::max(b.radius(), 1e-6f);
    const int size = std::max(1, s.shadowMapSize);
    std::vector<GpuLight> gpu;
    casters_.clear();
    int mapLayer = 0, cubeLayer = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        GpuLight g{};
        g.radiance = glm::vec4(l.color * l.intensity, float(int(l.type)));
        g.position = glm::vec4(l.position, l.range);
        g.direction = glm::vec4(glm::normalize(l.direction), std::cos(l.outerConeAngle));
        g.params = glm::vec4(std::cos(l.innerConeAngle), -1.0f, 0.0f, 0.0f);
        const glm::vec3 dir = glm::normalize(l.direction);
        const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        float farthest = 0.0f;
        for (int k = 0; k < 8; ++k) {
            glm::vec3 c((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z);
            farthest = std::max(farthest, glm::length(c - l.position));
        }
        const float far = l.range > 0.0f ? std::min(l.range, farthest * 1.01f + 1e-6f) : farthest * 1.01f + 1e-6f;
        const float near = std::max(far * 1e-4f, 1e-6f);
        if (l.type == LightType::Directional) {
            // Orthographic box around the scene's bounding sphere.
            glm::mat4 view = glm::lookAt(center - dir * (2.0f * R), center, up);
            glm::mat4 proj = glm::ortho(-R, R, -R, R, R * 0.5f, R * 3.5f);
            g.shadowMatrix = proj * view;
            g.params.y = float(mapLayer);
            g.params.z = 2.0f * R / float(size);
            casters_.push_back({int(i), g.shadowMatrix, mapLayer++, false, l.position, 0.0f});
        } else if (l.type == LightType::Spot) {
            const float fov = std::min(2.0f * l.outerConeAngle + 0.1f, glm::radians(170.0f));
            glm::mat4 view = glm::lookAt(l.position, l.position + dir, up);
            g.shadowMatrix = glm::perspective(fov, 1.0f, near, far) * view;
            g.params.y = float(mapLayer);
            g.params.z = 2.0f * std::tan(0.5f * fov) / float(size);
            casters_.push_back({int(i), g.shadowMatrix, mapLayer++, false, l.position, far});
        } else {
            static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
            const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
            for (int f = 0; f < 6; ++f)
                casters_.push_back({int(i), proj * glm::lookAt(l.position, l.position + dirs[f], ups[f]), cubeLayer * 6 + f,
                                    true, l.position, far});
            g.params.y = float(cubeLayer++);
            g.params.z = 2.0f / float(size);
            g.params.w = far;
        }
        gpu.push_back(g);
    }
    lightCount_ = int(gpu.size());
    lightTypes_.clear();
    for (const GpuLight& g : gpu) lightTypes_.push_back(int(g.radiance.w));
    if (gpu.empty()) gpu.emplace_back();
    uint64_t key = fnv1a(kFnvOffset, gpu.data(), gpu.size() * sizeof(GpuLight));
    key = fnv1a(key, &size, sizeof(size));
    const void* scenePtr = sceneGpu_.get();
    key = fnv1a(key, &scenePtr, sizeof(scenePtr));
    const uint64_t sceneVersion = sceneGpu_->version();  // objects moved or hidden: the shadows are redrawn
    key = fnv1a(key, &sceneVersion, sizeof(sceneVersion));
    if (key == shadowKey_) return;  // lights unchanged: the buffer already holds them (static scenes)
    if (gpu.size() < size_t(kBlockLights)) gpu.resize(kBlockLights);  // the uniform block's whole range is defined
    glNamedBufferData(lightSsbo_.id(), GLsizeiptr(gpu.size() * sizeof(GpuLight)), gpu.data(), GL_DYNAMIC_DRAW);
    shadowKey_ = key;
}

glm::mat4 Renderer::uploadFrameUniforms(const Settings& s) {
    const int fw = frameWidth(), fh = frameHeight();
    const float aspect = float(fw) / float(std::max(fh, 1));
    FrameUniformsStd140 u{};
    // The guard band widens the view by whole pixels: the frame's centre is the image, pixel for pixel.
    const Camera cam = guardedCamera(camera_, guard_);
    const Camera prev = guardedCamera(historyValid_ ? prevCamera_ : camera_, guard_);
    u.view = cam.view();
    u.proj = cam.projection(aspect);
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.prevViewProj = prev.projection(aspect) * prev.view();
    u.prevInvViewProj = glm::inverse(u.prevViewProj);
    u.cameraPos = glm::vec4(cam.position(), cam.perspective ? 1.0f : 0.0f);
    u.cameraForward = glm::vec4(cam.forward(), 0.0f);
    u.prevCameraPos = glm::vec4(prev.position(), prev.perspective ? 1.0f : 0.0f);
    u.prevCameraForward = glm::vec4(prev.forward(), 0.0f);
    u.viewport = glm::vec4(fw, fh, 1.0f / fw, 1.0f / fh);
    u.clip = glm::vec4(cam.znear, cam.zfar, projScale(cam, fh), float(frameIndex_));
    u.prevClip = glm::vec4(prev.znear, prev.zfar, projScale(prev, fh), 0.0f);
    u.background = glm::vec4(glm::vec3(s.background), 1.0f);
    {
        int rw = 0, rh = 0;
        config_.radiositySize().resolve(fw, fh, 0, rw, rh);
        u.radiosityGrid = glm::vec4(float(config_.radiosityDownsample), float(rw), float(rh), 0.0f);
    }
    {
        const glm::ivec2 c = tapSampleOffset(config_.tapLevel);
        u.tapSample = glm::vec4(float(config_.tapLevel), float(c.x), float(c.y), 0.0f);
    }
    glNamedBufferSubData(frameUbo_.id(), 0, sizeof(u), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUbo_.id());
    return u.viewProj;
}

float Renderer::sceneSize() const { return 2.0f * scene_->bounds.radius(); }

void Renderer::prepare(const Settings& user) { prepareResolved(resolveLengths(user, sceneSize())); }

void Renderer::prepareResolved(const Settings& s) {
    if (width_ <= 0 || height_ <= 0) return;
    // A multiple of the radiosity grid's divisor (and even), so that the grid's centre is the image's, texel for texel.
    const int unit = std::max(2, radiosityDownsample(s.radiosityResolution, softwareGl_, height_));
    const int guard = unit * int(std::lround(double(s.guardBand) * double(height_) / double(unit)));
    if (guard != guard_) historyValid_ = false;  // every screen-sized buffer changes size and meaning
    guard_ = guard;
    // The probe volume exists only where it can help: indirect light on, or an environment that lights (its sky
    // visibility lives in the probes), and a scene with surfaces.
    const bool wantProbes = ((s.probesEnabled && s.indirect) || environmentOn(*scene_, s)) && scene_->bounds.valid() &&
                            scene_->bounds.radius() > 0.0f;
    if (!wantProbes) probes_.reset();
    else if (!probes_ || ProbeVolume::layoutChanged(probeSettings_, s)) {
        probes_.reset();
        probes_ = std::make_unique<ProbeVolume>(*scene_, s);
        probeSettings_ = s;
    }
    if (probes_) probes_->setViewBias(s);
    PipelineConfig c = makeConfig(s);
    const bool rebuild = !configValid_ || !(c == config_);
    // Only G-buffer targets written afresh every frame come or go (the first move adds Motion): the history holds.
    PipelineConfig sameTargets = c;
    sameTargets.normalMaps = config_.normalMaps;
    sameTargets.objectIds = config_.objectIds;
    sameTargets.objectMotion = config_.objectMotion;
    const bool keepHistory = rebuild && configValid_ && sameTargets == config_;
    if (rebuild && !keepHistory) historyValid_ = false;  // buffers change meaning
    config_ = c;
    configValid_ = true;
    if (rebuild || stages_.size() != passes_.size()) buildPipeline();
    const uint64_t before = textures_.generation();
    textures_.reconcile(allocations_, frameWidth(), frameHeight(), std::max(1, s.shadowMapSize));
    if (textures_.generation() != before && !keepHistory) historyValid_ = false;
    if (fboGeneration_ != textures_.generation()) {
        fbos_.clear();
        fboGeneration_ = textures_.generation();
    }
    if (bindingGeneration_ != textures_.generation() || rebuild) {
        // Units in table order per pass; an absent optional texture is bound as 0 (the shader does not read it).
        for (Stage& st : stages_) {
            st.bindings.clear();
            int unit = kFirstTableUnit;
            for (const Channel& ch : st.table.channels()) {
                if (ch.sampler.empty()) continue;
                st.bindings.push_back({ch.texture, ch.sampler, unit++, textures_.has(ch.texture) ? textures_.id(ch.texture) : 0});
            }
        }
        bindingGeneration_ = textures_.generation();
    }
}

void Renderer::buildPipeline() {
    stages_.assign(passes_.size(), Stage{});
    std::vector<PassInfo> infos;
    for (size_t i = 0; i < passes_.size(); ++i) {
        passes_[i]->table(config_, stages_[i].table);
        stages_[i].enabled = passes_[i]->enabled(config_);
        infos.push_back({passes_[i]->name(), stages_[i].table, stages_[i].enabled});
    }
    GLint maxUnits = 16;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &maxUnits);
    for (size_t i = 0; i < passes_.size(); ++i) {
        int sampled = 0;
        for (const Channel& ch : stages_[i].table.channels()) sampled += !ch.sampler.empty();
        if (kFirstTableUnit + sampled > maxUnits)
            throw std::runtime_error(std::string("pipeline: pass '") + passes_[i]->name() + "' samples " + std::to_string(sampled) +
                                     " textures, more than the " + std::to_string(maxUnits - kFirstTableUnit) + " units left");
    }
    try {
        allocations_ = allocations(infos);
        order_ = schedulePasses(infos);
    } catch (...) {
        configValid_ = false;  // try again (and fail again, loudly) on the next frame
        stages_.clear();
        throw;
    }
}

std::vector<PassGraphNode> Renderer::graph() const {
    std::vector<PassGraphNode> out;
    auto node = [&](size_t i) {
        PassGraphNode n{passes_[i]->name(), {}, {}, stages_[i].enabled, {}};
        for (const Channel& ch : stages_[i].table.channels()) {
            auto add = [&](std::vector<std::string>& v) { if (std::find(v.begin(), v.end(), ch.texture) == v.end()) v.push_back(ch.texture); };
            if (ch.access == Access::Read || ch.access == Access::History || ch.access == Access::Update) add(n.reads);
            if (ch.access == Access::Write || ch.access == Access::Update || ch.access == Access::Scratch) add(n.writes);
            PassGraphChannel pc{ch.texture, ch.access, ch.levels, ch.sampler, -1, ch.isOptional, textures_.has(ch.texture)};
            for (const auto& b : stages_[i].bindings)
                if (b.texture == ch.texture && b.sampler == ch.sampler) pc.unit = b.unit;
            n.channels.push_back(pc);
        }
        out.push_back(std::move(n));
    };
    if (stages_.size() != passes_.size()) return out;
    // Disabled passes go right after the enabled pass that precedes them in the pass list.
    std::vector<bool> placed(passes_.size(), false);
    auto placeDisabledAfter = [&](size_t i) {
        for (size_t j = i + 1; j < passes_.size() && !stages_[j].enabled; ++j) { node(j); placed[j] = true; }
    };
    for (size_t j = 0; j < passes_.size() && !stages_[j].enabled; ++j) { node(j); placed[j] = true; }
    for (size_t i : order_) {
        node(i);
        placed[i] = true;
        placeDisabledAfter(i);
    }
    for (size_t j = 0; j < passes_.size(); ++j) if (!placed[j]) node(j);
    return out;
}

void Renderer::beginPass(size_t i, FrameContext& ctx) {
    ctx.pass = passes_[i].get();  // its table, as in execute(): the textures it may name
    ctx.table = &stages_[i].table;
    ctx.bindings = &stages_[i].bindings;
    passes_[i]->begin(ctx);
}

void Renderer::runPass(size_t i, FrameContext& ctx) {
    const Stage& st = stages_[i];
    for (const auto& b : st.bindings) glBindTextureUnit(GLuint(b.unit), b.id);
    ctx.pass = passes_[i].get();
    ctx.table = &st.table;
    ctx.bindings = &st.bindings;
    passes_[i]->execute(ctx);
    for (const auto& b : st.bindings) glBindTextureUnit(GLuint(b.unit), 0);
}

void Renderer::render(const Settings& user) {
    timings_.clear();
    if (width_ <= 0 || height_ <= 0) return;  // minimised: nothing to draw, nothing lost
    const Settings s = resolveLengths(user, sceneSize());  // the passes see lengths in scene units
    prepareResolved(s);
    FrameContext ctx = makeContext(s);

    using clock = std::chrono::steady_clock;
    const bool gpu = options_.timing == TimingMode::GpuQueries;
    const bool cpu = options_.timing == TimingMode::ThreadCpu;
    const bool finish = options_.timing == TimingMode::WallClock || cpu;
    auto& queries = queries_[frameIndex_ % 2];
    auto& queryNames = queryNames_[frameIndex_ % 2];
    if (gpu) {
        // Results of this set's previous use (two frames ago) are ready by now without stalling in practice.
        for (size_t i = 0; i < queryNames.size(); ++i) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(queries[i].id(), GL_QUERY_RESULT, &ns);
            timings_.push_back({queryNames[i], double(ns) * 1e-6});
        }
        queryNames.clear();
    }
    if (finish) glFinish();
    // Each pass's begin() counts in its own timing (wall clock or CPU time of this thread; queries cannot see it).
    std::vector<double> beginMs(passes_.size(), 0.0);
    for (size_t index : order_) {
        const auto b0 = clock::now();
        const double c0 = cpu ? threadCpuMs() : 0.0;
        beginPass(index, ctx);
        beginMs[index] = cpu ? threadCpuMs() - c0 : std::chrono::duration<double, std::milli>(clock::now() - b0).count();
    }
    size_t q = 0;
    bool rejected = false;  // a program failed its trial: this frame's outputs must not feed the next
    for (size_t index : order_) {
        RenderPass* p = passes_[index].get();
        // Watchdog frames time each pass alone: earlier passes' work is finished first, and uses of programs on
        // trial outside the passes (the viewer's buffer views) are forgotten.
        const bool watch = s.shaderWatchdogMs > 0 && shaders_->anyOnTrial();
        if (watch) {
            glFinish();
            shaders_->takeTrialUses();
        }
        const double watchStart = steadyMs();
        auto t0 = clock::now();
        const double c0 = cpu ? threadCpuMs() : 0.0;
        if (gpu) {
            if (q == queries.size()) {
                GLuint id = 0;
                glCreateQueries(GL_TIME_ELAPSED, 1, &id);
                queries.emplace_back(id);
            }
            glBeginQuery(GL_TIME_ELAPSED, queries[q].id());
        }
        runPass(index, ctx);
        if (gpu) {
            glEndQuery(GL_TIME_ELAPSED);
            queryNames.push_back(p->name());
            ++q;
        }
        if (watch && !checkTrials(p->name(), s.shaderWatchdogMs, watchStart)) rejected = true;
        if (!gpu && finish) {
            glFinish();
            timings_.push_back({p->name(), beginMs[index] + (cpu ? threadCpuMs() - c0 : std::chrono::duration<double, std::milli>(clock::now() - t0).count())});
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    prevCamera_ = camera_;
    sceneGpu_->endFrame();
    historyValid_ = !rejected;
    ++frameIndex_;
}

bool Renderer::checkTrials(const char* passName, int limitMs, double startMs) {
    const std::vector<std::string> used = shaders_->takeTrialUses();
    if (used.empty()) return true;
    // A fence after the pass's commands, waited on for what is left of the limit (flushing them).
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    const double left = std::max(0.0, double(limitMs) - (steadyMs() - startMs));
    const GLenum r = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(left * 1e6));
    // Also over the limit: draw calls that did their work on this thread (llvmpipe's vertex stages, or all of it
    // with LP_NUM_THREADS=0) before the fence existed.
    const bool slow = r == GL_TIMEOUT_EXPIRED || r == GL_WAIT_FAILED || steadyMs() - startMs > double(limitMs);
    if (!slow) {
        for (const auto& key : used) shaders_->passTrial(key);
    } else {
        glFinish();  // the slow program may still be running: let it finish before it is deleted
        char reason[256];
        std::snprintf(reason, sizeof(reason),
                      "pass '%s' took %.0f ms on a frame after the hot reload, over debug.shader_watchdog_ms = %d; "
                      "the previous program is restored",
                      passName, steadyMs() - startMs, limitMs);
        for (const auto& key : used) shaders_->failTrial(key, reason);
    }
    glDeleteSync(fence);
    return !slow;
}

FrameContext Renderer::makeContext(const Settings& s) {
    setupLights(s);
    const glm::mat4 viewProj = uploadFrameUniforms(s);
    sceneGpu_->beginFrame(historyValid_ && s.objectMotion);  // without: last frame's matrices = this frame's
    culledParts_ = sceneGpu_->cullToView(s.viewCulling ? &viewProj : nullptr);
    FrameContext ctx{s, config_, textures_, *shaders_, fbos_, *sceneGpu_, fullscreenVao_.id(), lightSsbo_.id(),
                     lightCount_, casters_, shadowKey_, frameWidth(), frameHeight(), historyValid_,
                     s.varyTaps ? float(frameIndex_ % 1024) * 0.618034f : 0.0f, probes_.get(), probeUbo_.id()};
    ctx.environment = scene_->environment.get();
    ctx.lightTypes = &lightTypes_;
    ctx.frameIndex = frameIndex_;
    return ctx;
}

void Renderer::executePass(const std::string& passName, const Settings& user) {
    if (width_ <= 0 || height_ <= 0) return;
    const Settings s = resolveLengths(user, sceneSize());
    prepareResolved(s);
    FrameContext ctx = makeContext(s);
    for (size_t i : order_)
        if (passName == passes_[i]->name()) {
            beginPass(i, ctx);  // alone, its begin() has nothing to run beside
            runPass(i, ctx);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            return;
        }
    std::string running;  // a pass that exists but is off (ao.enabled=false) has no textures to run on
    for (size_t i : order_) running += (running.empty() ? std::string() : std::string(", ")) + passes_[i]->name();
    for (const auto& p : passes_)
        if (passName == p->name())
            throw std::runtime_error("pass '" + passName + "' does not run with these settings (passes that run: " +
                                     running + ")");
    throw std::runtime_error("no pass named '" + passName + "' (passes that run: " + running + ")");
}

FloatImage Renderer::readLayer(const std::string& layerName, int level, bool decode) const {
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!textures_.findLayer(layerName, &e, &layer)) throw std::runtime_error("no buffer named '" + layerName + "'");
    const TextureDecl& d = e->decl;
    const bool cube = d.target == GL_TEXTURE_CUBE_MAP_ARRAY;
    level = std::clamp(level, 0, d.levels - 1);
    const int guard = cube ? 0 : guardTexels(*e, level);  // the guard band is not part of the image
    const int w = std::max(1, (e->width >> level) - 2 * guard), h = std::max(1, (e->height >> level) - 2 * guard);
    const bool depth = gl::isDepthFormat(d.format);
    const int faces = cube ? 6 : 1;
    const bool integer = d.format == GL_R32UI;  // Object ID: read as integers, returned as floats (exact below 2^24)
    const int channels = gl::formatChannels(d.format);
    const GLenum fmt = depth ? GL_DEPTH_COMPONENT : integer ? GL_RED_INTEGER : channels == 1 ? GL_RED : channels == 2 ? GL_RG : channels == 3 ? GL_RGB : GL_RGBA;
    std::vector<float> raw(size_t(w) * h * channels * faces);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const int zoff = d.target == GL_TEXTURE_2D ? 0 : (cube ? layer * 6 : layer);
    if (integer) {
        std::vector<uint32_t> ids(raw.size());
        glGetTextureSubImage(e->texture.id(), level, guard, guard, zoff, w, h, faces, fmt, GL_UNSIGNED_INT, GLsizei(ids.size() * sizeof(uint32_t)), ids.data());
        for (size_t i = 0; i < ids.size(); ++i) raw[i] = float(ids[i]);
    } else {
        glGetTextureSubImage(e->texture.id(), level, guard, guard, zoff, w, h, faces, fmt, GL_FLOAT, GLsizei(raw.size() * sizeof(float)), raw.data());
    }

    FloatImage img;
    img.width = w * faces;
    img.height = h;
    const bool decodeNormal = decode && d.vis == Visualize::Normal;
    const bool decodeDepth = decode && d.vis == Visualize::Depth;
    img.channels = decodeNormal ? 3 : channels;
    img.pixels.assign(size_t(img.width) * h * img.channels, 0.0f);
    const bool persp = camera_.perspective;
    const float n = camera_.znear, f = camera_.zfar;
    for (int face = 0; face < faces; ++face)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* src = &raw[((size_t(face) * h + y) * w + x) * channels];
                const int ox = face * w + x, oy = h - 1 - y;  // GL rows are bottom-up
                if (decodeNormal) {
                    const glm::vec3 v = octDecode(src[0], src[1]);
                    for (int c = 0; c < 3; ++c) img.at(ox, oy, c) = v[c];
                } else if (decodeDepth) {
                    float dv = src[0];
                    float z = linearDepth(dv, n, f, persp);
                    img.at(ox, oy, 0) = std::min(z, f);
                } else {
                    for (int c = 0; c < channels; ++c) img.at(ox, oy, c) = src[c];
                }
            }
    return img;
}

std::vector<unsigned char> Renderer::readDisplay() const {
    const auto& e = textures_.entry("Final Display");
    const int g = guardTexels(e), w = e.width - 2 * g, h = e.height - 2 * g;
    std::vector<unsigned char> px(size_t(w) * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(e.texture.id(), 0, g, g, 0, w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    std::vector<unsigned char> flipped(px.size());
    const size_t row = size_t(w) * 4;
    for (int y = 0; y < h; ++y) std::memcpy(&flipped[y * row], &px[(h - 1 - y) * row], row);
    return flipped;
}

}  // namespace deepgi
