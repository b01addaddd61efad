// The scene's node tree: world matrices, the parts' current model matrices, bounds, visibility.
#include "renderer/scene/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>

namespace deepgi {

glm::mat4 Transform::matrix() const {
    // The same products as the glTF loader's node matrix (translate * rotate * scale), so that a node left
    // untouched gets bit for bit the world matrix its vertices were placed with.
    glm::mat4 t = glm::translate(glm::mat4(1.0f), translation);
    glm::mat4 r = glm::mat4_cast(rotation);
    glm::mat4 s = glm::scale(glm::mat4(1.0f), scale);
    return t * r * s;
}

void Scene::computeNodeWorlds() {
    // Iterative walk from the roots (no recursion: deep hierarchies cannot overflow the stack). A node not reached
    // from a root (a broken parent link) is treated as a root.
    std::vector<char> done(nodes.size(), 0);
    std::vector<int> stack;
    auto walk = [&](int root) {
        stack.assign(1, root);
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            if (i < 0 || i >= int(nodes.size()) || done[size_t(i)]) continue;
            done[size_t(i)] = 1;
            SceneNode& n = nodes[size_t(i)];
            const int p = n.parent;
            n.world = (p >= 0 && p < int(nodes.size()) && done[size_t(p)]) ? nodes[size_t(p)].world * n.local.matrix() : n.local.matrix();
            for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back(*c);
        }
    };
    for (int r : roots) walk(r);
    for (int i = 0; i < int(nodes.size()); ++i)
        if (!done[size_t(i)]) walk(i);
}

void Scene::updateWorldTransforms() {
    computeNodeWorlds();
    for (auto& l : lights) {
        if (l.node < 0 || l.node >= int(nodes.size())) continue;
        const glm::mat4& w = nodes[size_t(l.node)].world;
        l.position = glm::vec3(w[3]);
        const glm::vec3 d = glm::vec3(w * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
        const float len = glm::length(d);
        if (len > 1e-20f && std::isfinite(len)) l.direction = d / len;  // a zero scale keeps the last direction
    }
    for (auto& c : cameras) {
        if (c.node < 0 || c.node >= int(nodes.size())) continue;
        // Scale removed: a camera's frame is orthonormal.
        glm::mat4 w = nodes[size_t(c.node)].world;
        for (int k = 0; k < 3; ++k) {
            const float len = glm::length(glm::vec3(w[k]));
            if (len > 1e-20f && std::isfinite(len)) w[k] /= len;
        }
        c.cameraToWorld = w;
    }
}

glm::mat4 Scene::partModel(int part) const {
    if (part < 0 || part >= int(parts.size())) return glm::mat4(1.0f);
    const MeshPart& p = parts[size_t(part)];
    if (p.node < 0 || p.node >= int(nodes.size())) return glm::mat4(1.0f);
    const glm::mat4& w = nodes[size_t(p.node)].world;
    if (w == p.restWorld) return glm::mat4(1.0f);  // == (not memcmp): -0 and +0 agree
    return w * glm::inverse(p.restWorld);
}

bool Scene::nodeVisible(int node) const {
    for (int guard = 0; node >= 0 && node < int(nodes.size()) && guard <= int(nodes.size()); ++guard) {
        if (!nodes[size_t(node)].visible) return false;
        node = nodes[size_t(node)].parent;
    }
    return true;
}

size_t extendByVertices(Aabb& b, const MeshPart& part, const glm::mat4& model) {
    const bool identity = model == glm::mat4(1.0f);  // a part where it was loaded: its positions as they are
    size_t left = 0;
    for (const auto& v : part.vertices) {
        const glm::vec3 q = identity ? v.position : glm::vec3(model * glm::vec4(v.position, 1.0f));
        if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)) b.extend(q);
        else ++left;
    }
    return left;
}

