// glTF loader, geometry: buffers, buffer views, accessors (sparse included) and mesh primitives. Every offset,
// stride and count is range-checked before anything is read, because tinygltf 2.7 trusts them.
#include "renderer/scene/gltf_reader.h"

#include <algorithm>
#include <cstring>

namespace deepgi {
namespace gltf {
namespace {

const char* componentTypeName(int t) {
    switch (t) {
        case kCompByte: return "byte";
        case kCompUByte: return "unsigned byte";
        case kCompShort: return "short";
        case kCompUShort: return "unsigned short";
        case kCompUInt: return "unsigned int";
        case kCompFloat: return "float";
        default: return "unknown";
    }
}

size_t componentSize(int t) {
    switch (t) {
        case kCompByte: case kCompUByte: return 1;
        case kCompShort: case kCompUShort: return 2;
        case kCompUInt: case kCompFloat: return 4;
        default: return 0;
    }
}

int typeComponents(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

double readComponent(const unsigned char* p, int type, bool normalized) {
    switch (type) {
        case kCompFloat: { float f; std::memcpy(&f, p, 4); return f; }
        case kCompUByte: return normalized ? p[0] / 255.0 : double(p[0]);
        case kCompByte: {
            int8_t v; std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : double(v);
        }
        case kCompUShort: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : double(v); }
        case kCompShort: {
            int16_t v; std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : double(v);
        }
        case kCompUInt: { uint32_t v; std::memcpy(&v, p, 4); return double(v); }
        default: return 0.0;
    }
}

uint32_t readIndex(const unsigned char* p, int type) {
    switch (type) {
        case kCompUByte: return p[0];
        case kCompUShort: { uint16_t v; std::memcpy(&v, p, 2); return v; }
        default: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    }
}

glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    return (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

// Locates `count` elements of `elemSize` bytes in a buffer view, with every range checked.
GltfReader::Span GltfReader::viewSpan(int viewIndex, size_t byteOffset, size_t count, size_t elemSize, bool allowStride,
              const std::string& what) const {
    if (viewIndex < 0 || size_t(viewIndex) >= model_.bufferViews.size())
        fail(what + ": buffer view " + std::to_string(viewIndex) + " out of range");
    const auto& view = model_.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        fail(what + ": buffer " + std::to_string(view.buffer) + " out of range");
    const auto& buf = model_.buffers[size_t(view.buffer)];
    if (view.byteOffset > buf.data.size() || view.byteLength > buf.data.size() - view.byteOffset)
        fail(what + ": buffer view " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) +
             ", length " + std::to_string(view.byteLength) + ") out of range of its buffer (" +
             std::to_string(buf.data.size()) + " bytes)");
    if (byteOffset > view.byteLength)
        fail(what + ": byte offset " + std::to_string(byteOffset) + " out of range of buffer view " +
             std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) + " bytes)");
    size_t stride = elemSize;
    if (allowStride && view.byteStride != 0) {
        if (view.byteStride < elemSize || view.byteStride > 252)
            fail(what + ": invalid byte stride " + std::to_string(view.byteStride));
        stride = view.byteStride;
    }
    if (count > 0) {
        // needed = byteOffset + (count-1)*stride + elemSize, overflow-checked
        unsigned long long span = 0, needed = 0;
        if (__builtin_mul_overflow((unsigned long long)(count - 1), (unsigned long long)stride, &span) ||
            __builtin_add_overflow(span, (unsigned long long)elemSize, &span) ||
            __builtin_add_overflow(span, (unsigned long long)byteOffset, &needed) || needed > view.byteLength)
            fail(what + ": " + std::to_string(count) + " elements out of range of buffer view " +
                 std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) + " bytes)");
    }
    Span s;
    s.base = buf.data.data() + view.byteOffset + byteOffset;
    s.stride = stride;
    return s;
}


const tinygltf::Accessor& GltfReader::accessor(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(what + ": accessor " + std::to_string(index) + " out of range");
    return model_.accessors[size_t(index)];
}

void GltfReader::reserveElements(size_t count, const std::string& what) {
    if (count > opt_.maxElements || elements_ + count > opt_.maxElements)
        fail(what + ": element count " + std::to_string(count) + " overflows the limit of " +
             std::to_string(opt_.maxElements) + " vertices + indices per file, every mesh instance counted");
    elements_ += count;
}

// Applies the sparse substitution of `acc` to `out` (numComp values per element), through `write`.
template <class Write>
void GltfReader::applySparse(const tinygltf::Accessor& acc, const std::string& what, size_t elemSize, Write write) {
    if (!acc.sparse.isSparse) return;
    if (acc.sparse.count < 0 || size_t(acc.sparse.count) > acc.count)
        fail(what + ": sparse count " + std::to_string(acc.sparse.count) + " out of range");
    const size_t n = size_t(acc.sparse.count);
    const int itype = acc.sparse.indices.componentType;
    if (itype != kCompUByte && itype != kCompUShort && itype != kCompUInt)
        fail(what + ": sparse indices have invalid component type " + std::to_string(itype));
    if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
        fail(what + ": negative sparse byte offset");
    Span is = viewSpan(acc.sparse.indices.bufferView, size_t(acc.sparse.indices.byteOffset), n,
                       componentSize(itype), false, what + " (sparse indices)");
    Span vs = viewSpan(acc.sparse.values.bufferView, size_t(acc.sparse.values.byteOffset), n, elemSize, false,
                       what + " (sparse values)");
    for (size_t i = 0; i < n; ++i) {
        uint32_t target = readIndex(is.base + i * is.stride, itype);
        if (target >= acc.count)
            fail(what + ": sparse index " + std::to_string(target) + " out of range (count " +
                 std::to_string(acc.count) + ")");
        write(size_t(target), vs.base + i * vs.stride);
    }
}

// Range check of an accessor that has a buffer view, without reading it (types are checked when it is read).
void GltfReader::checkAccessorFits(int index, const std::string& what) const {
    const auto& acc = accessor(index, what);
    const size_t elemSize = componentSize(acc.componentType) * size_t(typeComponents(acc.type));
    if (acc.bufferView < 0 || elemSize == 0) return;
    viewSpan(acc.bufferView, acc.byteOffset, acc.count, elemSize, true, what + " (accessor " + std::to_string(index) + ")");
}

// Reads a float attribute with `numComp` components (VEC2/VEC3). Allowed component types listed in `allowed`.
std::vector<float> GltfReader::readFloats(int index, int expectedType, std::initializer_list<int> allowed,
                              bool requireNormalizedInts, bool countTowardsLimit, const std::string& what) {
    const auto& acc = accessor(index, what);
    const int numComp = typeComponents(expectedType);
    if (acc.type != expectedType)
        fail(what + ": accessor " + std::to_string(index) + " has the wrong type (expected " +
             std::to_string(numComp) + " components)");
    if (std::find(allowed.begin(), allowed.end(), acc.componentType) == allowed.end() ||
        (requireNormalizedInts && acc.componentType != kCompFloat && !acc.normalized))
        fail(what + ": accessor " + std::to_string(index) + " has unsupported component type " +
             componentTypeName(acc.componentType) + (acc.normalized ? " (normalized)" : "") +
             (quantized_ || acc.componentType == kCompFloat ? "" : " (integer attributes need KHR_mesh_quantization in extensionsUsed)"));
    if (countTowardsLimit) reserveElements(acc.count, what);
    else if (acc.count > opt_.maxElements) reserveElements(acc.count, what);  // fails
    const size_t csize = componentSize(acc.componentType);
    const size_t elemSize = csize * size_t(numComp);
    Span s;
    if (acc.bufferView >= 0)  // range check before allocating anything
        s = viewSpan(acc.bufferView, acc.byteOffset, acc.count, elemSize, true,
                     what + " (accessor " + std::to_string(index) + ")");
    std::vector<float> out(acc.count * size_t(numComp), 0.0f);
    auto writeElem = [&](size_t i, const unsigned char* p) {
        for (int c = 0; c < numComp; ++c)
            out[i * size_t(numComp) + size_t(c)] =
                float(readComponent(p + size_t(c) * csize, acc.componentType, acc.normalized));
    };
    if (acc.bufferView >= 0) {
        for (size_t i = 0; i < acc.count; ++i) writeElem(i, s.base + i * s.stride);
    } else if (!acc.sparse.isSparse) {
        warn(what + ": accessor " + std::to_string(index) + " has no data; using zeros");
    }
    applySparse(acc, what, elemSize, writeElem);
    return out;
}

std::vector<uint32_t> GltfReader::readIndices(int index, const std::string& what) {
    const auto& acc = accessor(index, what);
    if (acc.type != TINYGLTF_TYPE_SCALAR)
        fail(what + ": index accessor " + std::to_string(index) + " is not SCALAR");
    const int ct = acc.componentType;
    if (ct != kCompUByte && ct != kCompUShort && ct != kCompUInt)
        fail(what + ": index accessor " + std::to_string(index) + " has unsupported component type " +
             componentTypeName(ct));
    reserveElements(acc.count, what);
    const size_t csize = componentSize(ct);
    Span s;
    if (acc.bufferView >= 0)
        s = viewSpan(acc.bufferView, acc.byteOffset, acc.count, csize, true,
                     what + " (accessor " + std::to_string(index) + ")");
    std::vector<uint32_t> out(acc.count, 0u);
    auto writeElem = [&](size_t i, const unsigned char* p) { out[i] = readIndex(p, ct); };
    if (acc.bufferView >= 0) {
        for (size_t i = 0; i < acc.count; ++i) writeElem(i, s.base + i * s.stride);
    }
    applySparse(acc, what, csize, writeElem);
    return out;
}

// ---- meshes ----

// Upper bound of the bytes addMesh holds for one primitive: the attributes and indices read, the world-space copy,
// the triangle list and the output (every corner its own vertex at worst). Saturates instead of overflowing.
uint64_t GltfReader::primitiveBytesBound(const tinygltf::Primitive& prim, int mode) const {
    auto countOf = [&](const char* attr) -> double {
        auto it = prim.attributes.find(attr);
        if (it == prim.attributes.end() || it->second < 0 || size_t(it->second) >= model_.accessors.size()) return 0.0;
        return double(model_.accessors[size_t(it->second)].count);
    };
    const double nv = countOf("POSITION");
    const double ni = (prim.indices >= 0 && size_t(prim.indices) < model_.accessors.size())
                          ? double(model_.accessors[size_t(prim.indices)].count) : nv;
    const double corners = mode == TINYGLTF_MODE_TRIANGLES ? ni : 3.0 * std::max(ni - 2.0, 0.0);
    const double bytes = nv * 12.0 + countOf("NORMAL") * 12.0 + std::max(countOf("TEXCOORD_0"), countOf("TEXCOORD_1")) * 8.0 + ni * 4.0 +
                         corners * 4.0 + nv * (double(sizeof(Vertex)) + 1.0 + 8.0) +
                         corners * (double(sizeof(Vertex)) + 4.0);
    return bytes >= 1.8e19 ? UINT64_MAX : uint64_t(bytes);
}

void GltfReader::addMesh(int meshIndex, const glm::mat4& world) {
    if (size_t(meshIndex) >= model_.meshes.size()) fail("mesh " + std::to_string(meshIndex) + " out of range");
    const auto& mesh = model_.meshes[size_t(meshIndex)];
    const std::string meshName = mesh.name.empty() ? "mesh" + std::to_string(meshIndex) : mesh.name;
    const glm::mat3 m3(world);
    const float det = glm::determinant(m3);
    // Inverse-transpose up to a positive scale: the cofactor matrix, sign-corrected by the determinant.
    glm::mat3 normalMat(glm::cross(m3[1], m3[2]), glm::cross(m3[2], m3[0]), glm::cross(m3[0], m3[1]));
    if (det < 0.0f) normalMat = -normalMat;
    const bool flip = det < 0.0f;
    if (meshInstances_.size() < model_.meshes.size()) meshInstances_.resize(model_.meshes.size(), 0);
    struct CountInstance {  // counted once per placement of the mesh, whatever its primitives do
        std::vector<uint32_t>& n; size_t i;
        ~CountInstance() { if (i < n.size()) ++n[i]; }
    } countInstance{meshInstances_, size_t(meshIndex)};

    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const auto& prim = mesh.primitives[pi];
        const std::string name = meshName + "/" + std::to_string(pi);
        const std::string what = "mesh '" + name + "'";
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            warn(what + ": primitive mode " + std::to_string(mode) + " is not triangles, skipped");
            continue;
        }
        auto posIt = prim.attributes.find("POSITION");
        if (posIt == prim.attributes.end()) {
            warn(what + ": primitive has no POSITION, skipped");
            continue;
        }
        // Memory for this instance, counted before anything is allocated (the accessor without bufferView that
        // is "all zeros" has a count bounded by no file size; a mesh placed 10000 times is copied 10000 times).
        // Accessors inside the file are range-checked first: their error ("out of range of buffer view") is the
        // more precise one, and only data-less accessors can claim more than the file holds.
        // The UV set the material's textures read (KHR_texture_transform may pick another), transformed at load.
        const UvSet uvSet = prim.material >= 0 && size_t(prim.material) < materialUv_.size()
                                ? materialUv_[size_t(prim.material)] : UvSet{};
        const std::string uvName = "TEXCOORD_" + std::to_string(uvSet.texCoord);
        for (const auto& [attr, index] : prim.attributes)
            if (attr == "POSITION" || attr == "NORMAL" || attr == uvName) checkAccessorFits(index, what + " " + attr);
        if (prim.indices >= 0) checkAccessorFits(prim.indices, what + " indices");
        const uint64_t transientBytes = primitiveBytesBound(prim, mode);
        const std::string instance = what + " (instance " + std::to_string(meshInstances_[size_t(meshIndex)] + 1) +
                                     " of mesh " + std::to_string(meshIndex) + ")";
        reserveMemory(transientBytes, instance, false);
        // KHR_mesh_quantization: integer positions (the node transform dequantizes), normalized integer normals,
        // integer texture coordinates normalized or not (a KHR_texture_transform usually rescales them).
        const std::initializer_list<int> quantTypes = {kCompFloat, kCompByte, kCompUByte, kCompShort, kCompUShort};
        const std::initializer_list<int> floatOnly = {kCompFloat};
        const std::initializer_list<int> normalTypes = {kCompFloat, kCompByte, kCompShort};
        const std::initializer_list<int> uvTypes = {kCompFloat, kCompUByte, kCompUShort};
        std::vector<float> pos = readFloats(posIt->second, TINYGLTF_TYPE_VEC3, quantized_ ? quantTypes : floatOnly,
                                            false, true, what + " POSITION");
        const size_t nv = pos.size() / 3;
        std::vector<float> nrm, uv;
        auto nIt = prim.attributes.find("NORMAL");
        if (nIt != prim.attributes.end()) {
            nrm = readFloats(nIt->second, TINYGLTF_TYPE_VEC3, quantized_ ? normalTypes : floatOnly, true, false,
                             what + " NORMAL");
            if (nrm.size() != pos.size()) fail(what + ": NORMAL count differs from POSITION count");
        }
        auto tIt = prim.attributes.find(uvName);
        if (tIt != prim.attributes.end()) {
            uv = readFloats(tIt->second, TINYGLTF_TYPE_VEC2, quantized_ ? quantTypes : uvTypes, !quantized_,
                            false, what + " " + uvName);
            if (uv.size() / 2 != nv) fail(what + ": " + uvName + " count differs from POSITION count");
        } else if (uvSet.texCoord != 0) {
            warn(what + ": its material's textures read " + uvName + ", which the primitive lacks; using (0, 0)");
        }

