// glTF loader, the raw JSON before tinygltf sees it. tinygltf 2.7 stores every index in an `int` through
// static_cast<int>(int64_t), so 4294967296 becomes 0 and later range checks pass; it fails on Draco primitives or a
// bad data URI with messages that name neither (or quote 4 MB of base64); and it allocates every buffer before the
// loader can count it. Those are caught here, on nlohmann's parse of the same bytes, naming the JSON path.
#include "renderer/scene/gltf_reader.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <set>

namespace deepgi {
namespace gltf {
namespace {

using json = nlohmann::json;

// Keys whose value tinygltf parses into an int (ParseIntegerProperty / ParseIntegerArrayProperty).
const std::set<std::string>& intKeys() {
    static const std::set<std::string> keys = {
        "bufferView", "buffer", "source", "sampler", "index", "texCoord", "material", "indices", "mode",
        "skin", "camera", "mesh", "children", "node", "input", "output", "nodes", "joints", "skeleton",
        "inverseBindMatrices", "scene", "width", "height", "target", "minFilter", "magFilter", "wrapS", "wrapT"};
    return keys;
}

std::string describe(const json& v) {
    std::string s = v.dump();
    return printable(s, 40);
}

// Checks one value that tinygltf will read as an int: an integer in [0, INT_MAX] (every such field of glTF is a
// non-negative index or enum). Arrays (children, nodes, joints) are checked element by element.
void checkIntValue(const json& v, const std::string& where, std::string& problem) {
    if (!problem.empty()) return;
    if (v.is_array()) {
        for (size_t i = 0; i < v.size() && problem.empty(); ++i)
            checkIntValue(v[i], where + "[" + std::to_string(i) + "]", problem);
        return;
    }
    if (!v.is_number()) return;  // wrong types are tinygltf's to report
    if (v.is_number_float()) {
        problem = where + " = " + describe(v) + " is not an integer";
    } else if (v.is_number_unsigned() ? v.get<uint64_t>() > uint64_t(INT_MAX)
                                      : (v.get<int64_t>() < 0 || v.get<int64_t>() > INT_MAX)) {
        problem = where + " = " + describe(v) + " is out of range (0 to " + std::to_string(INT_MAX) + ")";
    }
}

// Walks the document, skipping extras and extensions (free-form), checking every int-parsed field.
void walk(const json& node, const std::string& where, const std::string& parentKey, std::string& problem) {
    if (!problem.empty()) return;
    if (node.is_object()) {
        for (auto it = node.begin(); it != node.end() && problem.empty(); ++it) {
            const std::string& key = it.key();
            if (key == "extras" || key == "extensions") continue;
            const std::string here = where.empty() ? key : where + "." + key;
            // attributes/targets map names to accessor indices; a sparse accessor's count and offsets are ints too
            if (intKeys().count(key) || parentKey == "attributes" || parentKey == "targets" ||
                (parentKey == "sparse" && key == "count") ||
                ((parentKey == "indices" || parentKey == "values") && key == "byteOffset") ||
                (parentKey == "indices" && key == "componentType"))
                checkIntValue(it.value(), here, problem);
            if (it.value().is_structured()) walk(it.value(), here, key, problem);
        }
    } else if (node.is_array()) {
        for (size_t i = 0; i < node.size() && problem.empty(); ++i)
            if (node[i].is_structured()) walk(node[i], where + "[" + std::to_string(i) + "]", parentKey, problem);
    }
}

// Bytes a base64 payload decodes to (padding counted off), or -1 when it is not plain base64.
int64_t base64DecodedSize(const std::string& payload) {
    size_t n = payload.size(), pad = 0;
    for (char c : payload)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '=')) return -1;
    while (pad < 2 && n > pad && payload[n - 1 - pad] == '=') ++pad;
    if (n % 4 != 0) return -1;
    return int64_t(n / 4 * 3) - int64_t(pad);
}

}  // namespace

