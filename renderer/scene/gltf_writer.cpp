#include "renderer/scene/gltf_writer.h"

#include <tiny_gltf.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace deepgi {
namespace {

class Writer {
public:
    explicit Writer(const Scene& s) : s_(s) { m_.buffers.emplace_back(); }

    tinygltf::Model build() {
        m_.asset.version = "2.0";
        m_.asset.generator = "deepgi";
        writeImages();
        writeMaterials();
        writeCameras();
        writeLights();
        writeNodes();
        writeAnimations();
        tinygltf::Scene scene;
        for (int r : roots_) scene.nodes.push_back(r);
        m_.scenes.push_back(scene);
        m_.defaultScene = 0;
        if (m_.buffers[0].data.empty()) m_.buffers.clear();
        return std::move(m_);
    }

private:
    const Scene& s_;
    tinygltf::Model m_;
    std::vector<int> roots_;
    std::vector<int> extraLightNodes_;  // lights without a node get one of their own (glTF places lights by nodes)
    bool usedLights_ = false, usedEmissiveStrength_ = false, usedVisibility_ = false;

    void align4() {
        auto& d = m_.buffers[0].data;
        while (d.size() % 4) d.push_back(0);
    }
    int addView(const void* data, size_t bytes, int target) {
        align4();
        auto& d = m_.buffers[0].data;
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = d.size();
        v.byteLength = bytes;
        v.target = target;
        const auto* p = static_cast<const unsigned char*>(data);
        d.insert(d.end(), p, p + bytes);
        m_.bufferViews.push_back(v);
        return int(m_.bufferViews.size()) - 1;
    }
    int addAccessor(const std::vector<float>& v, int type, int comps, int target, bool minMax) {
        tinygltf::Accessor a;
        a.bufferView = addView(v.data(), v.size() * sizeof(float), target);
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.type = type;
        a.count = v.size() / size_t(comps);
        if (minMax && a.count > 0) {  // required for POSITION and animation inputs
            a.minValues.assign(size_t(comps), 1e300);
            a.maxValues.assign(size_t(comps), -1e300);
            for (size_t i = 0; i < a.count; ++i)
                for (int c = 0; c < comps; ++c) {
                    a.minValues[size_t(c)] = std::min(a.minValues[size_t(c)], double(v[i * size_t(comps) + size_t(c)]));
                    a.maxValues[size_t(c)] = std::max(a.maxValues[size_t(c)], double(v[i * size_t(comps) + size_t(c)]));
                }
        }
        m_.accessors.push_back(a);
        return int(m_.accessors.size()) - 1;
    }

    void writeImages() {
        for (const Image& img : s_.images) {
            tinygltf::Image gi;
            gi.name = img.name;
            std::vector<unsigned char> png;
            if (img.width > 0 && img.height > 0 && img.rgba8.size() >= size_t(img.width) * img.height * 4) {
                auto sink = [](void* ctx, void* data, int size) {
                    auto* out = static_cast<std::vector<unsigned char>*>(ctx);
                    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
                };
                if (!stbi_write_png_to_func(sink, &png, img.width, img.height, 4, img.rgba8.data(), img.width * 4))
                    throw std::runtime_error("image '" + img.name + "': PNG encoding failed");
            } else {
                // An image that failed to decode at load: a 1x1 white stand-in keeps the texture indices valid.
                const unsigned char white[4] = {255, 255, 255, 255};
                auto sink = [](void* ctx, void* data, int size) {
                    auto* out = static_cast<std::vector<unsigned char>*>(ctx);
                    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
                };
                stbi_write_png_to_func(sink, &png, 1, 1, 4, white, 4);
            }
            gi.bufferView = addView(png.data(), png.size(), 0);
            gi.mimeType = "image/png";
            m_.images.push_back(gi);
        }
        for (const Texture& t : s_.textures) {
            tinygltf::Sampler smp;
            auto wrap = [](WrapMode w) {
                return w == WrapMode::ClampToEdge ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
                       : w == WrapMode::MirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT : TINYGLTF_TEXTURE_WRAP_REPEAT;
            };
            smp.wrapS = wrap(t.wrapS);
            smp.wrapT = wrap(t.wrapT);
            smp.magFilter = t.magFilter == FilterMode::Nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
            smp.minFilter = t.mipmaps ? TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR : TINYGLTF_TEXTURE_FILTER_LINEAR;
            m_.samplers.push_back(smp);
            tinygltf::Texture gt;
            gt.sampler = int(m_.samplers.size()) - 1;
            gt.source = (t.image >= 0 && t.image < int(s_.images.size())) ? t.image : -1;
            m_.textures.push_back(gt);
        }
    }

