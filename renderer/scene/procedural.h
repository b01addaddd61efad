#pragma once
// Scenes built in code (tests, hard cases): quads and boxes with consistent CCW winding.
#include "renderer/scene/scene.h"

namespace deepgi::procedural {

int addMaterial(Scene& s, const glm::vec3& albedo, const glm::vec3& emission = glm::vec3(0.0f), bool doubleSided = false);
// Quad p0,p1,p2,p3 in counter-clockwise order seen from the side its normal points to.
void addQuad(Scene& s, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3, int material);
// Axis-aligned box; inward = faces point into the box (a room), else outward (a solid).
void addBox(Scene& s, const glm::vec3& lo, const glm::vec3& hi, int material, bool inward);
// Horizontal square at height y facing +Y.
void addFloor(Scene& s, float halfSize, float y, int material);
void addSun(Scene& s, const glm::vec3& direction, float irradiance);
void addCamera(Scene& s, const std::string& name, const glm::vec3& eye, const glm::vec3& target, float yfovDeg = 60.0f);

}  // namespace deepgi::procedural
