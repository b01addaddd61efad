#version 450 core
// Emits each triangle once per layer (gl_Layer), so one geometry pass fills both layers of the deep G-buffer.
#include "common.glsl"
layout(triangles) in;
layout(triangle_strip, max_vertices = 6) out;
in VS { vec3 world; vec3 normal; vec2 uv; } vs[];
out GS { vec3 world; vec3 normal; vec2 uv; } gs;
#ifdef NORMAL_MAPS
in vec4 vsTangent[];
out vec4 gsTangent;
#endif
#ifdef OBJECT_MOTION
in vec3 vsPrevWorld[];
out vec3 gsPrevWorld;      // the surface's position last frame (per-object motion)
#endif
#ifdef OBJECT_IDS
flat in uint vsObjectId[];
flat out uint gsObjectId;
#endif
invariant gl_Position;  // the same depth in every variant: layer 2's shading tests EQUAL against its depth prepass
uniform int uFirstLayer;  // 0, or 1 for the second pass of depth peeling
uniform int uLayerCount;  // 1 or 2
// Clip x, y -> xy * scale + offset * w: layer 2 drawn at level L of the targets, each of its pixels the ray through
// the level-0 pixel that level L samples (identity for a full-resolution draw).
uniform vec4 uClipMap;
void main() {
    for (int k = 0; k < 2; ++k) {
        if (k >= uLayerCount) break;
        int layer = uFirstLayer + k;
        for (int i = 0; i < 3; ++i) {
            gl_Layer = layer;  // set before every EmitVertex: outputs are undefined after it
            gs.world = vs[i].world;
            gs.normal = vs[i].normal;
            gs.uv = vs[i].uv;
#ifdef NORMAL_MAPS
            gsTangent = vsTangent[i];
#endif
#ifdef OBJECT_MOTION
            gsPrevWorld = vsPrevWorld[i];
#endif
#ifdef OBJECT_IDS
            gsObjectId = vsObjectId[i];
#endif
            gl_Position = uViewProj * vec4(vs[i].world, 1.0);
            gl_Position.xy = gl_Position.xy * uClipMap.xy + uClipMap.zw * gl_Position.w;
            EmitVertex();
        }
        EndPrimitive();
    }
}
