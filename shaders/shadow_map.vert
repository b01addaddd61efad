#version 450 core
#include "scene_objects.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aUV;
uniform mat4 uLightViewProj;
out vec3 vWorld;
out vec2 vUV;
void main() {
    vWorld = (uObjects[aObject].model * vec4(aPosition, 1.0)).xyz;
    vUV = aUV;
    gl_Position = uLightViewProj * vec4(vWorld, 1.0);
}