Aabb Scene::nodeBounds(int node) const {
    Aabb b;
    if (node < 0 || node >= int(nodes.size())) return b;
    std::vector<int> stack{node};
    for (size_t guard = 0; !stack.empty() && guard <= nodes.size(); ++guard) {
        const int i = stack.back();
        stack.pop_back();
        const SceneNode& n = nodes[size_t(i)];
        for (int pi : n.parts)
            if (pi >= 0 && pi < int(parts.size())) extendByVertices(b, parts[size_t(pi)], partModel(pi));
        for (int c : n.children)
            if (c >= 0 && c < int(nodes.size())) stack.push_back(c);
    }
    if (!b.valid()) b.extend(glm::vec3(nodes[size_t(node)].world[3]));
    return b;
}

Aabb Scene::currentBounds() const {
    Aabb b;
    for (int i = 0; i < int(parts.size()); ++i)
        if (partVisible(i)) extendByVertices(b, parts[size_t(i)], partModel(i));
    return b;
}

void Scene::linkNodes() {
    roots.clear();
    const int n = int(nodes.size());
    for (auto& node : nodes) {
        node.children.clear();
        node.parts.clear();
        node.light = node.camera = -1;
        if (node.parent >= n) node.parent = -1;
    }
    for (int i = 0; i < n; ++i) {
        const int p = nodes[size_t(i)].parent;
        if (p >= 0 && p != i) nodes[size_t(p)].children.push_back(i);
        else { nodes[size_t(i)].parent = -1; roots.push_back(i); }
    }
    for (int i = 0; i < int(parts.size()); ++i)
        if (parts[size_t(i)].node >= 0 && parts[size_t(i)].node < n) nodes[size_t(parts[size_t(i)].node)].parts.push_back(i);
        else parts[size_t(i)].node = -1;
    for (int i = 0; i < int(lights.size()); ++i)
        if (lights[size_t(i)].node >= 0 && lights[size_t(i)].node < n) nodes[size_t(lights[size_t(i)].node)].light = i;
        else lights[size_t(i)].node = -1;
    for (int i = 0; i < int(cameras.size()); ++i)
        if (cameras[size_t(i)].node >= 0 && cameras[size_t(i)].node < n) nodes[size_t(cameras[size_t(i)].node)].camera = i;
        else cameras[size_t(i)].node = -1;
}

int Scene::addNode(const std::string& name, int parent, const Transform& local) {
    SceneNode n;
    n.name = name.empty() ? "node[" + std::to_string(nodes.size()) + "]" : name;
    n.parent = (parent >= 0 && parent < int(nodes.size())) ? parent : -1;
    n.local = local;
    n.world = n.parent >= 0 ? nodes[size_t(n.parent)].world * local.matrix() : local.matrix();
    nodes.push_back(std::move(n));
    const int i = int(nodes.size()) - 1;
    if (nodes[size_t(i)].parent >= 0) nodes[size_t(nodes[size_t(i)].parent)].children.push_back(i);
    else roots.push_back(i);
    return i;
}

namespace {
// The rotation taking the node's -Z (a glTF light's direction) to d.
glm::quat rotationToDirection(const glm::vec3& d) {
    const float len = glm::length(d);
    if (!(len > 0.0f) || !std::isfinite(len)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    const glm::vec3 a(0.0f, 0.0f, -1.0f), b = d / len;
    const float c = glm::dot(a, b);
    if (c < -0.999999f) return glm::quat(0.0f, 1.0f, 0.0f, 0.0f);  // opposite: half a turn about X
    const glm::vec3 axis = glm::cross(a, b);
    return glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
}
}  // namespace

void Scene::ensureNodes() {
    for (auto& p : parts)
        if (p.node < 0) p.node = addNode(p.name);
    for (auto& l : lights)
        if (l.node < 0) {
            Transform t;
            t.translation = l.position;
            t.rotation = rotationToDirection(l.direction);
            l.node = addNode(l.name, -1, t);
        }
    for (auto& c : cameras)
        if (c.node < 0) {
            Transform t;
            t.translation = glm::vec3(c.cameraToWorld[3]);
            t.rotation = glm::quat_cast(glm::mat3(c.cameraToWorld));
            c.node = addNode(c.name, -1, t);
        }
    linkNodes();
    computeNodeWorlds();
    // The vertices are where the nodes are now.
    for (auto& p : parts) p.restWorld = nodes[size_t(p.node)].world;
}

}  // namespace deepgi