    void writeMaterials() {
        for (const Material& mat : s_.materials) {
            tinygltf::Material gm;
            gm.name = mat.name;
            gm.pbrMetallicRoughness.baseColorFactor = {mat.baseColorFactor.x, mat.baseColorFactor.y, mat.baseColorFactor.z, mat.baseColorFactor.w};
            gm.pbrMetallicRoughness.baseColorTexture.index = mat.baseColorTexture;
            gm.pbrMetallicRoughness.metallicFactor = 0.0;  // deepgi shades Lambertian: a rough dielectric elsewhere too
            gm.pbrMetallicRoughness.roughnessFactor = 1.0;
            // emissiveFactor is limited to [0, 1]: the rest goes into KHR_materials_emissive_strength.
            const float peak = std::max({mat.emissiveFactor.x, mat.emissiveFactor.y, mat.emissiveFactor.z});
            const float strength = peak > 1.0f ? peak : 1.0f;
            gm.emissiveFactor = {mat.emissiveFactor.x / strength, mat.emissiveFactor.y / strength, mat.emissiveFactor.z / strength};
            if (strength > 1.0f) {
                tinygltf::Value::Object o;
                o["emissiveStrength"] = tinygltf::Value(double(strength));
                gm.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(o);
                usedEmissiveStrength_ = true;
            }
            gm.emissiveTexture.index = mat.emissiveTexture;
            gm.alphaMode = mat.alphaMode == AlphaMode::Opaque ? "OPAQUE" : mat.alphaMode == AlphaMode::Mask ? "MASK" : "BLEND";
            gm.alphaCutoff = mat.alphaCutoff;
            gm.doubleSided = mat.doubleSided;
            m_.materials.push_back(gm);
        }
    }

    void writeCameras() {
        for (const CameraDesc& c : s_.cameras) {
            tinygltf::Camera gc;
            gc.name = c.name;
            if (c.perspective) {
                gc.type = "perspective";
                gc.perspective.yfov = c.yfov;
                gc.perspective.aspectRatio = c.aspectRatio;
                gc.perspective.znear = c.znear;
                gc.perspective.zfar = c.zfar;
            } else {
                gc.type = "orthographic";
                gc.orthographic.xmag = c.xmag;
                gc.orthographic.ymag = c.ymag;
                gc.orthographic.znear = c.znear;
                gc.orthographic.zfar = c.zfar > c.znear ? c.zfar : c.znear + 1e6;  // required in glTF
            }
            m_.cameras.push_back(gc);
        }
    }

    void writeLights() {
        for (const Light& l : s_.lights) {
            tinygltf::Light gl;
            gl.name = l.name;
            gl.type = l.type == LightType::Directional ? "directional" : l.type == LightType::Point ? "point" : "spot";
            gl.color = {l.color.x, l.color.y, l.color.z};
            gl.intensity = l.intensity;
            gl.range = l.range;
            if (l.type == LightType::Spot) {
                gl.spot.innerConeAngle = l.innerConeAngle;
                gl.spot.outerConeAngle = l.outerConeAngle;
            }
            m_.lights.push_back(gl);
            usedLights_ = true;
        }
    }

