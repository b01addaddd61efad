#pragma once
// Decoding of the G-buffer's stored forms on the CPU, the inverses of shaders/common.glsl's encodings (one place
// for the renderer's read-back and the inspector's readout).
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

// Distance along the view axis from a [0,1] depth-buffer value (common.glsl eyeDepth).
inline float linearDepth(float d, float znear, float zfar, bool perspective) {
    if (!perspective) return znear + d * (zfar - znear);
    return 2.0f * znear * zfar / std::max(zfar + znear - (d * 2.0f - 1.0f) * (zfar - znear), 1e-30f);
}

// Unit vector from its octahedral encoding in [-1,1]^2 (common.glsl octDecode).
inline glm::vec3 octDecode(float x, float y) {
    glm::vec3 v(x, y, 1.0f - std::abs(x) - std::abs(y));
    if (v.z < 0.0f) {
        const float vx = (1.0f - std::abs(v.y)) * (v.x >= 0.0f ? 1.0f : -1.0f);
        v.y = (1.0f - std::abs(v.x)) * (v.y >= 0.0f ? 1.0f : -1.0f);
        v.x = vx;
    }
    const float l = glm::length(v);
    return l > 0.0f ? v / l : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace deepgi
