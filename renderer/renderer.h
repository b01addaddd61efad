#pragma once
// deepgi's renderer: the Deep G-Buffer GI pipeline over a scene, into registered textures. Needs a current
// OpenGL 4.5 context (OSMesa headless, or a window's); knows nothing of windows or UI.
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/core/texture_registry.h"
#include "renderer/gl/shader_library.h"
#include "renderer/passes/pass.h"
#include "renderer/scene/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace deepgi {

class ProbeVolume;

enum class TimingMode {
    None,       // no synchronisation
    WallClock,  // glFinish around each pass (llvmpipe: timer queries miss vertex work)
    GpuQueries,  // GL_TIME_ELAPSED per pass; timings() then report the frame before last (no stall)
    ThreadCpu    // glFinish around each pass, CPU time of the calling thread: with LP_NUM_THREADS=0 llvmpipe renders on
                 // it, so other processes' load on a shared machine does not count (single-threaded times)
};

struct PassTiming {
    std::string name;
    double ms = 0.0;
};

// One pass of the pipeline as the renderer runs it, for the viewer's pipeline panel and `deepgi graph`.
struct PassGraphChannel {
    std::string texture;
    Access access;
    Levels levels = Levels::All;
    std::string sampler;  // "" = render target or copy
    int unit = -1;        // texture unit the renderer assigned (-1: not sampled)
    bool optional = false;
    bool present = false;  // the texture exists in this pipeline
};
struct PassGraphNode {
    std::string name;
    std::vector<std::string> reads, writes;  // writes: written, updated in place, or scratch
    bool enabled;
    std::vector<PassGraphChannel> channels;  // the pass's table as the renderer bound it
};

// What changed in the Scene the renderer holds (Renderer::sceneChanged), OR-ed.
enum class SceneChange : unsigned { Transforms = 1, Visibility = 2, Lights = 4, Materials = 8 };
inline unsigned operator|(SceneChange a, SceneChange b) { return unsigned(a) | unsigned(b); }
inline unsigned operator|(unsigned a, SceneChange b) { return a | unsigned(b); }

struct RendererOptions {
    std::string shaderDir = DEEPGI_SHADER_DIR;
    TimingMode timing = TimingMode::WallClock;
    // The client edits the scene live (the viewer): every frame writes Object ID (picking, the selection outline).
    // Otherwise Object ID is not written. Either way Motion (each object's own motion, with gbuffer.object_motion)
    // is written only in frames where a part moved since the last frame; its coming and going keeps the history.
    bool sceneEditing = false;
};