    // One glTF mesh of the node's parts, vertices back in the node's local space (the inverse of the placement
    // they were loaded with).
    int writeMesh(const SceneNode& n) {
        tinygltf::Mesh mesh;
        mesh.name = n.name;
        for (int pi : n.parts) {
            const MeshPart& p = s_.parts[size_t(pi)];
            if (p.indices.empty() || p.vertices.empty()) continue;
            const glm::mat4 toLocal = glm::inverse(p.restWorld);
            const glm::mat3 nrm = glm::transpose(glm::mat3(p.restWorld));  // inverse transpose of toLocal's 3x3
            const bool mirrored = glm::determinant(glm::mat3(p.restWorld)) < 0.0f;
            std::vector<float> pos, normal, uv;
            for (const Vertex& v : p.vertices) {
                const glm::vec3 q = glm::vec3(toLocal * glm::vec4(v.position, 1.0f));
                glm::vec3 nn = nrm * v.normal;
                const float len = glm::length(nn);
                nn = (len > 1e-20f && std::isfinite(len)) ? nn / len : glm::vec3(0.0f, 0.0f, 1.0f);
                pos.insert(pos.end(), {q.x, q.y, q.z});
                normal.insert(normal.end(), {nn.x, nn.y, nn.z});
                uv.insert(uv.end(), {v.uv.x, v.uv.y});
            }
            std::vector<uint32_t> idx = p.indices;
            if (mirrored)  // the loader flips mirrored placements' winding; flip back so it does again
                for (size_t t = 0; t + 2 < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            prim.material = p.material;
            prim.attributes["POSITION"] = addAccessor(pos, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
            prim.attributes["NORMAL"] = addAccessor(normal, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            prim.attributes["TEXCOORD_0"] = addAccessor(uv, TINYGLTF_TYPE_VEC2, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
            tinygltf::Accessor ia;
            ia.bufferView = addView(idx.data(), idx.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
            ia.type = TINYGLTF_TYPE_SCALAR;
            ia.count = idx.size();
            m_.accessors.push_back(ia);
            prim.indices = int(m_.accessors.size()) - 1;
            mesh.primitives.push_back(prim);
        }
        if (mesh.primitives.empty()) return -1;
        m_.meshes.push_back(mesh);
        return int(m_.meshes.size()) - 1;
    }

    static void setTrs(tinygltf::Node& g, const Transform& t) {
        g.translation = {t.translation.x, t.translation.y, t.translation.z};
        g.rotation = {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w};
        g.scale = {t.scale.x, t.scale.y, t.scale.z};
    }
    static tinygltf::Value lightRef(int i) {
        tinygltf::Value::Object o;
        o["light"] = tinygltf::Value(i);
        return tinygltf::Value(o);
    }

    void writeNodes() {
        // Scene node i = glTF node i; lights without a node get extra root nodes after them.
        for (const SceneNode& n : s_.nodes) {
            tinygltf::Node g;
            g.name = n.name;
            setTrs(g, n.local);
            for (int c : n.children) g.children.push_back(c);
            g.mesh = writeMesh(n);
            g.camera = n.camera;
            if (n.light >= 0) g.extensions["KHR_lights_punctual"] = lightRef(n.light);
            if (!n.visible) {
                tinygltf::Value::Object o;
                o["visible"] = tinygltf::Value(false);
                g.extensions["KHR_node_visibility"] = tinygltf::Value(o);
                usedVisibility_ = true;
            }
            m_.nodes.push_back(g);
        }
        for (int r : s_.roots) roots_.push_back(r);
        for (size_t i = 0; i < s_.lights.size(); ++i) {
            const Light& l = s_.lights[i];
            if (l.node >= 0) continue;
            tinygltf::Node g;
            g.name = l.name;
            Transform t;
            t.translation = l.position;
            const glm::vec3 a(0.0f, 0.0f, -1.0f), b = glm::normalize(l.direction);
            const float c = glm::dot(a, b);
            const glm::vec3 axis = glm::cross(a, b);
            t.rotation = c < -0.999999f ? glm::quat(0.0f, 1.0f, 0.0f, 0.0f) : glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
            setTrs(g, t);
            g.extensions["KHR_lights_punctual"] = lightRef(int(i));
            m_.nodes.push_back(g);
            roots_.push_back(int(m_.nodes.size()) - 1);
        }
        if (usedLights_) m_.extensionsUsed.push_back("KHR_lights_punctual");
        if (usedEmissiveStrength_) m_.extensionsUsed.push_back("KHR_materials_emissive_strength");
        if (usedVisibility_) m_.extensionsUsed.push_back("KHR_node_visibility");
    }

    void writeAnimations() {
        for (const Animation& a : s_.animations) {
            tinygltf::Animation ga;
            ga.name = a.name;
            for (const AnimationChannel& c : a.channels) {
                if (c.node < 0 || c.node >= int(s_.nodes.size()) || c.times.empty()) continue;
                tinygltf::AnimationSampler smp;
                smp.input = addAccessor(c.times, TINYGLTF_TYPE_SCALAR, 1, 0, true);
                const bool rot = c.path == AnimationPath::Rotation;
                smp.output = addAccessor(c.values, rot ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, rot ? 4 : 3, 0, false);
                smp.interpolation = c.interpolation == Interpolation::Step ? "STEP" : c.interpolation == Interpolation::CubicSpline ? "CUBICSPLINE" : "LINEAR";
                ga.samplers.push_back(smp);
                tinygltf::AnimationChannel ch;
                ch.sampler = int(ga.samplers.size()) - 1;
                ch.target_node = c.node;
                ch.target_path = c.path == AnimationPath::Translation ? "translation" : rot ? "rotation" : "scale";
                ga.channels.push_back(ch);
            }
            if (!ga.channels.empty()) m_.animations.push_back(ga);
        }
    }
};

bool endsWithGlb(const std::string& p) {
    if (p.size() < 4) return false;
    std::string e = p.substr(p.size() - 4);
    for (char& ch : e) ch = char(std::tolower((unsigned char)ch));
    return e == ".glb";
}

}  // namespace

void saveGltf(const Scene& scene, const std::string& path) {
    tinygltf::Model model = Writer(scene).build();
    tinygltf::TinyGLTF io;
    const bool binary = endsWithGlb(path);
    // Buffers: inside the .glb, else a .bin beside the .gltf; images live in buffer views (PNG) either way.
    if (!io.WriteGltfSceneToFile(&model, path, false, false, true, binary))
        throw std::runtime_error(path + ": cannot write the glTF file (folder missing or not writable?)");
}

}  // namespace deepgi
