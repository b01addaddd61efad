#pragma once
// One validation of what a scene's cameras, lights and material factors mean, shared by the GL renderer and the
// path tracer so the two never disagree on a file: the loader runs validateScene() once (its warnings reach every
// command through Scene::warnings), effectiveLights() and the path tracer's shading apply the same corrections to
// scenes built in code, and both renderers refuse a camera that cameraProblem() rejects.
//
// Rules (each correction or refusal is one warning naming the camera/light/material):
//   camera  non-finite, degenerate (scale 0, collinear axes) or too distant (> 1e18) transform: refused;
//           mirrored or sheared rotation: orthonormalised; yfov outside (0, pi): 0.8; aspectRatio < 0: the image's;
//           znear <= 0 or non-finite (perspective): 0.05; znear >= zfar: the far plane is ignored (infinite);
//           orthographic ymag zero/non-finite: refused (no size to choose); negative magnification: its magnitude.
//   light   non-finite colour, intensity or position/direction: refused; negative colour or intensity: 0;
//           negative or NaN range: infinite; spot cones: outer clamped to (0, pi/2], inner to [0, outer], an
//           inner cone larger than the outer one is swapped with it.
//   material baseColorFactor outside [0, 1] or non-finite: clamped (the G-buffer stores albedo in RGBA8, so the
//           renderer has always clamped it); negative or non-finite emissiveFactor: 0; metallic, roughness,
//           occlusion strength outside [0, 1]: clamped (non-finite: 1); non-finite normal scale: 1.
#include "renderer/scene/scene.h"

#include <string>
#include <vector>

namespace deepgi {

struct Camera;

// Each returns false when the item is refused (the caller drops it); corrections are made in place. Every message
// appended to `warnings` names the item.
bool validateCamera(CameraDesc& camera, std::vector<std::string>* warnings);
bool validateLight(Light& light, std::vector<std::string>* warnings);
void validateMaterial(Material& material, std::vector<std::string>* warnings);

// All of the scene's cameras, lights and materials; refused cameras and lights are removed. Warnings go to
// scene.warnings.
void validateScene(Scene& scene);

// "" when the runtime camera can be rendered; otherwise why not (non-finite or degenerate transform, position
// beyond 1e18, bad field of view, magnification or clip planes). Both renderers refuse such a camera.
std::string cameraProblem(const Camera& camera);

}  // namespace deepgi
