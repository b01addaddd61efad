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
    std::vector<uint32_t> objectOfVertex;  // part index per vertex (attribute 7)
    // Group parts by material so each material is one draw of consecutive indices.
    std::map<int, std::vector<const MeshPart*>> byMaterial;
    for (const auto& p : scene.parts)
        if (!p.indices.empty()) byMaterial[p.material].push_back(&p);
    partBounds_.resize(scene.parts.size());
    for (size_t i = 0; i < scene.parts.size(); ++i)
        if (extendByVertices(partBounds_[i], scene.parts[i]) > 0) partBounds_[i] = Aabb{};
    for (const auto& [mat, parts] : byMaterial) {
        Batch b{mat, uint32_t(indices.size()), 0, 0, {}};
        for (const MeshPart* p : parts) {
            const uint32_t base = uint32_t(vertices.size());
            const int partIndex = int(p - scene.parts.data());
            b.parts.push_back({uint32_t(indices.size()), uint32_t(p->indices.size()), partIndex});
            vertices.insert(vertices.end(), p->vertices.begin(), p->vertices.end());
            objectOfVertex.insert(objectOfVertex.end(), p->vertices.size(), uint32_t(partIndex));
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
    // Per-vertex part index, a buffer of its own (binding 1) beside the vertices.
    objectIds_ = gl::createBuffer("scene vertex objects");
    if (!objectOfVertex.empty()) glNamedBufferStorage(objectIds_.id(), objectOfVertex.size() * sizeof(uint32_t), objectOfVertex.data(), 0);
    glVertexArrayVertexBuffer(v, 1, objectIds_.id(), 0, sizeof(uint32_t));
    glEnableVertexArrayAttrib(v, kObjectAttribute);
    glVertexArrayAttribIFormat(v, kObjectAttribute, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(v, kObjectAttribute, 1);
    objectSsbo_ = gl::createBuffer("scene objects");
    updateObjects(scene);
    lastFrame_ = current_;

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

std::vector<std::string> SceneGpu::materialTextureDefines(unsigned textures) {
    std::vector<std::string> defs;
    if (textures & kBaseTex) defs.push_back("BASE_TEX");
    if (textures & kEmissiveTex) defs.push_back("EMISSIVE_TEX");
    if (textures & kMetalRoughTex) defs.push_back("METAL_ROUGH_TEX");
    if (textures & kNormalTex) defs.push_back("NORMAL_TEX");
    if (textures & kOcclusionTex) defs.push_back("OCCLUSION_TEX");
    return defs;
}

void SceneGpu::draw(const ProgramFor& programFor, bool masked, bool cullBackFaces, int instances, bool viewCulled) const {
    const std::vector<char>& drawn = viewCulled ? inView_ : visible_;
    const bool allDrawn = viewCulled ? allInView_ : allVisible_;
    glBindVertexArray(vao_.id());
    GLuint program = 0;
    unsigned programTextures = ~0u;
    GLint locBase = -1, locEmissive = -1, locCutoff = -1, locPbr = -1, locNormalOcc = -1;
    static const Material kDefault{};
    for (const auto& b : batches_) {
        if (!allDrawn && std::none_of(b.parts.begin(), b.parts.end(), [&](const Range& r) { return drawn[size_t(r.part)]; }))
            continue;  // nothing of it drawn: no program or texture changes either
        const Material& m = (b.material >= 0 && b.material < (int)materials_.size()) ? materials_[b.material] : kDefault;
        if (m.masked() != masked) continue;
        auto texOf = [&](int i) -> GLuint { return (i >= 0 && i < (int)textures_.size()) ? textures_[i].id() : 0; };
        const GLuint baseTex = texOf(m.baseColorTexture), emTex = texOf(m.emissiveTexture);
        // Metallic-roughness, normal and occlusion (material.glsl): units 2..4.
        const GLuint mrTex = texOf(m.metallicRoughnessTexture), nTex = texOf(m.normalTexture), oTex = texOf(m.occlusionTexture);
        const unsigned textures = (baseTex ? kBaseTex : 0u) | (emTex ? kEmissiveTex : 0u) | (mrTex ? kMetalRoughTex : 0u) |
                                  (nTex ? kNormalTex : 0u) | (oTex ? kOcclusionTex : 0u);
        if (textures != programTextures) {
            programTextures = textures;
            program = programFor(textures);
            // A variant may leave a uniform out (-1 locations are ignored by GL).
            locBase = glGetUniformLocation(program, "uBaseColor");
            locEmissive = glGetUniformLocation(program, "uEmissive");
            locCutoff = glGetUniformLocation(program, "uAlphaCutoff");
            locPbr = glGetUniformLocation(program, "uMetalRoughF0");
            locNormalOcc = glGetUniformLocation(program, "uNormalScaleOcclusion");
        }
        glProgramUniform4fv(program, locBase, 1, &m.baseColorFactor.x);
        glProgramUniform3fv(program, locEmissive, 1, &m.emissiveFactor.x);
        glProgramUniform1f(program, locCutoff, m.alphaCutoff);
        glBindTextureUnit(0, baseTex);
        glBindTextureUnit(1, emTex);
        const glm::vec4 pbr(m.metallic, m.roughness, m.dielectricF0, m.specular() ? 1.0f : 0.0f);
        const glm::vec2 normalOcc(m.normalScale, m.occlusionStrength);
        glProgramUniform4fv(program, locPbr, 1, &pbr.x);
        glProgramUniform2fv(program, locNormalOcc, 1, &normalOcc.x);
        glBindTextureUnit(2, mrTex);
        glBindTextureUnit(3, nTex);
        glBindTextureUnit(4, oTex);
        if (cullBackFaces && !m.doubleSided) glEnable(GL_CULL_FACE);
        else glDisable(GL_CULL_FACE);
        drawBatch(b, instances, drawn, allDrawn);
    }
    glDisable(GL_CULL_FACE);
}

// ---- Objects: model matrices and visibility ----

namespace {
// std430 mirror of SceneObject in shaders/scene_objects.glsl.
struct SceneObjectStd430 {
    glm::mat4 model, prevModel;
    glm::mat4 normalMatrix;  // inverse transpose of the upper 3x3, in the first three columns
    glm::uvec4 id;           // x = node index + 1 (0 = none)
};
}  // namespace

uint64_t SceneGpu::geometryBytes(const Scene& scene) {
    uint64_t bytes = uint64_t(std::max<size_t>(scene.parts.size(), 1)) * sizeof(SceneObjectStd430);
    for (const auto& p : scene.parts)
        if (!p.indices.empty()) bytes += p.vertices.size() * (sizeof(Vertex) + sizeof(uint32_t)) + p.indices.size() * sizeof(uint32_t);
    return bytes;
}

void SceneGpu::drawBatch(const Batch& b, int instances, const std::vector<char>& drawn, bool allDrawn) const {
    if (allDrawn) {
        glDrawElementsInstanced(GL_TRIANGLES, GLsizei(b.indexCount), GL_UNSIGNED_INT,
                                reinterpret_cast<const void*>(uintptr_t(b.firstIndex) * sizeof(uint32_t)), instances);
        return;
    }
    // Visible parts only, consecutive ones merged into one range.
    std::vector<GLsizei> counts;
    std::vector<const void*> offsets;
    uint32_t start = 0, count = 0;
    auto flush = [&] {
        if (count == 0) return;
        counts.push_back(GLsizei(count));
        offsets.push_back(reinterpret_cast<const void*>(uintptr_t(start) * sizeof(uint32_t)));
        count = 0;
    };
    for (const Range& r : b.parts) {
        if (!drawn[size_t(r.part)]) { flush(); continue; }
        if (count == 0) start = r.firstIndex;
        count += r.indexCount;
    }
    flush();
    if (instances == 1) {
        if (!counts.empty()) glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(), GLsizei(counts.size()));
        return;
    }
    for (size_t i = 0; i < counts.size(); ++i) glDrawElementsInstanced(GL_TRIANGLES, counts[i], GL_UNSIGNED_INT, offsets[i], instances);
}

void SceneGpu::updateObjects(const Scene& scene) {
    const size_t n = scene.parts.size();
    std::vector<glm::mat4> models(n);
    std::vector<char> visible(n);
    for (size_t i = 0; i < n; ++i) {
        models[i] = scene.partModel(int(i));
        visible[i] = scene.partVisible(int(i));
    }
    if (models != current_ || visible != visible_) ++version_;
    current_ = std::move(models);
    visible_ = std::move(visible);
    allVisible_ = std::find(visible_.begin(), visible_.end(), 0) == visible_.end();
    inView_ = visible_;  // until the next cullToView()
    allInView_ = allVisible_;
    if (lastFrame_.size() != n) lastFrame_ = current_;
    nodeOfPart_.resize(n);
    for (size_t i = 0; i < n; ++i) nodeOfPart_[i] = scene.parts[i].node;
    objectsDirty_ = true;
}

int SceneGpu::cullToView(const glm::mat4* viewProj) {
    inView_ = visible_;
    allInView_ = allVisible_;
    if (!viewProj) return 0;
    int culled = 0;
    for (size_t i = 0; i < inView_.size() && i < partBounds_.size(); ++i) {
        const Aabb& b = partBounds_[i];
        if (!inView_[i] || !b.valid()) continue;
        // The clip planes are linear in the corners: a box whose 8 corners are all beyond one is clipped whole,
        // whatever the signs of w. A NaN compares false and keeps the part.
        const glm::mat4 m = *viewProj * current_[i];
        unsigned beyondAll = 63u;
        for (int c = 0; c < 8 && beyondAll; ++c) {
            const glm::vec4 q = m * glm::vec4(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z, 1.0f);
            beyondAll &= unsigned(q.x < -q.w) | unsigned(q.x > q.w) << 1 | unsigned(q.y < -q.w) << 2 |
                         unsigned(q.y > q.w) << 3 | unsigned(q.z < -q.w) << 4 | unsigned(q.z > q.w) << 5;
        }
        if (beyondAll) {
            inView_[i] = 0;
            allInView_ = false;
            ++culled;
        }
    }
    return culled;
}

void SceneGpu::beginFrame(bool historyValid) {
    const std::vector<glm::mat4>& prev = historyValid ? lastFrame_ : current_;
    if (objectsDirty_ || prev != uploadedPrev_) {
        std::vector<SceneObjectStd430> objs(std::max<size_t>(current_.size(), 1));
        for (size_t i = 0; i < current_.size(); ++i) {
            SceneObjectStd430& o = objs[i];
            o.model = current_[i];
            o.prevModel = prev[i];
            const glm::mat3 m3(current_[i]);
            // Cofactor matrix (inverse transpose up to a positive scale, sign-corrected): finite for singular scales.
            glm::mat3 nm(glm::cross(m3[1], m3[2]), glm::cross(m3[2], m3[0]), glm::cross(m3[0], m3[1]));
            if (glm::determinant(m3) < 0.0f) nm = -nm;
            o.normalMatrix = glm::mat4(nm);
            o.id = glm::uvec4(uint32_t(nodeOfPart_[i] + 1), 0u, 0u, 0u);
        }
        const GLsizeiptr bytes = GLsizeiptr(objs.size() * sizeof(SceneObjectStd430));
        if (bytes != objectBytes_) {
            glNamedBufferData(objectSsbo_.id(), bytes, objs.data(), GL_DYNAMIC_DRAW);
            objectBytes_ = bytes;
        } else {
            glNamedBufferSubData(objectSsbo_.id(), 0, bytes, objs.data());
        }
        uploadedPrev_ = prev;
        objectsDirty_ = false;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBinding, objectSsbo_.id());
}

}  // namespace deepgi
