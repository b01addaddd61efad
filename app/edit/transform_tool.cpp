#include "app/edit/transform_tool.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace deepgi::edit {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kMinScale = 1e-4f;  // a factor of 0 would make the object's normal matrix singular
const char* kAxisNames[] = {"X", "Y", "Z"};

// The pointer's angle about c on the screen, counter-clockwise positive (the pointer's y grows downwards).
float screenAngle(const glm::vec2& p, const glm::vec2& c) { return std::atan2(-(p.y - c.y), p.x - c.x); }
float wrapAngle(float a) {
    while (a > kPi) a -= 2.0f * kPi;
    while (a < -kPi) a += 2.0f * kPi;
    return a;
}
std::string number(float v) {
    char b[32];
    std::snprintf(b, sizeof(b), "%.4g", double(v));
    return b;
}
}  // namespace

glm::mat4 Trs::matrix() const {
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

glm::quat rotationOf(const glm::mat4& m) {
    glm::mat3 r(m);
    for (int i = 0; i < 3; ++i) {
        const float l = glm::length(r[i]);
        r[i] = l > 0.0f ? r[i] / l : glm::vec3(i == 0, i == 1, i == 2);
    }
    if (glm::determinant(r) < 0.0f) r[0] = -r[0];
    return glm::normalize(glm::quat_cast(r));
}

bool TransformTool::begin(ToolMode mode, const std::vector<TransformTarget>& targets, const glm::vec3& pivot,
                          const ToolView& view, const glm::vec2& pointer) {
    if (active()) cancel();
    if (mode == ToolMode::None || targets.empty()) return false;
    *this = TransformTool();
    mode_ = mode;
    targets_ = targets;
    pivot_ = pivot;
    view_ = view;
    start_ = at_ = pointer;
    return true;
}

void TransformTool::pointer(const glm::vec2& at) {
    if (!active()) return;
    if (mode_ == ToolMode::Rotate) {  // turns accumulate: a pointer circling the pivot twice turns 720 degrees
        const glm::vec2 c = project(pivot_);
        angle_ += wrapAngle(screenAngle(at, c) - screenAngle(at_, c));
    }
    at_ = at;
}

void TransformTool::axis(int a, bool plane) {
    if (!active() || a < 0 || a > 2) return;
    if (mode_ == ToolMode::Rotate) plane = false;  // rotating "in the plane without X" is rotating about X
    if (axis_ == a && plane_ == plane) {
        if (orient_ == Orientation::Global) orient_ = Orientation::Local;
        else axis_ = -1, plane_ = false, orient_ = Orientation::Global;
    } else {
        axis_ = a;
        plane_ = plane;
        orient_ = Orientation::Global;
    }
    if (component_ >= components()) component_ = 0;
}

int TransformTool::components() const {
    if (mode_ != ToolMode::Translate) return 1;
    return axis_ < 0 ? 3 : plane_ ? 2 : 1;
}

bool TransformTool::type(char c) {
    if (!active()) return false;
    std::string& t = text_[component_];
    if (c >= '0' && c <= '9') t += c;
    else if (c == '.') { if (t.find('.') == std::string::npos) t += c; }
    else if (c == '-') negate_[component_] = !negate_[component_];
    else if (c == '/') reciprocal_[component_] = !reciprocal_[component_];
    else return false;
    typing_ = true;
    return true;
}

void TransformTool::backspace() {
    if (!active() || !typing_) return;
    std::string& t = text_[component_];
    if (!t.empty()) { t.pop_back(); return; }
    if (negate_[component_] || reciprocal_[component_]) { negate_[component_] = reciprocal_[component_] = false; return; }
    // Nothing left to delete: typing ends, the pointer drives again.
    typing_ = false;
    for (int i = 0; i < 3; ++i) text_[i].clear(), negate_[i] = reciprocal_[i] = false;
    component_ = 0;
}

void TransformTool::tab() {
    if (active()) component_ = (component_ + 1) % components();
}

float TransformTool::typedValue(int i, float untyped) const {
    float v = text_[i].empty() ? untyped : float(std::strtod(text_[i].c_str(), nullptr));  // "." reads as 0
    if (reciprocal_[i]) v = v != 0.0f ? 1.0f / v : untyped;
    return negate_[i] ? -v : v;
}

void TransformTool::rayAt(const glm::vec2& p, glm::vec3& o, glm::vec3& d) const {
    const Camera& c = view_.camera;
    const float w = std::max(view_.width, 1.0f), h = std::max(view_.height, 1.0f), aspect = w / h;
    const float nx = 2.0f * p.x / w - 1.0f, ny = 1.0f - 2.0f * p.y / h;
    glm::vec3 lo, ld;
    if (c.perspective) {
        const float t = std::tan(0.5f * c.yfov);
        lo = glm::vec3(0.0f);
        ld = glm::normalize(glm::vec3(nx * t * aspect, ny * t, -1.0f));
    } else {
        lo = glm::vec3(nx * c.orthoHalfHeight * aspect, ny * c.orthoHalfHeight, 0.0f);
        ld = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    o = glm::vec3(c.cameraToWorld * glm::vec4(lo, 1.0f));
    d = glm::normalize(glm::vec3(c.cameraToWorld * glm::vec4(ld, 0.0f)));
}

glm::vec2 TransformTool::project(const glm::vec3& p) const {
    const float w = std::max(view_.width, 1.0f), h = std::max(view_.height, 1.0f);
    const glm::vec4 clip = view_.camera.projection(w / h) * view_.camera.view() * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-12f && view_.camera.perspective) return glm::vec2(w, h) * 0.5f;  // behind the eye: the centre
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return glm::vec2((ndc.x + 1.0f) * 0.5f * w, (1.0f - ndc.y) * 0.5f * h);
}

glm::vec3 TransformTool::worldAxis(int i, int a) const {
    if (orient_ == Orientation::Global || i < 0 || i >= int(targets_.size())) return glm::vec3(a == 0, a == 1, a == 2);
    return glm::normalize(rotationOf(targets_[size_t(i)].world()) * glm::vec3(a == 0, a == 1, a == 2));
}

glm::vec3 TransformTool::amount() const {
    if (!active()) return glm::vec3(0.0f);
    if (mode_ == ToolMode::Translate) {
        if (typing_) return glm::vec3(typedValue(0, 0.0f), typedValue(1, 0.0f), typedValue(2, 0.0f));
        glm::vec3 o0, d0, o1, d1;
        rayAt(start_, o0, d0);
        rayAt(at_, o1, d1);
        if (axis_ >= 0 && !plane_) {
            // Blender's axis motion: the pointer projected onto the axis as drawn on the screen, then the point of
            // the axis under that projection (the object stays under the pointer's foot on the axis line).
            const glm::vec3 a = worldAxis(0, axis_);
            const float depth = std::max(glm::length(pivot_ - view_.camera.position()), 1e-3f);
            const glm::vec2 s0 = project(pivot_), s1 = project(pivot_ + a * (0.1f * depth));
            glm::vec2 ds = s1 - s0;
            if (glm::length(ds) < 1e-3f) return glm::vec3(0.0f);  // the axis points at the eye: no motion along it
            ds = glm::normalize(ds);
            auto along = [&](const glm::vec2& p) {
                glm::vec3 o, d;
                rayAt(s0 + ds * glm::dot(p - s0, ds), o, d);
                const glm::vec3 w0 = pivot_ - o;
                const float b = glm::dot(a, d), den = 1.0f - b * b;
                return den < 1e-6f ? 0.0f : (b * glm::dot(d, w0) - glm::dot(a, w0)) / den;
            };
            return glm::vec3(along(at_) - along(start_), 0.0f, 0.0f);
        }
        // The view plane (no constraint) or the constraint plane, through the pivot: the pointer rays' hits. A
        // constraint plane seen nearly edge-on takes the view plane's motion without its normal part instead.
        const glm::vec3 fwd = view_.camera.forward();
        const glm::vec3 n = axis_ >= 0 ? worldAxis(0, axis_) : fwd;
        const bool edgeOn = axis_ >= 0 && std::abs(glm::dot(n, fwd)) < 0.2f;
        const glm::vec3 pn = edgeOn ? fwd : n;
        auto hit = [&](const glm::vec3& o, const glm::vec3& d, glm::vec3& out) {
            const float dn = glm::dot(d, pn);
            if (std::abs(dn) < 1e-4f) return false;
            out = o + d * (glm::dot(pivot_ - o, pn) / dn);
            return true;
        };
        glm::vec3 h0, h1;
        if (!hit(o0, d0, h0) || !hit(o1, d1, h1)) return glm::vec3(0.0f);
        if (edgeOn) h1 -= n * glm::dot(h1 - h0, n);
        const glm::vec3 delta = h1 - h0;
        if (axis_ < 0) return delta;  // world axes
        const int u = (axis_ + 1) % 3, v = (axis_ + 2) % 3;
        const int first = std::min(u, v), second = std::max(u, v);
        return glm::vec3(glm::dot(delta, worldAxis(0, first)), glm::dot(delta, worldAxis(0, second)), 0.0f);
    }
    if (mode_ == ToolMode::Rotate) {  // degrees, in the sense applied about the rotation axis
        if (typing_) return glm::vec3(axis_ >= 0 ? typedValue(0, 0.0f) : -typedValue(0, 0.0f), 0.0f, 0.0f);
        float sign = 1.0f;
        if (axis_ >= 0 && glm::dot(worldAxis(0, axis_), -view_.camera.forward()) < 0.0f) sign = -1.0f;
        return glm::vec3(glm::degrees(angle_) * sign, 0.0f, 0.0f);
    }
    // Scale: a factor.
    float f = 1.0f;
    if (typing_) {
        f = typedValue(0, 1.0f);
    } else {
        const glm::vec2 c = project(pivot_), r0 = start_ - c, r1 = at_ - c;
        f = glm::length(r1) / std::max(glm::length(r0), 1.0f);
        if (glm::dot(r0, r1) < 0.0f) f = -f;  // past the pivot: mirrored
    }
    if (std::abs(f) < kMinScale) f = f < 0.0f ? -kMinScale : kMinScale;
    return glm::vec3(f, 0.0f, 0.0f);
}

glm::vec3 TransformTool::translationOf(int i) const {
    const glm::vec3 a = amount();
    if (axis_ < 0) return a;  // world axes (typed: X, Y, Z; pointer: the view plane)
    if (!plane_) return a.x * worldAxis(i, axis_);
    const int u = std::min((axis_ + 1) % 3, (axis_ + 2) % 3), v = std::max((axis_ + 1) % 3, (axis_ + 2) % 3);
    return a.x * worldAxis(i, u) + a.y * worldAxis(i, v);
}

std::vector<Trs> TransformTool::current() const {
    std::vector<Trs> out;
    out.reserve(targets_.size());
    for (int i = 0; i < int(targets_.size()); ++i) {
        const TransformTarget& t = targets_[size_t(i)];
        Trs r = t.local;
        const glm::mat4 world = t.world();
        const glm::vec3 w = glm::vec3(world[3]);
        const glm::mat4 toParent = glm::inverse(t.parentWorld);
        glm::vec3 moved = w;
        if (mode_ == ToolMode::Translate) {
            moved = w + translationOf(i);
        } else if (mode_ == ToolMode::Rotate) {
            const glm::vec3 axis = axis_ >= 0 ? worldAxis(i, axis_) : -view_.camera.forward();
            const glm::quat q = glm::angleAxis(glm::radians(amount().x), glm::normalize(axis));
            moved = pivot_ + q * (w - pivot_);
            const glm::quat qp = rotationOf(t.parentWorld);
            r.rotation = glm::normalize(glm::inverse(qp) * q * qp * t.local.rotation);
        } else if (mode_ == ToolMode::Scale) {
            const float f = amount().x;
            glm::vec3 fk(f);  // factor per axis of the constraint frame
            if (axis_ >= 0) {
                fk = glm::vec3(plane_ ? f : 1.0f);
                fk[axis_] = plane_ ? 1.0f : f;
            }
            glm::mat3 s(0.0f);
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 e = worldAxis(i, k);
                s += fk[k] * glm::outerProduct(e, e);
            }
            moved = pivot_ + s * (w - pivot_);
            // Exact when the frame's axes are the object's own (local, uniform, or an unrotated object): the factors
            // go to the local scale; otherwise the scaled matrix is split again (a shear it would need is dropped).
            const glm::quat qo = rotationOf(world);
            bool aligned = true;
            glm::vec3 fj(1.0f);
            if (fk.x == fk.y && fk.y == fk.z) {
                fj = fk;
            } else {
                for (int j = 0; j < 3 && aligned; ++j) {
                    const glm::vec3 oj = qo * glm::vec3(j == 0, j == 1, j == 2);
                    int match = -1;
                    for (int k = 0; k < 3; ++k)
                        if (std::abs(glm::dot(oj, worldAxis(i, k))) > 1.0f - 1e-5f) match = k;
                    if (match < 0) aligned = false;
                    else fj[j] = fk[match];
                }
            }
            if (aligned) {
                r.scale = t.local.scale * fj;
            } else {
                const glm::mat3 local = glm::mat3(toParent) * (s * glm::mat3(world));
                glm::mat3 rot = local;
                glm::vec3 sc;
                for (int j = 0; j < 3; ++j) sc[j] = glm::length(local[j]);
                if (glm::determinant(local) < 0.0f) sc.x = -sc.x;
                // Gram-Schmidt: the rotation nearest the scaled columns' directions.
                rot[0] = glm::normalize(local[0] / sc.x);
                rot[1] = glm::normalize(local[1] - glm::dot(local[1], rot[0]) * rot[0]);
                rot[2] = glm::cross(rot[0], rot[1]);
                r.rotation = glm::normalize(glm::quat_cast(rot));
                r.scale = sc;
            }
        }
        if (moved != w) r.translation = glm::vec3(toParent * glm::vec4(moved, 1.0f));
        out.push_back(r);
    }
    return out;
}

