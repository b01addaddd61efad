#include "renderer/scene/tangents.h"

#include <cmath>
#include <vector>

namespace deepgi {

void generateTangents(MeshPart& part) {
    const size_t nv = part.vertices.size();
    std::vector<glm::vec3> sumT(nv, glm::vec3(0.0f)), sumB(nv, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < part.indices.size(); t += 3) {
        const uint32_t i0 = part.indices[t], i1 = part.indices[t + 1], i2 = part.indices[t + 2];
        if (i0 >= nv || i1 >= nv || i2 >= nv) continue;
        const Vertex &a = part.vertices[i0], &b = part.vertices[i1], &c = part.vertices[i2];
        const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        const glm::vec2 d1 = b.uv - a.uv, d2 = c.uv - a.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) continue;
        // dP/du and dP/dv scaled by the triangle's UV area sign and |det| (area weighting of the sums).
        const float s = det > 0.0f ? 1.0f : -1.0f;
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) * s, dPdv = (e2 * d1.x - e1 * d2.x) * s;
        for (uint32_t i : {i0, i1, i2}) {
            sumT[i] += dPdu;
            sumB[i] += dPdv;
        }
    }
    for (size_t i = 0; i < nv; ++i) {
        Vertex& v = part.vertices[i];
        const glm::vec3 n = v.normal;
        glm::vec3 t = sumT[i] - n * glm::dot(n, sumT[i]);
        float len = glm::length(t);
        if (!(len > 1e-20f) || !std::isfinite(len)) {
            // Any perpendicular: the normal map then tilts in an arbitrary but consistent direction.
            t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
            len = glm::length(t);
            if (!(len > 1e-20f)) t = glm::vec3(1, 0, 0), len = 1.0f;
        }
        t /= len;
        const float w = glm::dot(glm::cross(n, t), -sumB[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangent = glm::vec4(t, w);
    }
}

}  // namespace deepgi
