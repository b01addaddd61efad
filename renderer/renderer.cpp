#include "renderer/renderer.h"

#include "renderer/core/util.h"
#include "renderer/passes/ambient_occlusion_pass.h"
#include "renderer/passes/bilateral_blur_pass.h"
#include "renderer/passes/composite_pass.h"
#include "renderer/passes/deep_gbuffer_pass.h"
#include "renderer/passes/input_radiance_pass.h"
#include "renderer/passes/radiosity_gather_pass.h"
#include "renderer/passes/reproject_radiance_pass.h"
#include "renderer/passes/shadow_map_pass.h"
#include "renderer/passes/temporal_blend_pass.h"
#include "renderer/scene/lighting.h"
#include "renderer/scene/scene_gpu.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace deepgi {

namespace {

// std140 mirror of FrameUniforms in shaders/common.glsl.
struct FrameUniformsStd140 {
    glm::mat4 view, proj, viewProj, invViewProj, prevViewProj, prevInvViewProj;
    glm::vec4 cameraPos, cameraForward, prevCameraPos, prevCameraForward, viewport, clip, prevClip, background;
};

// std430 mirror of GpuLight in shaders/lighting.glsl.
struct GpuLight {
    glm::vec4 radiance, position, direction, params;
    glm::mat4 shadowMatrix;
};

float projScale(const Camera& c, int height) {
    return c.perspective ? float(height) / (2.0f * std::tan(0.5f * c.yfov)) : float(height) / (2.0f * c.orthoHalfHeight);
}

}  // namespace

Renderer::Renderer(RendererOptions options) : options_(std::move(options)) {
    shaders_ = std::make_unique<gl::ShaderLibrary>(options_.shaderDir);
    passes_.push_back(std::make_unique<ShadowMapPass>());
    passes_.push_back(std::make_unique<DeepGBufferPass>());
    passes_.push_back(std::make_unique<ReprojectRadiancePass>());
    passes_.push_back(std::make_unique<InputRadiancePass>());
    passes_.push_back(std::make_unique<RadiosityGatherPass>());
    passes_.push_back(std::make_unique<AmbientOcclusionPass>());
    passes_.push_back(std::make_unique<BilateralBlurPass>());
    passes_.push_back(std::make_unique<TemporalBlendPass>());
    passes_.push_back(std::make_unique<CompositePass>());
    fullscreenVao_ = gl::createVertexArray("fullscreen triangle");
    frameUbo_ = gl::createBuffer("frame uniforms");
    glNamedBufferData(frameUbo_.id(), sizeof(FrameUniformsStd140), nullptr, GL_DYNAMIC_DRAW);
    lightSsbo_ = gl::createBuffer("lights");
    scene_ = std::make_shared<Scene>();
    sceneGpu_ = std::make_unique<SceneGpu>(*scene_);
}

Renderer::~Renderer() = default;

void Renderer::setScene(std::shared_ptr<const Scene> scene) {
    scene_ = scene ? std::move(scene) : std::make_shared<Scene>();
    sceneGpu_ = std::make_unique<SceneGpu>(*scene_);
    shadowKey_ = 0;
    configValid_ = false;
    historyValid_ = false;
}

void Renderer::resize(int w, int h) {
    if (w < 0 || h < 0) throw std::runtime_error("invalid size " + std::to_string(w) + "x" + std::to_string(h));
    if (w != width_ || h != height_) historyValid_ = false;
    width_ = w;
    height_ = h;
}

int Renderer::lastGeometryPasses() const {
    for (const auto& p : passes_)
        if (auto* g = dynamic_cast<const DeepGBufferPass*>(p.get())) return g->lastGeometryPasses();
    return 0;
}

PipelineConfig Renderer::makeConfig(const Settings& s) const {
    PipelineConfig c;
    c.layer2 = s.layer2;
    c.emission = scene_->hasEmission();
    c.indirect = s.indirect;
    c.seedComposite = s.compositeMode == 1;
    c.blur = s.blur;
    c.temporal = s.temporal;
    c.temporalFirst = s.filterOrder == 1 && s.temporal;
    c.depthPeel = s.generation == 1 && s.layer2;
    c.ao = s.aoEnabled;
    for (const auto& l : effectiveLights(*scene_, s)) {
        if (l.type == LightType::Point) ++c.shadowCubeLayers;
        else ++c.shadowMapLayers;
    }
    return c;
}