class Renderer {
public:
    explicit Renderer(RendererOptions options = {});
    // A renderer over other passes (tests of the pass-table rules); the default is standardPasses().
    Renderer(RendererOptions options, std::vector<std::unique_ptr<RenderPass>> passes);
    static std::vector<std::unique_ptr<RenderPass>> standardPasses();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void setScene(std::shared_ptr<const Scene> scene);  // uploads it; resets the history
    const Scene& scene() const { return *scene_; }
    // After editing the Scene given to setScene (its owner keeps a non-const pointer; call
    // Scene::updateWorldTransforms() first after moving nodes): `changes` = SceneChange bits. Transforms /
    // Visibility: object matrices re-uploaded (each object's previous transform kept for motion: the G-buffer's
    // Motion texture), shadow maps re-rendered, the probes' Embree scene refit (their history restarts on
    // Visibility; moves keep it, under its hysteresis). Lights: shadows follow by themselves; the probes and the
    // temporal history restart (no ghost of the old lighting). Materials: the GPU scene is rebuilt, the probe
    // volume re-made, the history restarts.
    void sceneChanged(unsigned changes);
    void sceneChanged(SceneChange change) { sceneChanged(unsigned(change)); }
    // Node index under pixel (x, y) (row 0 = top) of the last frame, -1 = none (sky, outside, no frame yet); from
    // the "Object ID" texture, layer 1 (written with RendererOptions::sceneEditing; -1 without).
    int objectAt(int x, int y) const;
    // 0 x 0 is allowed (a minimised window): render() then does nothing.
    void resize(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    // The guard band (gbuffer.guard_band) of the last prepared frame, in pixels on each side: screen-sized textures
    // are (width + 2 guard) x (height + 2 guard) and the image is their centre. readLayer/readDisplay/objectAt crop
    // it; a client drawing a texture itself offsets by guardTexels().
    int guardPixels() const { return guard_; }
    int frameWidth() const { return width_ + 2 * guard_; }
    int frameHeight() const { return height_ + 2 * guard_; }
    // Texels of the guard band on each side of a registered texture's level (0 for textures not screen-sized).
    int guardTexels(const TextureRegistry::Entry& e, int level = 0) const;
    // The camera the frame is rendered with: camera() widened by the guard band (camera() itself when there is none).
    Camera frameCamera() const { return guardedCamera(camera_, guard_); }
    // The camera of the next frame. Call resetHistory() as well on a cut (a jump that is not motion).
    void setCamera(const Camera& camera) { camera_ = camera; }
    const Camera& camera() const { return camera_; }
    void resetHistory() { historyValid_ = false; }
    bool historyValid() const { return historyValid_; }

    // The scene's size (the diagonal of its bounds): what lengths "x scene size" multiply (scene.length_unit = 0).
    float sceneSize() const;
    // Builds the pipeline the settings need from the pass tables (allocates textures, orders and checks the
    // passes: std::runtime_error naming pass and texture on a broken table) without rendering.
    void prepare(const Settings& settings);
    // Renders one frame. Throws gl::ShaderError if a shader has never compiled, std::runtime_error on allocation
    // failure (e.g. a size too large for memory).
    void render(const Settings& settings);

    // Runs one pass (by name()) alone on the current textures with the last frame's state: for tests.
    void executePass(const std::string& passName, const Settings& settings);

    TextureRegistry& textures() { return textures_; }
    const TextureRegistry& textures() const { return textures_; }
    gl::ShaderLibrary& shaders() { return *shaders_; }
    const std::vector<PassTiming>& timings() const { return timings_; }
    const std::vector<std::unique_ptr<RenderPass>>& passes() const { return passes_; }
    // Every pass of the pipeline prepare()/render() last built, in execution order; disabled passes are listed
    // where they would run, with enabled = false.
    std::vector<PassGraphNode> graph() const;
    const PipelineConfig& config() const { return config_; }
    const ProbeVolume* probeVolume() const { return probes_.get(); }
    uint64_t frameIndex() const { return frameIndex_; }
    int lastGeometryPasses() const;
    // Visible parts the last frame left out of the deep G-buffer as outside the view (gbuffer.view_culling).
    int lastCulledParts() const { return culledParts_; }
    // The level of the G-buffer textures that holds layer 2 after the last frame (DeepGBufferPass::layer2Level):
    // 0, or the gather's finest tap level L, whose texel T is the ray through level-0 pixel T 2^L + tapSampleOffset(L).
    int lastLayer2Level() const;
    void setTimingMode(TimingMode m) { options_.timing = m; }

    // Reads one registered layer back, row 0 at the top. decode: depth -> distance along the view axis (sky reads
    // as the far plane), oct16 normals -> unit xyz, others raw. A cube layer comes as its 6 faces side by side.
    FloatImage readLayer(const std::string& layerName, int level = 0, bool decode = true) const;
    FloatImage readFinalRadiance() const { return readLayer("Final Radiance"); }
    // The display image (sRGB 8-bit RGBA), row 0 at the top.
    std::vector<unsigned char> readDisplay() const;

private:
    Camera guardedCamera(const Camera& c, int guard) const;
    PipelineConfig makeConfig(const Settings& s) const;
    void prepareResolved(const Settings& s);  // s with lengths already in scene units
    void setupLights(const Settings& s);
    glm::mat4 uploadFrameUniforms(const Settings& s);  // returns the frame's view-projection
    FrameContext makeContext(const Settings& s);
    void buildPipeline();
    void beginPass(size_t index, FrameContext& ctx);  // the pass's begin() with its table in ctx
    void runPass(size_t index, FrameContext& ctx);
    // The slow-shader watchdog: the programs on trial that the pass just used pass if its work finishes within
    // limitMs of startMs (steady-clock ms), else they get their previous programs back. Returns false on a failure.
    bool checkTrials(const char* passName, int limitMs, double startMs);

    RendererOptions options_;
    std::unique_ptr<gl::ShaderLibrary> shaders_;
    std::shared_ptr<const Scene> scene_;
    std::unique_ptr<SceneGpu> sceneGpu_;
    Aabb lightBounds_;  // what the shadow maps cover: the scene's bounds now (moved objects included)
    TextureRegistry textures_;
    FramebufferCache fbos_;
    uint64_t fboGeneration_ = 0;
    std::vector<std::unique_ptr<RenderPass>> passes_;
    // The pipeline of config_: each pass's table and bindings (index = passes_), and the execution order.
    struct Stage {
        PassTable table;
        bool enabled = false;
        std::vector<TextureBinding> bindings;
    };
    std::vector<Stage> stages_;
    std::vector<size_t> order_;      // enabled passes in execution order
    std::vector<TextureDecl> allocations_;  // what the tables allocate
    uint64_t bindingGeneration_ = 0;  // textures_.generation() the bindings were made for
    PipelineConfig config_;
    bool configValid_ = false;
    gl::VertexArrayHandle fullscreenVao_;
    gl::BufferHandle frameUbo_, lightSsbo_, probeUbo_;
    std::unique_ptr<ProbeVolume> probes_;  // the world-space fallback (null when off)
    Settings probeSettings_;               // what probes_ was laid out with
    int lightCount_ = 0;
    std::vector<int> lightTypes_;  // per light, its LightType (GpuLight::radiance.w): FrameContext::lightTypes
    std::vector<ShadowCaster> casters_;
    uint64_t shadowKey_ = 0;
    int width_ = 0, height_ = 0;
    int guard_ = 0;  // guard band in pixels on each side (a change restarts the history, as a resize does)
    Camera camera_, prevCamera_;
    bool softwareGl_ = false;      // llvmpipe/softpipe: the platform-dependent auto settings follow it
    bool hasVertexLayer_ = false;  // GL_ARB_shader_viewport_layer_array: gbuffer.layer_routing can be vertex
    bool historyValid_ = false;
    uint64_t frameIndex_ = 0;
    int culledParts_ = 0;
    std::vector<PassTiming> timings_;
    // GpuQueries: two sets of one GL_TIME_ELAPSED query per pass; a set is read back when reused two frames later.
    std::vector<gl::QueryHandle> queries_[2];
    std::vector<std::string> queryNames_[2];
};

}  // namespace deepgi