std::string GltfReader::checkJson(const unsigned char* p, size_t n, bool binary) {
    json doc = json::parse(p, p + n, nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object()) return "";  // invalid JSON: tinygltf's message says where
    bool rewritten = false;  // the JSON tinygltf gets differs (Draco indices, meshopt fallback buffers)

    // Required extensions first, before tinygltf fails on what it does not know with messages naming neither.
    if (doc.contains("extensionsRequired") && doc["extensionsRequired"].is_array())
        for (const auto& e : doc["extensionsRequired"])
            if (e.is_string() && !supportedExtensions().count(e.get<std::string>()))
                fail("required extension '" + printable(e.get<std::string>()) + "' is not supported");

    std::string problem;
    walk(doc, "", "", problem);
    if (!problem.empty()) fail(problem);

    if (doc.contains("meshes") && doc["meshes"].is_array()) {
        const auto& meshes = doc["meshes"];
        for (size_t m = 0; m < meshes.size(); ++m) {
            if (!meshes[m].is_object() || !meshes[m].contains("primitives") || !meshes[m]["primitives"].is_array())
                continue;
            const auto& prims = meshes[m]["primitives"];
            for (size_t i = 0; i < prims.size(); ++i) {
                const std::string where = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(i) + "]";
                if (!prims[i].is_object()) continue;
                if (prims[i].contains("extensions") && prims[i]["extensions"].is_object() &&
                    prims[i]["extensions"].contains("KHR_draco_mesh_compression")) {
                    // tinygltf 2.7 refuses the index accessor of a Draco primitive (it has no bufferView): it is
                    // kept here and put back once decodeDraco() has given it one.
                    if (prims[i].contains("indices") && prims[i]["indices"].is_number_integer()) {
                        dracoIndices_[{int(m), int(i)}] = prims[i]["indices"].get<int>();
                        doc["meshes"][m]["primitives"][i].erase("indices");
                        rewritten = true;
                    }
                    continue;
                }
                // tinygltf refuses an index accessor without bufferView (valid glTF: all zeros) as "invalid bufferView"
                if (prims[i].contains("indices") && prims[i]["indices"].is_number_integer() &&
                    doc.contains("accessors") && doc["accessors"].is_array()) {
                    const auto ai = prims[i]["indices"].get<int64_t>();
                    const auto& accs = doc["accessors"];
                    if (ai >= 0 && size_t(ai) < accs.size() && accs[size_t(ai)].is_object() &&
                        !accs[size_t(ai)].contains("bufferView"))
                        fail(where + ": index accessor " + std::to_string(ai) +
                             " has no bufferView (all-zero indices are not supported)");
                }
            }
        }
    }

    if (doc.contains("buffers") && doc["buffers"].is_array()) {
        const auto& buffers = doc["buffers"];
        for (size_t b = 0; b < buffers.size(); ++b) {
            const auto& buf = buffers[b];
            if (!buf.is_object()) continue;
            const std::string where = "buffer " + std::to_string(b);
            const bool meshoptFallback = buf.contains("extensions") && buf["extensions"].is_object() &&
                                         buf["extensions"].contains("EXT_meshopt_compression") &&
                                         buf["extensions"]["EXT_meshopt_compression"].is_object() &&
                                         buf["extensions"]["EXT_meshopt_compression"].value("fallback", false);
            if (meshoptFallback && !buf.contains("uri")) {
                // A placeholder with no data (EXT_meshopt_compression): every view into it is decoded by
                // decodeMeshopt() into a buffer of its own. tinygltf gets one byte instead of a missing URI.
                doc["buffers"][b] = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
                meshoptFallbacks_.insert(int(b));
                rewritten = true;
                continue;
            }
            if (!buf.contains("uri")) {
                if (!binary || b > 0)
                    fail(where + " has no uri (only the first buffer of a .glb may omit it: it is the BIN chunk)");
            } else if (buf["uri"].is_string()) {
                const std::string uri = buf["uri"].get<std::string>();
                for (unsigned char c : uri)
                    if (c < 0x20 || c == 0x7f)
                        fail(where + ": URI '" + printable(uri) + "' contains a control character");
                if (uri.compare(0, 5, "data:") == 0 && buf.contains("byteLength") &&
                    buf["byteLength"].is_number_unsigned()) {
                    const size_t comma = uri.find(',');
                    const bool base64 = comma != std::string::npos && comma >= 7 &&
                                        uri.compare(comma - 7, 7, ";base64") == 0;
                    const int64_t decoded = base64 ? base64DecodedSize(uri.substr(comma + 1)) : -1;
                    if (decoded < 0)
                        fail(where + ": data URI is not base64 ('" + printable(uri, 48) + "')");
                    const uint64_t byteLength = buf["byteLength"].get<uint64_t>();
                    if (uint64_t(decoded) != byteLength)
                        fail(where + ": data URI holds " + std::to_string(decoded) + " bytes but byteLength says " +
                             std::to_string(byteLength));
                }
            }
            // tinygltf allocates every buffer before the loader sees it: count them against the budget first.
            if (buf.contains("byteLength") && buf["byteLength"].is_number_unsigned())
                reserveMemory(buf["byteLength"].get<uint64_t>(), where + " (byteLength)", true);
        }
    }
    // (invalid UTF-8 in a name is replaced, not a reason to refuse the file)
    return rewritten ? doc.dump(-1, ' ', false, json::error_handler_t::replace) : std::string();
}

}  // namespace gltf
}  // namespace deepgi
