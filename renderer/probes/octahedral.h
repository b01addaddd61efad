#pragma once
// Octahedral mapping of unit directions to [-1,1]^2 (z >= 0 inside the diamond |u|+|v| <= 1), mirrored in
// shaders/probe_volume.glsl. The square's edges fold onto themselves mirrored, which the atlas borders copy.
#include <glm/glm.hpp>

#include <cmath>

namespace deepgi::octahedral {

inline float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

inline glm::vec2 encode(const glm::vec3& d) {
    const float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    glm::vec2 p(d.x / l1, d.y / l1);
    if (d.z < 0.0f) p = glm::vec2((1.0f - std::abs(p.y)) * signNotZero(p.x), (1.0f - std::abs(p.x)) * signNotZero(p.y));
    return p;
}

inline glm::vec3 decode(const glm::vec2& p) {
    glm::vec3 v(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (v.z < 0.0f) {
        const float x = v.x;
        v.x = (1.0f - std::abs(v.y)) * signNotZero(x);
        v.y = (1.0f - std::abs(x)) * signNotZero(v.y);
    }
    return glm::normalize(v);
}

// The direction at the centre of interior texel (i, j) of an n x n map.
inline glm::vec3 texelDirection(int i, int j, int n) {
    return decode(glm::vec2((float(i) + 0.5f) / float(n) * 2.0f - 1.0f, (float(j) + 0.5f) / float(n) * 2.0f - 1.0f));
}

}  // namespace deepgi::octahedral
