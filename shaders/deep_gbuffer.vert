#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUV;
layout(location = 3) in vec4 aTangent;  // xyz, w = handedness (Vertex::tangent)
out VS { vec3 world; vec3 normal; vec2 uv; vec4 tangent; } vs;
void main() {
    vs.world = aPosition;
    vs.normal = aNormal;
    vs.uv = aUV;
    vs.tangent = aTangent;
    gl_Position = vec4(aPosition, 1.0);
}