void Renderer::setupLights(const Settings& s) {
    const std::vector<Light> lights = effectiveLights(*scene_, s);
    const Aabb& b = scene_->bounds;
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
    if (gpu.empty()) gpu.emplace_back();
    uint64_t key = fnv1a(kFnvOffset, gpu.data(), gpu.size() * sizeof(GpuLight));
    key = fnv1a(key, &size, sizeof(size));
    const void* scenePtr = sceneGpu_.get();
    key = fnv1a(key, &scenePtr, sizeof(scenePtr));
    if (key == shadowKey_) return;  // lights unchanged: the buffer already holds them (static scenes)
    glNamedBufferData(lightSsbo_.id(), GLsizeiptr(gpu.size() * sizeof(GpuLight)), gpu.data(), GL_DYNAMIC_DRAW);
    shadowKey_ = key;
}

void Renderer::uploadFrameUniforms(const Settings& s) {
    const float aspect = float(width_) / float(std::max(height_, 1));
    FrameUniformsStd140 u{};
    const Camera& prev = historyValid_ ? prevCamera_ : camera_;
    u.view = camera_.view();
    u.proj = camera_.projection(aspect);
    u.viewProj = u.proj * u.view;
    u.invViewProj = glm::inverse(u.viewProj);
    u.prevViewProj = prev.projection(aspect) * prev.view();
    u.prevInvViewProj = glm::inverse(u.prevViewProj);
    u.cameraPos = glm::vec4(camera_.position(), camera_.perspective ? 1.0f : 0.0f);
    u.cameraForward = glm::vec4(camera_.forward(), 0.0f);
    u.prevCameraPos = glm::vec4(prev.position(), prev.perspective ? 1.0f : 0.0f);
    u.prevCameraForward = glm::vec4(prev.forward(), 0.0f);
    u.viewport = glm::vec4(width_, height_, 1.0f / width_, 1.0f / height_);
    u.clip = glm::vec4(camera_.znear, camera_.zfar, projScale(camera_, height_), float(frameIndex_));
    u.prevClip = glm::vec4(prev.znear, prev.zfar, projScale(prev, height_), 0.0f);
    u.background = glm::vec4(glm::vec3(s.background), 1.0f);
    glNamedBufferSubData(frameUbo_.id(), 0, sizeof(u), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUbo_.id());
}

void Renderer::prepare(const Settings& s) {
    if (width_ <= 0 || height_ <= 0) return;
    PipelineConfig c = makeConfig(s);
    if (!configValid_ || !(c == config_)) historyValid_ = false;  // buffers change meaning
    config_ = c;
    configValid_ = true;
    std::vector<TextureDecl> decls;
    for (const auto& p : passes_) p->declare(config_, decls);
    const uint64_t before = textures_.generation();
    textures_.reconcile(decls, width_, height_, std::max(1, s.shadowMapSize));
    if (textures_.generation() != before) historyValid_ = false;
    if (fboGeneration_ != textures_.generation()) {
        fbos_.clear();
        fboGeneration_ = textures_.generation();
    }
}

