#include "renderer/scene/scene_validation.h"

#include "renderer/core/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace deepgi {
namespace {

// Embree refuses ray origins beyond about 1.8e18 (its ray.valid() assertion aborts the process); float positions
// that far out have a spacing of 1e11 anyway.
constexpr double kMaxCoordinate = 1e18;
constexpr float kPi = 3.14159265f;

bool finite(float v) { return std::isfinite(v); }
bool finite3(const glm::vec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }

std::string num(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

void note(std::vector<std::string>* w, const std::string& msg) {
    if (w) w->push_back(msg);
}

// Orthonormal rotation from the camera's world matrix (scale removed, computed in double so a scale of 1e-30 still
// normalises), or "" problem set when the axes are degenerate.
std::string orthonormalise(glm::mat4& m, bool* corrected) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return "non-finite node transform";
    const glm::dvec3 t(m[3]);
    if (std::abs(t.x) > kMaxCoordinate || std::abs(t.y) > kMaxCoordinate || std::abs(t.z) > kMaxCoordinate)
        return "position (" + num(t.x) + ", " + num(t.y) + ", " + num(t.z) + ") is farther than " +
               num(kMaxCoordinate) + " from the origin";
    glm::dvec3 axis[3];
    for (int i = 0; i < 3; ++i) {
        axis[i] = glm::dvec3(m[i]);
        const double len = glm::length(axis[i]);
        if (!(len > 0.0) || !std::isfinite(len)) return "degenerate node transform (an axis is scaled to 0)";
        axis[i] /= len;
    }
    const double det = glm::dot(glm::cross(axis[0], axis[1]), axis[2]);
    if (!(std::abs(det) > 1e-6)) return "degenerate node transform (collinear axes)";
    // Keep the view axis (-Z) and the up direction, rebuild a right-handed frame.
    const glm::dvec3 z = axis[2];
    glm::dvec3 y = axis[1] - glm::dot(axis[1], z) * z;
    y /= glm::length(y);
    const glm::dvec3 x = glm::cross(y, z);
    *corrected = det < 0.0 || glm::length(x - axis[0]) > 1e-3 || glm::length(y - axis[1]) > 1e-3;
    m[0] = glm::vec4(glm::vec3(x), 0.0f);
    m[1] = glm::vec4(glm::vec3(y), 0.0f);
    m[2] = glm::vec4(glm::vec3(z), 0.0f);
    m[3][3] = 1.0f;
    return "";
}

}  // namespace

bool validateCamera(CameraDesc& c, std::vector<std::string>* w) {
    const std::string who = "camera '" + c.name + "': ";
    bool corrected = false;
    const std::string problem = orthonormalise(c.cameraToWorld, &corrected);
    if (!problem.empty()) {
        note(w, who + problem + "; camera skipped");
        return false;
    }
    if (corrected) note(w, who + "mirrored or sheared node transform, rotation orthonormalised");
    if (c.perspective) {
        if (!(c.yfov > 0.0f && c.yfov < kPi)) {
            note(w, who + "invalid yfov " + num(c.yfov) + ", using 0.8");
            c.yfov = 0.8f;
        }
        if (!(c.aspectRatio >= 0.0f) || !finite(c.aspectRatio)) {
            note(w, who + "invalid aspectRatio " + num(c.aspectRatio) + ", using the image's");
            c.aspectRatio = 0.0f;
        }
        if (!(c.znear > 0.0f) || !finite(c.znear)) {
            note(w, who + "invalid znear " + num(c.znear) + " (must be > 0), using 0.05");
            c.znear = 0.05f;
        }
    } else {
        if (!finite(c.ymag) || c.ymag == 0.0f) {
            note(w, who + "orthographic ymag " + num(c.ymag) + " gives an image of no size; camera skipped");
            return false;
        }
        if (c.ymag < 0.0f || c.xmag < 0.0f) {
            note(w, who + "negative orthographic magnification, using its magnitude");
            c.ymag = std::abs(c.ymag);
            c.xmag = std::abs(c.xmag);
        }
        if (!(c.znear >= 0.0f) || !finite(c.znear)) {
            note(w, who + "invalid znear " + num(c.znear) + " (must be >= 0), using 0");
            c.znear = 0.0f;
        }
    }
    if (std::isinf(c.zfar) && c.zfar > 0.0f) c.zfar = 0.0f;  // +inf means what 0 means here: infinite
    if (!(c.zfar >= 0.0f)) {
        note(w, who + "invalid zfar " + num(c.zfar) + ", using an infinite far plane");
        c.zfar = 0.0f;
    }
    if (c.zfar > 0.0f && c.znear >= c.zfar) {
        note(w, who + "znear " + num(c.znear) + " >= zfar " + num(c.zfar) + ": zfar ignored (infinite far plane)");
        c.zfar = 0.0f;
    }
    return true;
}

