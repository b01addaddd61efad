#include "renderer/scene/procedural.h"

#include <glm/gtc/matrix_transform.hpp>

namespace deepgi::procedural {

int addMaterial(Scene& s, const glm::vec3& albedo, const glm::vec3& emission, bool doubleSided) {
    Material m;
    m.name = "material" + std::to_string(s.materials.size());
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.emissiveFactor = emission;
    m.doubleSided = doubleSided;
    s.materials.push_back(m);
    return int(s.materials.size()) - 1;
}

namespace {
// One quad part drawn by `node` (its own new node when -1).
void addQuadTo(Scene& s, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3, int material, int node) {
    MeshPart part;
    part.name = "quad" + std::to_string(s.parts.size());
    part.material = material;
    const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    const glm::vec3 ps[4] = {p0, p1, p2, p3};
    const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (int i = 0; i < 4; ++i) part.vertices.push_back({ps[i], n, uvs[i]});
    part.indices = {0, 1, 2, 0, 2, 3};
    part.node = node >= 0 ? node : s.addNode(part.name);
    part.restWorld = s.nodes[size_t(part.node)].world;
    s.nodes[size_t(part.node)].parts.push_back(int(s.parts.size()));
    s.parts.push_back(std::move(part));
    s.computeBounds();
}
}  // namespace

void addQuad(Scene& s, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3, int material) {
    addQuadTo(s, p0, p1, p2, p3, material, -1);
}

void addBox(Scene& s, const glm::vec3& lo, const glm::vec3& hi, int material, bool inward) {
    auto P = [&](int x, int y, int z) { return glm::vec3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z); };
    // Outward CCW quads per face.
    const glm::vec3 q[6][4] = {
        {P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)},  // +X
        {P(0, 0, 1), P(0, 1, 1), P(0, 1, 0), P(0, 0, 0)},  // -X
        {P(0, 1, 0), P(0, 1, 1), P(1, 1, 1), P(1, 1, 0)},  // +Y
        {P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)},  // -Y
        {P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)},  // +Z
        {P(1, 0, 0), P(0, 0, 0), P(0, 1, 0), P(1, 1, 0)},  // -Z
    };
    const int node = s.addNode("box" + std::to_string(s.nodes.size()));  // one object: six quads
    for (const auto& f : q) {
        if (inward) addQuadTo(s, f[3], f[2], f[1], f[0], material, node);
        else addQuadTo(s, f[0], f[1], f[2], f[3], material, node);
    }
}

void addFloor(Scene& s, float h, float y, int material) {
    addQuad(s, {-h, y, h}, {h, y, h}, {h, y, -h}, {-h, y, -h}, material);
}

void addSun(Scene& s, const glm::vec3& direction, float irradiance) {
    Light l;
    l.name = "sun";
    l.type = LightType::Directional;
    l.direction = glm::normalize(direction);
    l.intensity = irradiance;
    s.lights.push_back(l);
    s.ensureNodes();  // a node that turns the sun
}

void addCamera(Scene& s, const std::string& name, const glm::vec3& eye, const glm::vec3& target, float yfovDeg) {
    CameraDesc c;
    c.name = name;
    c.yfov = glm::radians(yfovDeg);
    c.znear = 0.05f;
    const glm::vec3 fwd = glm::normalize(target - eye);
    const glm::vec3 up = std::abs(fwd.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
    s.cameras.push_back(c);
    s.ensureNodes();
}

}  // namespace deepgi::procedural
