#version 450 core
// Defines: NORMAL_MAPS (tangents interpolated), OBJECT_IDS (node index out), OBJECT_MOTION (last frame's position
// from the object's previous matrix; without, the object is still: its previous position is this one).
#include "scene_objects.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
layout(location = 3) in vec4 aTangent;  // xyz, w = handedness (Vertex::tangent)
out VS { vec3 world; vec3 normal; vec2 uv; } vs;
#ifdef NORMAL_MAPS
out vec4 vsTangent;
#endif
#ifdef OBJECT_MOTION
out vec3 vsPrevWorld;     // where this vertex was last frame (its object's previous model matrix)
#endif
#ifdef OBJECT_IDS
flat out uint vsObjectId; // node index + 1
#endif
void main() {
    SceneObject o = uObjects[aObject];
    vs.world = (o.model * vec4(aPosition, 1.0)).xyz;
    vs.normal = mat3(o.normalMatrix) * aNormal;
    vs.uv = aUV;
#ifdef NORMAL_MAPS
    vsTangent = vec4(mat3(o.model) * aTangent.xyz, aTangent.w);  // tangents move with the object
#endif
#ifdef OBJECT_MOTION
    vsPrevWorld = (o.prevModel * vec4(aPosition, 1.0)).xyz;
#endif
#ifdef OBJECT_IDS
    vsObjectId = o.id.x;
#endif
    gl_Position = vec4(vs.world, 1.0);
}
