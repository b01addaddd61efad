#pragma once
// A render pass: one class, one shader file. It declares the textures it owns and names those it reads/writes.
#include "renderer/core/settings.h"
#include "renderer/core/texture_registry.h"
#include "renderer/gl/gl.h"
#include "renderer/gl/shader_library.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_gpu.h"

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

namespace deepgi {

class ProbeVolume;

// What this frame's pipeline contains, derived from the scene and the settings (model only what is needed).
struct PipelineConfig {
    bool layer2 = true;
    bool emission = false;
    bool indirect = true;
    bool seedComposite = false;
    bool blur = true;
    bool temporal = true;
    bool temporalFirst = false;
    bool depthPeel = false;
    bool ao = false;           // the ambient-occlusion pass runs
    bool probes = false;       // the world-space probe fallback runs (probes.enabled, indirect on)
    int probeIrradianceSize[2] = {0, 0}, probeDepthSize[2] = {0, 0}, probeDataSize[2] = {0, 0};
    int shadowMapLayers = 0;   // directional + spot lights
    int shadowCubeLayers = 0;  // point lights
    bool operator==(const PipelineConfig& o) const;
};

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

struct FrameContext {
    const Settings& settings;
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

    // Draws a full-screen triangle into fbo with a viewport of w x h.
    void drawFullscreen(GLuint program, GLuint fbo, int w, int h) const;
    // Uniforms of lighting.glsl.
    void setLightUniforms(GLuint program) const;
};

class RenderPass {
public:
    virtual ~RenderPass() = default;
    virtual const char* name() const = 0;
    // Textures this pass allocates (it is their single declaration).
    virtual void declare(const PipelineConfig&, std::vector<TextureDecl>&) const {}
    virtual std::vector<std::string> reads() const = 0;
    virtual std::vector<std::string> writes() const = 0;
    virtual bool enabled(const PipelineConfig&) const { return true; }
    virtual void execute(FrameContext& ctx) = 0;
};

// Uniform helpers (location looked up by name; -1 is ignored by GL).
void setUniform(GLuint program, const char* name, int v);
void setUniform(GLuint program, const char* name, float v);
void setUniform(GLuint program, const char* name, const glm::vec2& v);
void setUniform(GLuint program, const char* name, const glm::ivec2& v);
void setUniform(GLuint program, const char* name, const glm::vec3& v);
void setUniform(GLuint program, const char* name, const glm::mat4& v);

}  // namespace deepgi
