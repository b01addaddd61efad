#version 450 core
#include "scene_objects.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
out VS { vec3 world; vec3 normal; vec2 uv; } vs;
out vec3 vsPrevWorld;     // where this vertex was last frame (its object's previous model matrix)
flat out uint vsObjectId; // node index + 1
void main() {
    SceneObject o = uObjects[aObject];
    vs.world = (o.model * vec4(aPosition, 1.0)).xyz;
    vs.normal = mat3(o.normalMatrix) * aNormal;
    vs.uv = aUV;
    vsPrevWorld = (o.prevModel * vec4(aPosition, 1.0)).xyz;
    vsObjectId = o.id.x;
    gl_Position = vec4(vs.world, 1.0);
}
