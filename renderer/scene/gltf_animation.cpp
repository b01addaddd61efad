// glTF loader, animations: TRS channels of the nodes in the scene, kept as keyframes (animation.h samples them).
// Skins and morph targets are not animated: one warning each.
#include "renderer/scene/gltf_reader.h"

#include <cmath>

namespace deepgi {
namespace gltf {

void GltfReader::loadAnimations() {
    if (!model_.skins.empty())
        warn("the file has " + std::to_string(model_.skins.size()) + " skin(s): skinning is not supported, meshes stay in their bind pose");
    bool morph = false;
    for (const auto& m : model_.meshes)
        for (const auto& p : m.primitives) morph = morph || !p.targets.empty();
    for (const auto& a : model_.animations)
        for (const auto& c : a.channels) morph = morph || c.target_path == "weights";
    if (morph) warn("the file has morph targets: they are not supported (base shapes drawn, weight animations ignored)");

    for (size_t ai = 0; ai < model_.animations.size(); ++ai) {
        const auto& ga = model_.animations[ai];
        Animation anim;
        anim.name = ga.name.empty() ? "animation[" + std::to_string(ai) + "]" : ga.name;
        for (size_t ci = 0; ci < ga.channels.size(); ++ci) {
            const auto& gc = ga.channels[ci];
            const std::string what = "animation '" + anim.name + "' channel " + std::to_string(ci);
            if (gc.target_path == "weights") continue;  // warned above
            AnimationChannel ch;
            if (gc.target_path == "translation") ch.path = AnimationPath::Translation;
            else if (gc.target_path == "rotation") ch.path = AnimationPath::Rotation;
            else if (gc.target_path == "scale") ch.path = AnimationPath::Scale;
            else { warn(what + ": unknown target path '" + gc.target_path + "', skipped"); continue; }
            if (gc.target_node < 0 || size_t(gc.target_node) >= model_.nodes.size()) { warn(what + ": target node out of range, skipped"); continue; }
            ch.node = sceneNodeOf_.empty() ? -1 : sceneNodeOf_[size_t(gc.target_node)];
            if (ch.node < 0) continue;  // a node outside the displayed scene
            if (gc.sampler < 0 || size_t(gc.sampler) >= ga.samplers.size()) { warn(what + ": sampler out of range, skipped"); continue; }
            const auto& gs = ga.samplers[size_t(gc.sampler)];
            if (gs.interpolation == "STEP") ch.interpolation = Interpolation::Step;
            else if (gs.interpolation == "CUBICSPLINE") ch.interpolation = Interpolation::CubicSpline;
            else if (gs.interpolation.empty() || gs.interpolation == "LINEAR") ch.interpolation = Interpolation::Linear;
            else { warn(what + ": unknown interpolation '" + gs.interpolation + "', skipped"); continue; }
            try {
                ch.times = readFloats(gs.input, TINYGLTF_TYPE_SCALAR, {kCompFloat}, false, true, what + " input");
                const bool rot = ch.path == AnimationPath::Rotation;
                if (rot)
                    ch.values = readFloats(gs.output, TINYGLTF_TYPE_VEC4, {kCompFloat, kCompByte, kCompUByte, kCompShort, kCompUShort},
                                           true, true, what + " output");
                else
                    ch.values = readFloats(gs.output, TINYGLTF_TYPE_VEC3, {kCompFloat}, false, true, what + " output");
                const size_t per = (rot ? 4 : 3) * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
                if (ch.times.empty() || ch.values.size() != ch.times.size() * per) {
                    warn(what + ": " + std::to_string(ch.times.size()) + " key times but " + std::to_string(ch.values.size() / (rot ? 4 : 3)) +
                         " output values (need " + std::to_string(per / (rot ? 4 : 3)) + " per key), skipped");
                    continue;
                }
                bool ok = true;
                for (size_t k = 0; k < ch.times.size(); ++k)
                    ok = ok && std::isfinite(ch.times[k]) && (k == 0 || ch.times[k] > ch.times[k - 1]);
                for (float v : ch.values) ok = ok && std::isfinite(v);
                if (!ok) { warn(what + ": key times not strictly increasing or values not finite, skipped"); continue; }
            } catch (const SceneLoadError& e) {
                warn(std::string(e.what()) + " (channel skipped)");
                continue;
            }
            anim.channels.push_back(std::move(ch));
        }
        if (!anim.channels.empty()) scene_.animations.push_back(std::move(anim));
    }
}

}  // namespace gltf
}  // namespace deepgi