        std::vector<uint32_t> idx;
        if (prim.indices >= 0) {
            idx = readIndices(prim.indices, what + " indices");
            for (uint32_t i : idx)
                if (i >= nv)
                    fail(what + ": index " + std::to_string(i) + " out of range (vertex count " +
                         std::to_string(nv) + ")");
        } else {
            if (nv > UINT32_MAX) fail(what + ": too many vertices");
            idx.resize(nv);
            for (size_t i = 0; i < nv; ++i) idx[i] = uint32_t(i);
        }

        // Triangle list in source winding.
        std::vector<uint32_t> tris;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (idx.size() % 3 != 0) warn(what + ": index count not a multiple of 3, trailing indices ignored");
            tris.assign(idx.begin(), idx.begin() + std::ptrdiff_t(idx.size() / 3 * 3));
        } else if (idx.size() >= 3) {
            tris.reserve((idx.size() - 2) * 3);
            for (size_t i = 0; i + 2 < idx.size(); ++i) {
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                    if (i % 2 == 0) tris.insert(tris.end(), {idx[i], idx[i + 1], idx[i + 2]});
                    else tris.insert(tris.end(), {idx[i + 1], idx[i], idx[i + 2]});
                } else {
                    tris.insert(tris.end(), {idx[i + 1], idx[i + 2], idx[0]});
                }
            }
        }
        if (tris.empty()) continue;

        MeshPart part;
        part.name = name;
        part.node = currentNode_;
        if (prim.material >= 0 && size_t(prim.material) >= scene_.materials.size())
            warn(what + ": material " + std::to_string(prim.material) + " does not exist; using the default");
        else
            part.material = prim.material;

        // World-space vertices.
        std::vector<Vertex> verts(nv);
        std::vector<char> badNormal(nv, 0);
        for (size_t i = 0; i < nv; ++i) {
            Vertex& v = verts[i];
            v.position = glm::vec3(world * glm::vec4(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2], 1.0f));
            v.uv = uv.empty() ? glm::vec2(0.0f) : glm::vec2(uvSet.transform * glm::vec3(uv[i * 2], uv[i * 2 + 1], 1.0f));
            if (!finite3(glm::vec3(v.uv, 0.0f))) v.uv = glm::vec2(0.0f);
            if (nrm.empty()) {
                badNormal[i] = 1;
                continue;
            }
            glm::vec3 n = normalMat * glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
            const float len = glm::length(n);
            if (len > 1e-20f && std::isfinite(len)) v.normal = n / len;
            else badNormal[i] = 1;
        }

        // Emit triangles: skip non-finite ones, flip winding for mirroring transforms, give vertices without a
        // usable normal a per-triangle copy carrying the flat face normal.
        std::vector<int64_t> remap(nv, -1);
        uint64_t skipped = 0;
        for (size_t t = 0; t + 2 < tris.size(); t += 3) {
            uint32_t tri[3] = {tris[t], tris[t + 1], tris[t + 2]};
            if (flip) std::swap(tri[1], tri[2]);
            const glm::vec3 &a = verts[tri[0]].position, &b = verts[tri[1]].position, &c = verts[tri[2]].position;
            if (!finite3(a) || !finite3(b) || !finite3(c)) {
                ++skipped;
                continue;
            }
            const glm::vec3 fn = faceNormal(a, b, c);
            for (uint32_t k : tri) {
                if (badNormal[k]) {
                    Vertex v = verts[k];
                    v.normal = fn;
                    part.indices.push_back(uint32_t(part.vertices.size()));
                    part.vertices.push_back(v);
                } else {
                    if (remap[k] < 0) {
                        remap[k] = int64_t(part.vertices.size());
                        part.vertices.push_back(verts[k]);
                    }
                    part.indices.push_back(uint32_t(remap[k]));
                }
            }
        }
        skippedNonFinite_ += skipped;
        if (part.indices.empty()) continue;
        reserveMemory(part.vertices.size() * sizeof(Vertex) + part.indices.size() * sizeof(uint32_t), instance, true);
        scene_.parts.push_back(std::move(part));
    }
}

}  // namespace gltf
}  // namespace deepgi