void Renderer::render(const Settings& s) {
    timings_.clear();
    if (width_ <= 0 || height_ <= 0) return;  // minimised: nothing to draw, nothing lost
    prepare(s);
    FrameContext ctx = makeContext(s);

    std::vector<RenderPass*> order;
    for (const auto& p : passes_) order.push_back(p.get());
    if (config_.temporalFirst) {  // temporal blend before the blur
        auto blur = std::find_if(order.begin(), order.end(), [](RenderPass* p) { return dynamic_cast<BilateralBlurPass*>(p); });
        auto temporal = std::find_if(order.begin(), order.end(), [](RenderPass* p) { return dynamic_cast<TemporalBlendPass*>(p); });
        std::iter_swap(blur, temporal);
    }

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
    size_t q = 0;
    for (RenderPass* p : order) {
        if (!p->enabled(config_)) continue;
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
        p->execute(ctx);
        if (gpu) {
            glEndQuery(GL_TIME_ELAPSED);
            queryNames.push_back(p->name());
            ++q;
        } else if (finish) {
            glFinish();
            timings_.push_back({p->name(), cpu ? threadCpuMs() - c0 : std::chrono::duration<double, std::milli>(clock::now() - t0).count()});
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    prevCamera_ = camera_;
    historyValid_ = true;
    ++frameIndex_;
}

FrameContext Renderer::makeContext(const Settings& s) {
    setupLights(s);
    uploadFrameUniforms(s);
    return FrameContext{s, config_, textures_, *shaders_, fbos_, *sceneGpu_, fullscreenVao_.id(), lightSsbo_.id(),
                        lightCount_, casters_, shadowKey_, width_, height_, historyValid_,
                        s.varyTaps ? float(frameIndex_ % 1024) * 0.618034f : 0.0f};
}

void Renderer::executePass(const std::string& passName, const Settings& s) {
    if (width_ <= 0 || height_ <= 0) return;
    prepare(s);
    FrameContext ctx = makeContext(s);
    for (const auto& p : passes_)
        if (passName == p->name()) {
            p->execute(ctx);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            return;
        }
    throw std::runtime_error("no pass named '" + passName + "'");
}

FloatImage Renderer::readLayer(const std::string& layerName, int level, bool decode) const {
    const TextureRegistry::Entry* e = nullptr;
    int layer = 0;
    if (!textures_.findLayer(layerName, &e, &layer)) throw std::runtime_error("no buffer named '" + layerName + "'");
    const TextureDecl& d = e->decl;
    level = std::clamp(level, 0, d.levels - 1);
    const int w = std::max(1, e->width >> level), h = std::max(1, e->height >> level);
    const bool depth = gl::isDepthFormat(d.format);
    const bool cube = d.target == GL_TEXTURE_CUBE_MAP_ARRAY;
    const int faces = cube ? 6 : 1;
    int channels = depth ? 1 : (d.format == GL_RG8_SNORM ? 2 : (d.format == GL_RGBA8 || d.format == GL_RGBA16F ? 4 : 3));
    const GLenum fmt = depth ? GL_DEPTH_COMPONENT : channels == 2 ? GL_RG : channels == 3 ? GL_RGB : GL_RGBA;
    std::vector<float> raw(size_t(w) * h * channels * faces);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const int zoff = d.target == GL_TEXTURE_2D ? 0 : (cube ? layer * 6 : layer);
    glGetTextureSubImage(e->texture.id(), level, 0, 0, zoff, w, h, faces, fmt, GL_FLOAT, GLsizei(raw.size() * sizeof(float)), raw.data());

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
                    glm::vec3 v(src[0], src[1], 1.0f - std::abs(src[0]) - std::abs(src[1]));
                    if (v.z < 0.0f) {
                        float vx = (1.0f - std::abs(v.y)) * (v.x >= 0.0f ? 1.0f : -1.0f);
                        float vy = (1.0f - std::abs(v.x)) * (v.y >= 0.0f ? 1.0f : -1.0f);
                        v.x = vx;
                        v.y = vy;
                    }
                    v = glm::normalize(v);
                    for (int c = 0; c < 3; ++c) img.at(ox, oy, c) = v[c];
                } else if (decodeDepth) {
                    float dv = src[0];
                    float z = persp ? 2.0f * n * f / std::max(f + n - (dv * 2.0f - 1.0f) * (f - n), 1e-30f) : n + dv * (f - n);
                    img.at(ox, oy, 0) = std::min(z, f);
                } else {
                    for (int c = 0; c < channels; ++c) img.at(ox, oy, c) = src[c];
                }
            }
    return img;
}

std::vector<unsigned char> Renderer::readDisplay() const {
    const auto& e = textures_.entry("Final Display");
    std::vector<unsigned char> px(size_t(e.width) * e.height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(e.texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    std::vector<unsigned char> flipped(px.size());
    const size_t row = size_t(e.width) * 4;
    for (int y = 0; y < e.height; ++y) std::memcpy(&flipped[y * row], &px[(e.height - 1 - y) * row], row);
    return flipped;
}

}  // namespace deepgi