std::vector<Trs> TransformTool::confirm() {
    std::vector<Trs> r = current();
    *this = TransformTool();
    return r;
}

std::vector<Trs> TransformTool::cancel() {
    std::vector<Trs> r;
    for (const auto& t : targets_) r.push_back(t.local);
    *this = TransformTool();
    return r;
}

std::string TransformTool::header() const {
    if (!active()) return "";
    const char* name = mode_ == ToolMode::Translate ? "Move" : mode_ == ToolMode::Rotate ? "Rotate" : "Scale";
    std::string h = name;
    auto typed = [&](int i) {
        std::string s = (negate_[i] ? "-" : "") + text_[i] + (reciprocal_[i] ? "/" : "");
        if (i == component_) s = "[" + s + "|]";
        return s;
    };
    const glm::vec3 a = amount();
    if (mode_ == ToolMode::Translate) {
        h += "  D: ";
        for (int i = 0; i < components(); ++i) h += (i ? " | " : "") + (typing_ ? typed(i) + " " : std::string()) + number(a[i]);
    } else if (mode_ == ToolMode::Rotate) {
        h += "  " + (typing_ ? typed(0) + " " : std::string()) + number(typing_ ? typedValue(0, 0.0f) : a.x) + " deg";
    } else {
        h += "  " + (typing_ ? typed(0) + " " : std::string()) + number(a.x);
        if (std::abs(a.x) <= kMinScale) h += " (0 would be degenerate: 0.0001 is the smallest)";
    }
    const std::string orient = orient_ == Orientation::Global ? "global" : "local";
    if (axis_ < 0) h += mode_ == ToolMode::Scale ? "  uniform" : mode_ == ToolMode::Rotate ? "  about the view axis" : "  in the view plane";
    else if (plane_) h += "  in the " + orient + " " + kAxisNames[std::min((axis_ + 1) % 3, (axis_ + 2) % 3)] +
                          kAxisNames[std::max((axis_ + 1) % 3, (axis_ + 2) % 3)] + " plane";
    else h += "  along " + orient + " " + kAxisNames[axis_];
    h += "   (X/Y/Z axis, Shift: plane, type a value, Enter/click confirm, Esc/right-click cancel)";
    return h;
}

}  // namespace deepgi::edit
