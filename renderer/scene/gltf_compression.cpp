// glTF loader, compressed geometry: EXT_meshopt_compression buffer views (Debian's libmeshoptimizer) and
// KHR_draco_mesh_compression primitives (Debian's libdraco). Both are decoded right after parsing into plain buffers
// appended to the model, and the views/accessors are pointed at them, so everything after (range checks, accessor
// reading, quantized types) is the code path of an uncompressed file.
#include "renderer/scene/gltf_reader.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>

namespace deepgi {
namespace gltf {
namespace {

int typeComponentsOf(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;
    }
}

// A non-negative integer member of an extension object, or `fallback` when absent; -1 when present but invalid.
int64_t intMember(const tinygltf::Value& o, const char* key, int64_t fallback) {
    if (!o.Has(key)) return fallback;
    const tinygltf::Value& v = o.Get(key);
    if (!v.IsNumber()) return -1;
    const double d = v.GetNumberAsDouble();
    if (!(d >= 0.0 && d <= 9.0e15) || d != std::floor(d)) return -1;
    return int64_t(d);
}

std::string stringMember(const tinygltf::Value& o, const char* key, const std::string& fallback) {
    if (!o.Has(key) || !o.Get(key).IsString()) return fallback;
    return o.Get(key).Get<std::string>();
}

}  // namespace

int GltfReader::appendBuffer(std::vector<unsigned char>&& bytes, size_t byteStride) {
    tinygltf::Buffer b;
    b.name = "decoded";
    b.data = std::move(bytes);
    model_.buffers.push_back(std::move(b));
    tinygltf::BufferView v;
    v.buffer = int(model_.buffers.size()) - 1;
    v.byteOffset = 0;
    v.byteLength = model_.buffers.back().data.size();
    v.byteStride = byteStride;
    model_.bufferViews.push_back(v);
    return int(model_.bufferViews.size()) - 1;
}

void GltfReader::decodeMeshopt() {
    for (size_t vi = 0; vi < model_.bufferViews.size(); ++vi) {
        auto it = model_.bufferViews[vi].extensions.find("EXT_meshopt_compression");
        if (it == model_.bufferViews[vi].extensions.end()) {
            if (meshoptFallbacks_.count(model_.bufferViews[vi].buffer))
                fail("buffer view " + std::to_string(vi) + " points into the EXT_meshopt_compression placeholder buffer " +
                     std::to_string(model_.bufferViews[vi].buffer) + " without being compressed");
            continue;
        }
        const std::string what = "buffer view " + std::to_string(vi) + " (EXT_meshopt_compression)";
        const tinygltf::Value& e = it->second;
        if (!e.IsObject()) fail(what + ": the extension is not an object");
        const int64_t buffer = intMember(e, "buffer", -1), offset = intMember(e, "byteOffset", 0),
                      length = intMember(e, "byteLength", -1), stride = intMember(e, "byteStride", -1),
                      count = intMember(e, "count", -1);
        const std::string mode = stringMember(e, "mode", ""), filter = stringMember(e, "filter", "NONE");
        if (buffer < 0 || size_t(buffer) >= model_.buffers.size() || meshoptFallbacks_.count(int(buffer)))
            fail(what + ": buffer " + std::to_string(buffer) + " is missing or is a placeholder");
        const auto& src = model_.buffers[size_t(buffer)].data;
        if (offset < 0 || length < 0 || uint64_t(offset) > src.size() || uint64_t(length) > src.size() - uint64_t(offset))
            fail(what + ": byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                 " out of range of buffer " + std::to_string(buffer) + " (" + std::to_string(src.size()) + " bytes)");
        if (count < 0 || stride <= 0) fail(what + ": count and byteStride must be given");
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0 || stride > 256) fail(what + ": ATTRIBUTES byteStride " + std::to_string(stride) + " is not a multiple of 4 up to 256");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) fail(what + ": " + mode + " byteStride must be 2 or 4, not " + std::to_string(stride));
            if (mode == "TRIANGLES" && count % 3 != 0) fail(what + ": TRIANGLES count " + std::to_string(count) + " is not a multiple of 3");
        } else {
            fail(what + ": unknown mode '" + printable(mode) + "'");
        }
        if (uint64_t(count) > opt_.maxElements) fail(what + ": count " + std::to_string(count) + " is past the element limit");
        const uint64_t bytes = uint64_t(count) * uint64_t(stride);
        reserveMemory(bytes, what + " decoded", true);
        std::vector<unsigned char> out(static_cast<size_t>(bytes));
        const unsigned char* in = src.data() + offset;
        int rc = 0;
        if (mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(out.data(), size_t(count), size_t(stride), in, size_t(length));
        else if (mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(out.data(), size_t(count), size_t(stride), in, size_t(length));
        else rc = meshopt_decodeIndexSequence(out.data(), size_t(count), size_t(stride), in, size_t(length));
        if (rc != 0) fail(what + ": meshopt decoding failed (error " + std::to_string(rc) + ": corrupt or truncated data)");
        if (filter == "OCTAHEDRAL") {
            if (mode != "ATTRIBUTES" || (stride != 4 && stride != 8)) fail(what + ": OCTAHEDRAL filter needs ATTRIBUTES with byteStride 4 or 8");
            meshopt_decodeFilterOct(out.data(), size_t(count), size_t(stride));
        } else if (filter == "QUATERNION") {
            if (mode != "ATTRIBUTES" || stride != 8) fail(what + ": QUATERNION filter needs ATTRIBUTES with byteStride 8");
            meshopt_decodeFilterQuat(out.data(), size_t(count), size_t(stride));
        } else if (filter == "EXPONENTIAL") {
            if (mode != "ATTRIBUTES") fail(what + ": EXPONENTIAL filter needs ATTRIBUTES");
            meshopt_decodeFilterExp(out.data(), size_t(count), size_t(stride));
        } else if (filter != "NONE") {
            fail(what + ": unknown filter '" + printable(filter) + "'");
        }
        const int decoded = appendBuffer(std::move(out), mode == "ATTRIBUTES" ? size_t(stride) : 0);
        // The view keeps its index (accessors refer to it) and now reads the decoded bytes.
        tinygltf::BufferView& view = model_.bufferViews[vi];
        const tinygltf::BufferView& fresh = model_.bufferViews[size_t(decoded)];
        view.buffer = fresh.buffer;
        view.byteOffset = 0;
        view.byteLength = fresh.byteLength;
        view.byteStride = fresh.byteStride;
        view.extensions.erase("EXT_meshopt_compression");
    }
}

void GltfReader::decodeDraco() {
    for (size_t mi = 0; mi < model_.meshes.size(); ++mi) {
        for (size_t pi = 0; pi < model_.meshes[mi].primitives.size(); ++pi) {
            tinygltf::Primitive& prim = model_.meshes[mi].primitives[pi];
            auto it = prim.extensions.find("KHR_draco_mesh_compression");
            if (it == prim.extensions.end()) continue;
            const std::string meshName = model_.meshes[mi].name.empty() ? "mesh" + std::to_string(mi) : model_.meshes[mi].name;
            const std::string what = "mesh '" + meshName + "/" + std::to_string(pi) + "' (KHR_draco_mesh_compression)";
            const tinygltf::Value& e = it->second;
            if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject())
                fail(what + ": the extension has no attributes object");
            const int64_t bv = intMember(e, "bufferView", -1);
            if (bv < 0 || size_t(bv) >= model_.bufferViews.size()) fail(what + ": bufferView " + std::to_string(bv) + " out of range");
            const size_t length = model_.bufferViews[size_t(bv)].byteLength;
            if (length == 0) fail(what + ": empty buffer view");
            const Span s = viewSpan(int(bv), 0, 1, length, false, what);

            // What the decoded primitive will hold, from the accessors, counted before decoding.
            auto idxIt = dracoIndices_.find({int(mi), int(pi)});
            uint64_t expected = 0;
            for (const auto& [name, ai] : prim.attributes)
                if (ai >= 0 && size_t(ai) < model_.accessors.size())
                    expected += uint64_t(model_.accessors[size_t(ai)].count) * 16;
            if (idxIt != dracoIndices_.end() && idxIt->second >= 0 && size_t(idxIt->second) < model_.accessors.size())
                expected += uint64_t(model_.accessors[size_t(idxIt->second)].count) * 4;
            reserveMemory(2 * expected, what + " decoding", false);

            draco::DecoderBuffer buffer;
            buffer.Init(reinterpret_cast<const char*>(s.base), length);
            draco::Decoder decoder;
            auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
            if (!decoded.ok()) fail(what + ": Draco decoding failed: " + decoded.status().error_msg_string());
            const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
            if (!mesh) fail(what + ": Draco decoding gave no mesh");
            const size_t points = mesh->num_points(), faces = mesh->num_faces();
            if (points > opt_.maxElements || faces * 3 > opt_.maxElements)
                fail(what + ": " + std::to_string(points) + " points and " + std::to_string(faces) + " faces are past the element limit");

            const tinygltf::Value& attrs = e.Get("attributes");
            for (auto& [name, ai] : prim.attributes) {
                if (!attrs.Has(name)) continue;  // not compressed: read from its own buffer view
                const int64_t id = intMember(attrs, name.c_str(), -1);
                const draco::PointAttribute* pa = id < 0 ? nullptr : mesh->GetAttributeByUniqueId(uint32_t(id));
                if (!pa) fail(what + ": attribute " + name + " (Draco id " + std::to_string(id) + ") is not in the compressed data");
                if (ai < 0 || size_t(ai) >= model_.accessors.size()) fail(what + ": " + name + " accessor out of range");
                tinygltf::Accessor acc = model_.accessors[size_t(ai)];
                const int comps = typeComponentsOf(acc.type);
                if (comps == 0 || pa->num_components() < comps)
                    fail(what + ": attribute " + name + " has " + std::to_string(int(pa->num_components())) +
                         " components, its accessor wants " + std::to_string(comps));
                reserveMemory(uint64_t(points) * uint64_t(comps) * 4, what + " " + name, true);
                std::vector<unsigned char> bytes(points * size_t(comps) * 4);
                std::vector<float> value(static_cast<size_t>(comps));
                for (size_t p = 0; p < points; ++p) {
                    if (!pa->ConvertValue<float>(pa->mapped_index(draco::PointIndex(uint32_t(p))), int8_t(comps), value.data()))
                        fail(what + ": attribute " + name + " could not be converted to float");
                    std::memcpy(bytes.data() + p * size_t(comps) * 4, value.data(), size_t(comps) * 4);
                }
                // A fresh accessor per primitive: an accessor shared with another primitive keeps its own data.
                acc.bufferView = appendBuffer(std::move(bytes), 0);
                acc.byteOffset = 0;
                acc.componentType = kCompFloat;
                acc.normalized = false;
                acc.count = points;
                acc.sparse = tinygltf::Accessor().sparse;
                model_.accessors.push_back(acc);
                ai = int(model_.accessors.size()) - 1;
            }
            reserveMemory(uint64_t(faces) * 12, what + " indices", true);
            std::vector<unsigned char> bytes(faces * 12);
            for (size_t f = 0; f < faces; ++f) {
                const auto& face = mesh->face(draco::FaceIndex(uint32_t(f)));
                for (int k = 0; k < 3; ++k) {
                    const uint32_t v = face[k].value();
                    std::memcpy(bytes.data() + (f * 3 + size_t(k)) * 4, &v, 4);
                }
            }
            tinygltf::Accessor idx;
            if (idxIt != dracoIndices_.end() && idxIt->second >= 0 && size_t(idxIt->second) < model_.accessors.size())
                idx = model_.accessors[size_t(idxIt->second)];
            idx.bufferView = appendBuffer(std::move(bytes), 0);
            idx.byteOffset = 0;
            idx.componentType = kCompUInt;
            idx.normalized = false;
            idx.type = TINYGLTF_TYPE_SCALAR;
            idx.count = faces * 3;
            idx.sparse = tinygltf::Accessor().sparse;
            model_.accessors.push_back(idx);
            prim.indices = int(model_.accessors.size()) - 1;
            prim.extensions.erase(it);
        }
    }
}

}  // namespace gltf
}  // namespace deepgi
