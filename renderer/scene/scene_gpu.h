#pragma once
// The scene's geometry, materials and textures on the GPU, drawn in batches grouped by material.
#include "renderer/gl/gl.h"
#include "renderer/scene/scene.h"

#include <vector>

namespace deepgi {

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);
    SceneGpu(const SceneGpu&) = delete;
    SceneGpu& operator=(const SceneGpu&) = delete;

    // Draws the batches with the given alpha mode (masked or opaque) using `program`, setting its material
    // uniforms (material.glsl) and binding textures. Back faces are culled except for double-sided materials
    // when cullBackFaces is set.
    void draw(GLuint program, bool masked, bool cullBackFaces) const;
    bool hasMasked() const { return hasMasked_; }
    bool hasOpaque() const { return hasOpaque_; }
    bool empty() const { return batches_.empty(); }

private:
    struct Batch {
        int material;
        uint32_t firstIndex, indexCount;
        int32_t baseVertex;
    };
    std::vector<Batch> batches_;
    std::vector<Material> materials_;
    std::vector<gl::TextureHandle> textures_;  // one per Scene::textures entry (0 = failed/absent)
    gl::VertexArrayHandle vao_;
    gl::BufferHandle vbo_, ibo_;
    bool hasMasked_ = false, hasOpaque_ = false;
};

}  // namespace deepgi
