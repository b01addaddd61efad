#pragma once
// Per-vertex tangent frames for normal mapping where a file has none (glTF without TANGENT, scenes built in code).
// Chosen over a per-pixel derivative frame in the shader so that the GL renderer and the path tracers shade with
// the very same frame (both read Vertex::tangent), and so the frame is smooth across triangles.
#include "renderer/scene/scene.h"

namespace deepgi {

// Sets every vertex's tangent from the triangles' UV gradients (MikkTSpace-like: per-triangle dP/du and dP/dv,
// area-weighted sums per vertex, Gram-Schmidt against the vertex normal). w = +1 where cross(normal, tangent)
// points along -dP/dv (glTF's +Y up in the image, v down), -1 for a mirrored UV layout. Vertices whose UVs are
// degenerate get any unit tangent perpendicular to the normal.
void generateTangents(MeshPart& part);

}  // namespace deepgi