bool validateLight(Light& l, std::vector<std::string>* w) {
    const std::string who = "light '" + l.name + "': ";
    if (!finite3(l.color) || !finite(l.intensity)) {
        note(w, who + "non-finite colour or intensity; light skipped");
        return false;
    }
    if (!finite3(l.position) || std::abs(l.position.x) > kMaxCoordinate || std::abs(l.position.y) > kMaxCoordinate ||
        std::abs(l.position.z) > kMaxCoordinate) {
        note(w, who + "non-finite or too distant position; light skipped");
        return false;
    }
    const float dirLen = glm::length(l.direction);
    if (l.type != LightType::Point) {
        if (!(dirLen > 0.0f) || !std::isfinite(dirLen)) {
            note(w, who + "degenerate direction (node transform scaled to 0); light skipped");
            return false;
        }
        l.direction /= dirLen;
    }
    if (l.color.x < 0.0f || l.color.y < 0.0f || l.color.z < 0.0f) {
        note(w, who + "negative colour (" + num(l.color.x) + ", " + num(l.color.y) + ", " + num(l.color.z) +
                    "), negative channels set to 0");
        l.color = glm::max(l.color, glm::vec3(0.0f));
    }
    if (l.intensity < 0.0f) {
        note(w, who + "negative intensity " + num(l.intensity) + ", using 0 (light off)");
        l.intensity = 0.0f;
    }
    if (std::isinf(l.range) && l.range > 0.0f) l.range = 0.0f;
    if (!(l.range >= 0.0f)) {
        note(w, who + "invalid range " + num(l.range) + ", using an infinite range");
        l.range = 0.0f;
    }
    if (l.type == LightType::Spot) {
        const float halfPi = 0.5f * kPi;
        if (!finite(l.outerConeAngle) || !finite(l.innerConeAngle)) {
            note(w, who + "non-finite cone angle, using inner 0 and outer pi/4");
            l.innerConeAngle = 0.0f;
            l.outerConeAngle = 0.25f * kPi;
        }
        if (l.innerConeAngle > l.outerConeAngle) {
            note(w, who + "inner cone angle " + num(l.innerConeAngle) + " larger than the outer one " +
                        num(l.outerConeAngle) + ", swapped");
            std::swap(l.innerConeAngle, l.outerConeAngle);
        }
        if (!(l.outerConeAngle > 0.0f) || l.outerConeAngle > halfPi) {
            note(w, who + "outer cone angle " + num(l.outerConeAngle) + " outside (0, pi/2], clamped");
            l.outerConeAngle = glm::clamp(l.outerConeAngle, 1e-3f, halfPi);
        }
        if (l.innerConeAngle < 0.0f || l.innerConeAngle > l.outerConeAngle) {
            note(w, who + "inner cone angle " + num(l.innerConeAngle) + " outside [0, outer], clamped");
            l.innerConeAngle = glm::clamp(l.innerConeAngle, 0.0f, l.outerConeAngle);
        }
    }
    return true;
}

void validateMaterial(Material& m, std::vector<std::string>* w) {
    const std::string who = "material '" + m.name + "': ";
    glm::vec4& f = m.baseColorFactor;
    bool bad = false;
    for (int c = 0; c < 4; ++c) {
        if (!std::isfinite(f[c])) { f[c] = 1.0f; bad = true; }
        if (f[c] < 0.0f || f[c] > 1.0f) { f[c] = glm::clamp(f[c], 0.0f, 1.0f); bad = true; }
    }
    if (bad) note(w, who + "baseColorFactor outside [0, 1] or non-finite, clamped to (" + num(f.x) + ", " + num(f.y) +
                         ", " + num(f.z) + ", " + num(f.w) + ")");
    glm::vec3& e = m.emissiveFactor;
    if (!finite3(e) || e.x < 0.0f || e.y < 0.0f || e.z < 0.0f) {
        for (int c = 0; c < 3; ++c) if (!std::isfinite(e[c]) || e[c] < 0.0f) e[c] = 0.0f;
        note(w, who + "negative or non-finite emissiveFactor, those channels set to 0");
    }
    // Metallic-roughness factors: [0, 1] (glTF's range); normal scale finite; occlusion strength [0, 1].
    const auto unit = [&](float& v, float fallback, const char* what) {
        if (std::isfinite(v) && v >= 0.0f && v <= 1.0f) return;
        const float fixed = std::isfinite(v) ? glm::clamp(v, 0.0f, 1.0f) : fallback;
        note(w, who + what + " " + num(v) + " outside [0, 1] or non-finite, set to " + num(fixed));
        v = fixed;
    };
    unit(m.metallic, 1.0f, "metallicFactor");
    unit(m.roughness, 1.0f, "roughnessFactor");
    unit(m.occlusionStrength, 1.0f, "occlusion strength");
    unit(m.dielectricF0, 0.04f, "dielectric F0");
    if (!std::isfinite(m.normalScale)) {
        note(w, who + "non-finite normal texture scale, set to 1");
        m.normalScale = 1.0f;
    }
}

void validateScene(Scene& s) {
    std::vector<CameraDesc> cameras;
    for (auto& c : s.cameras)
        if (validateCamera(c, &s.warnings)) cameras.push_back(std::move(c));
    s.cameras = std::move(cameras);
    std::vector<Light> lights;
    for (auto& l : s.lights)
        if (validateLight(l, &s.warnings)) lights.push_back(std::move(l));
    s.lights = std::move(lights);
    for (auto& m : s.materials) validateMaterial(m, &s.warnings);
}

std::string cameraProblem(const Camera& c) {
    glm::mat4 m = c.cameraToWorld;
    bool corrected = false;
    std::string p = orthonormalise(m, &corrected);
    if (!p.empty()) return p;
    if (c.perspective && !(c.yfov > 0.0f && c.yfov < kPi)) return "field of view " + num(c.yfov) + " outside (0, pi)";
    if (!c.perspective && !(std::isfinite(c.orthoHalfHeight) && c.orthoHalfHeight > 0.0f))
        return "orthographic half height " + num(c.orthoHalfHeight) + " is not positive";
    if (!(c.znear >= 0.0f) || !(c.zfar > c.znear) || !std::isfinite(c.zfar))
        return "clip planes znear " + num(c.znear) + ", zfar " + num(c.zfar) + " (need 0 <= znear < zfar)";
    return "";
}

}  // namespace deepgi
