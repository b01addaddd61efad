#version 450 core
// Defines: NORMAL_MAPS (tangents interpolated), OBJECT_IDS (node index out), OBJECT_MOTION (last frame's position
// from the object's previous matrix; without, the object is still: its previous position is this one).
// LAYERED: no geometry shader; instance i of the draw goes to layer uFirstLayer + i (gl_Layer from the vertex
// stage), so the outputs are the fragment shader's inputs (block GS, gs* names).
#ifdef LAYERED
#extension GL_ARB_shader_viewport_layer_array : require
#define vsTangent gsTangent
#define vsPrevWorld gsPrevWorld
#define vsObjectId gsObjectId
#include "common.glsl"
uniform int uFirstLayer;
uniform int uLayerCount;
uniform vec4 uClipMap;  // xy scale, zw offset x w of clip x, y: layer 2 drawn at a coarser level (identity otherwise)
#endif
#include "scene_objects.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
layout(location = 3) in vec4 aTangent;  // xyz, w = handedness (Vertex::tangent)
#ifdef LAYERED
out GS { vec3 world; vec3 normal; vec2 uv; } vs;
#else
out VS { vec3 world; vec3 normal; vec2 uv; } vs;
#endif
#ifdef NORMAL_MAPS
out vec4 vsTangent;
#endif
#ifdef OBJECT_MOTION
out vec3 vsPrevWorld;     // where this vertex was last frame (its object's previous model matrix)
#endif
#ifdef OBJECT_IDS
flat out uint vsObjectId; // node index + 1
#endif
#ifdef LAYERED
invariant gl_Position;  // the same depth in every variant: layer 2's shading tests EQUAL against its depth prepass
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
#ifdef LAYERED
    gl_Layer = uFirstLayer + min(gl_InstanceID, uLayerCount - 1);
    gl_Position = uViewProj * vec4(vs.world, 1.0);
    gl_Position.xy = gl_Position.xy * uClipMap.xy + uClipMap.zw * gl_Position.w;
#else
    gl_Position = vec4(vs.world, 1.0);
#endif
}
