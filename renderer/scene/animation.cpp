#include "renderer/scene/animation.h"

#include <algorithm>
#include <cmath>

namespace deepgi {
namespace {

int componentsOf(const AnimationChannel& c) { return c.path == AnimationPath::Rotation ? 4 : 3; }

glm::vec4 load(const AnimationChannel& c, size_t key, int slot) {
    // slot: 0 in-tangent, 1 value, 2 out-tangent (CUBICSPLINE); value only otherwise.
    const int n = componentsOf(c);
    const size_t stride = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const size_t base = (key * stride + size_t(c.interpolation == Interpolation::CubicSpline ? slot : 0)) * size_t(n);
    glm::vec4 v(0.0f);
    for (int i = 0; i < n; ++i) v[i] = c.values[base + size_t(i)];
    return v;
}

glm::vec4 normalizeQuat(glm::vec4 q) {
    const float len = glm::length(q);
    return (len > 0.0f && std::isfinite(len)) ? q / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

glm::vec4 slerp(glm::vec4 a, glm::vec4 b, float t) {
    float d = glm::dot(a, b);
    if (d < 0.0f) { b = -b; d = -d; }  // the shorter arc
    if (d > 0.9995f) return normalizeQuat(a + (b - a) * t);  // nearly equal: linear is exact to float precision
    const float theta = std::acos(std::min(d, 1.0f));
    const float s = std::sin(theta);
    return (a * std::sin((1.0f - t) * theta) + b * std::sin(t * theta)) / s;
}

}  // namespace

glm::vec4 sampleChannel(const AnimationChannel& c, float t) {
    const size_t keys = c.times.size();
    const bool rotation = c.path == AnimationPath::Rotation;
    if (keys == 0) return rotation ? glm::vec4(0, 0, 0, 1) : glm::vec4(0.0f);
    auto finish = [&](glm::vec4 v) { return rotation ? normalizeQuat(v) : v; };
    if (!(t > c.times.front())) return finish(load(c, 0, 1));
    if (t >= c.times.back()) return finish(load(c, keys - 1, 1));
    // The key interval [k, k+1] holding t.
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const float t0 = c.times[k], t1 = c.times[k + 1], td = t1 - t0;
    const float u = td > 0.0f ? (t - t0) / td : 0.0f;
    switch (c.interpolation) {
    case Interpolation::Step: return finish(load(c, k, 1));
    case Interpolation::Linear: {
        const glm::vec4 a = load(c, k, 1), b = load(c, k + 1, 1);
        return rotation ? slerp(normalizeQuat(a), normalizeQuat(b), u) : a + (b - a) * u;
    }
    case Interpolation::CubicSpline: {
        // glTF 2.0 Appendix C: Hermite with the tangents scaled by the interval's length.
        const glm::vec4 v0 = load(c, k, 1), b0 = load(c, k, 2), a1 = load(c, k + 1, 0), v1 = load(c, k + 1, 1);
        const float u2 = u * u, u3 = u2 * u;
        const glm::vec4 p = (2 * u3 - 3 * u2 + 1) * v0 + td * (u3 - 2 * u2 + u) * b0 + (-2 * u3 + 3 * u2) * v1 + td * (u3 - u2) * a1;
        return finish(p);
    }
    }
    return finish(load(c, k, 1));
}

void applyAnimation(Scene& scene, float seconds) {
    for (const auto& a : scene.animations)
        for (const auto& c : a.channels) {
            if (c.node < 0 || c.node >= int(scene.nodes.size())) continue;
            const glm::vec4 v = sampleChannel(c, seconds);
            Transform& local = scene.nodes[size_t(c.node)].local;
            if (c.path == AnimationPath::Translation) local.translation = glm::vec3(v);
            else if (c.path == AnimationPath::Scale) local.scale = glm::vec3(v);
            else local.rotation = glm::quat(v.w, v.x, v.y, v.z);
        }
    scene.updateWorldTransforms();
}

}  // namespace deepgi
