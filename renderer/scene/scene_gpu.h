#pragma once
// The scene's geometry, materials and textures on the GPU, drawn in batches grouped by material. Vertices stay as
// loaded; each carries its part's index (attribute 7), which selects the part's current and previous model
// matrices in the object buffer (shaders/scene_objects.glsl, SSBO binding 5). Hidden parts are left out of the draws.
#include "renderer/gl/gl.h"
#include "renderer/scene/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace deepgi {

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);
    // Bytes of the buffers the constructor uploads for `scene`: vertices, their part indices, indices and the object
    // buffer (3 matrices + an id per part). For `deepgi buffers`.
    static uint64_t geometryBytes(const Scene& scene);
    SceneGpu(const SceneGpu&) = delete;
    SceneGpu& operator=(const SceneGpu&) = delete;

    // Which of a material's textures are bound (material.glsl's BASE_TEX ... OCCLUSION_TEX): each is a shader
    // variant, since llvmpipe samples a texture under `if (uniform)` whatever the uniform says (every draw read
    // all five units, bound or not).
    enum MaterialTexture : unsigned { kBaseTex = 1, kEmissiveTex = 2, kMetalRoughTex = 4, kNormalTex = 8, kOcclusionTex = 16 };
    // The defines of a mask of MaterialTexture bits.
    static std::vector<std::string> materialTextureDefines(unsigned textures);
    // Returns the program to draw the batches whose materials have these textures, in use and with its own
    // uniforms set; called once per change of the mask.
    using ProgramFor = std::function<GLuint(unsigned textures)>;

    // Draws the batches with the given alpha mode (masked or opaque) with the program programFor() gives for
    // each material's textures, setting its material uniforms (material.glsl) and binding textures. Back faces
    // are culled except for double-sided materials when cullBackFaces is set.
    // instances > 1: every batch drawn that many times (gl_InstanceID), e.g. once per layer of a layered target.
    // viewCulled: the parts the last cullToView() left out are not drawn either.
    void draw(const ProgramFor& programFor, bool masked, bool cullBackFaces, int instances = 1, bool viewCulled = false) const;
    bool hasMasked() const { return hasMasked_; }
    bool hasOpaque() const { return hasOpaque_; }
    bool empty() const { return batches_.empty(); }

    // Reads every part's current model matrix and visibility from the scene (after an edit).
    void updateObjects(const Scene& scene);
    // Before a frame's passes: uploads {current, previous} matrices (previous = the last frame's, or the current
    // ones without history) and binds the object buffer at 5.
    void beginFrame(bool historyValid);
    // Marks the parts whose bounds, moved by their current model matrices, lie wholly beyond one clip plane of
    // viewProj (what the rasteriser would clip whole), for draws with viewCulled; no matrix: none. Call after
    // updateObjects(). Returns how many visible parts it leaves out.
    int cullToView(const glm::mat4* viewProj);
    // Whether a part's model matrix differs from the last frame's (endFrame()): this frame has object motion.
    bool objectsMoved() const { return current_ != lastFrame_; }
    // After a frame: its matrices become the previous ones.
    void endFrame() { lastFrame_ = current_; }
    // Changes whenever a part moved or its visibility changed (the shadow maps' key).
    uint64_t version() const { return version_; }
    static constexpr GLuint kObjectBinding = 5;
    static constexpr GLuint kObjectAttribute = 7;

private:
    struct Range { uint32_t firstIndex, indexCount; int part; };
    struct Batch {
        int material;
        uint32_t firstIndex, indexCount;
        int32_t baseVertex;
        std::vector<Range> parts;  // consecutive sub-ranges, one per part
    };
    void drawBatch(const Batch& b, int instances, const std::vector<char>& drawn, bool allDrawn) const;
    std::vector<glm::mat4> current_, lastFrame_, uploadedPrev_;
    std::vector<Aabb> partBounds_;  // per part, its vertices as loaded; invalid (never culled) if one is not finite
    std::vector<char> visible_, inView_;  // inView_: visible and not culled by the last cullToView()
    bool allVisible_ = true, allInView_ = true, objectsDirty_ = true;
    uint64_t version_ = 1;
    std::vector<int> nodeOfPart_;
    GLsizeiptr objectBytes_ = 0;
    gl::BufferHandle objectIds_, objectSsbo_;
    std::vector<Batch> batches_;
    std::vector<Material> materials_;
    std::vector<gl::TextureHandle> textures_;  // one per Scene::textures entry (0 = failed/absent)
    gl::VertexArrayHandle vao_;
    gl::BufferHandle vbo_, ibo_;
    bool hasMasked_ = false, hasOpaque_ = false;
};

}  // namespace deepgi
