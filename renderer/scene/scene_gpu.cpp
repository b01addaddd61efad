#include "renderer/scene/scene_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>

namespace deepgi {

static GLint glWrap(WrapMode w) {
    switch (w) {
    case WrapMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
    case WrapMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
    default: return GL_REPEAT;
    }
}

SceneGpu::SceneGpu(const Scene& scene) : materials_(scene.materials) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    // Group parts by material so each material is one draw of consecutive indices.
    std::map<int, std::vector<const MeshPart*>> byMaterial;
    for (const auto& p : scene.parts)
        if (!p.indices.empty()) byMaterial[p.material].push_back(&p);
    for (const auto& [mat, parts] : byMaterial) {
        Batch b{mat, uint32_t(indices.size()), 0, 0};
        for (const MeshPart* p : parts) {
            const uint32_t base = uint32_t(vertices.size());
            vertices.insert(vertices.end(), p->vertices.begin(), p->vertices.end());
            for (uint32_t i : p->indices) indices.push_back(base + i);
        }
        b.indexCount = uint32_t(indices.size()) - b.firstIndex;
        batches_.push_back(b);
        if (scene.material(mat).masked()) hasMasked_ = true;
        else hasOpaque_ = true;
    }
    vao_ = gl::createVertexArray("scene");
    vbo_ = gl::createBuffer("scene vertices");
    ibo_ = gl::createBuffer("scene indices");
    if (!vertices.empty()) {
        glNamedBufferStorage(vbo_.id(), vertices.size() * sizeof(Vertex), vertices.data(), 0);
        glNamedBufferStorage(ibo_.id(), indices.size() * sizeof(uint32_t), indices.data(), 0);
    }
    const GLuint v = vao_.id();
    glVertexArrayVertexBuffer(v, 0, vbo_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(v, ibo_.id());
    const GLuint offsets[4] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv), offsetof(Vertex, tangent)};
    const GLint sizes[4] = {3, 3, 2, 4};
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(v, a);
        glVertexArrayAttribFormat(v, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(v, a, 0);
    }
    // Textures: sRGB colour or linear data (normal, metallic-roughness, occlusion) with trilinear mipmaps.
    for (const auto& t : scene.textures) {
        if (t.image < 0 || t.image >= (int)scene.images.size() || scene.images[t.image].rgba8.empty()) {
            textures_.emplace_back();
            continue;
        }
        const Image& img = scene.images[t.image];
        auto tex = gl::createTexture(GL_TEXTURE_2D, img.name);
        const int levels = 1 + int(std::log2(double(std::max(img.width, img.height))));
        glTextureStorage2D(tex.id(), levels, t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(tex.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba8.data());
        glGenerateTextureMipmap(tex.id());
        glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_S, glWrap(t.wrapS));
        glTextureParameteri(tex.id(), GL_TEXTURE_WRAP_T, glWrap(t.wrapT));
        glTextureParameteri(tex.id(), GL_TEXTURE_MAG_FILTER, t.magFilter == FilterMode::Nearest ? GL_NEAREST : GL_LINEAR);
        glTextureParameteri(tex.id(), GL_TEXTURE_MIN_FILTER, t.mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        textures_.push_back(std::move(tex));
    }
}

void SceneGpu::draw(GLuint program, bool masked, bool cullBackFaces) const {
    glBindVertexArray(vao_.id());
    const GLint locBase = glGetUniformLocation(program, "uBaseColor");
    const GLint locEmissive = glGetUniformLocation(program, "uEmissive");
    const GLint locHasBase = glGetUniformLocation(program, "uHasBaseTex");
    const GLint locHasEm = glGetUniformLocation(program, "uHasEmissiveTex");
    const GLint locCutoff = glGetUniformLocation(program, "uAlphaCutoff");
    const GLint locPbr = glGetUniformLocation(program, "uMetalRoughF0");
    const GLint locNormalOcc = glGetUniformLocation(program, "uNormalScaleOcclusion");
    const GLint locHasPbr = glGetUniformLocation(program, "uHasPbrTex");
    static const Material kDefault{};
    for (const auto& b : batches_) {
        const Material& m = (b.material >= 0 && b.material < (int)materials_.size()) ? materials_[b.material] : kDefault;
        if (m.masked() != masked) continue;
        auto texOf = [&](int i) -> GLuint { return (i >= 0 && i < (int)textures_.size()) ? textures_[i].id() : 0; };
        const GLuint baseTex = texOf(m.baseColorTexture), emTex = texOf(m.emissiveTexture);
        glProgramUniform4fv(program, locBase, 1, &m.baseColorFactor.x);
        glProgramUniform3fv(program, locEmissive, 1, &m.emissiveFactor.x);
        glProgramUniform1i(program, locHasBase, baseTex != 0);
        glProgramUniform1i(program, locHasEm, emTex != 0);
        glProgramUniform1f(program, locCutoff, m.alphaCutoff);
        glBindTextureUnit(0, baseTex);
        glBindTextureUnit(1, emTex);
        // Metallic-roughness, normal and occlusion (material.glsl): units 2..4, -1 locations ignored by GL.
        const GLuint mrTex = texOf(m.metallicRoughnessTexture), nTex = texOf(m.normalTexture), oTex = texOf(m.occlusionTexture);
        const glm::vec4 pbr(m.metallic, m.roughness, m.dielectricF0, m.specular() ? 1.0f : 0.0f);
        const glm::vec2 normalOcc(m.normalScale, m.occlusionStrength);
        glProgramUniform4fv(program, locPbr, 1, &pbr.x);
        glProgramUniform2fv(program, locNormalOcc, 1, &normalOcc.x);
        glProgramUniform3i(program, locHasPbr, mrTex != 0, nTex != 0, oTex != 0);
        glBindTextureUnit(2, mrTex);
        glBindTextureUnit(3, nTex);
        glBindTextureUnit(4, oTex);
        if (cullBackFaces && !m.doubleSided) glEnable(GL_CULL_FACE);
        else glDisable(GL_CULL_FACE);
        glDrawElements(GL_TRIANGLES, GLsizei(b.indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(uintptr_t(b.firstIndex) * sizeof(uint32_t)));
    }
    glDisable(GL_CULL_FACE);
}

}  // namespace deepgi
