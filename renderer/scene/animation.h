#pragma once
// glTF node animation: samples TRS channels (LINEAR, STEP, CUBICSPLINE, as the glTF 2.0 specification defines them)
// and applies them to the scene's nodes.
#include "renderer/scene/scene.h"

#include <glm/glm.hpp>

namespace deepgi {

// The channel's value at `seconds` (clamped to its first and last key): xyz for translation and scale, a unit
// quaternion (x, y, z, w) for rotation. LINEAR rotation is a spherical interpolation along the shorter arc.
glm::vec4 sampleChannel(const AnimationChannel& channel, float seconds);

// Sets every animated node's local TRS at that instant (all animations), then Scene::updateWorldTransforms().
void applyAnimation(Scene& scene, float seconds);

}  // namespace deepgi
