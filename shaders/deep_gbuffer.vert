#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
out VS { vec3 world; vec3 normal; vec2 uv; } vs;
void main() {
    vs.world = aPosition;
    vs.normal = aNormal;
    vs.uv = aUV;
    gl_Position = vec4(aPosition, 1.0);
}
