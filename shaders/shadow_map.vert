#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aUV;
uniform mat4 uLightViewProj;
out vec3 vWorld;
out vec2 vUV;
void main() {
    vWorld = aPosition;
    vUV = aUV;
    gl_Position = uLightViewProj * vec4(aPosition, 1.0);
}
