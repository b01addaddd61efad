#version 450 core
// Depth-only; MASKED variant alpha-tests; CUBE variant stores distance to the light / far (point lights).
#include "material.glsl"
in vec3 vWorld;
in vec2 vUV;
uniform vec3 uLightPos;
uniform float uShadowFar;
void main() {
#ifdef MASKED
    if (baseColor(vUV).a < uAlphaCutoff) discard;
#endif
#ifdef CUBE
    gl_FragDepth = clamp(length(vWorld - uLightPos) / uShadowFar, 0.0, 1.0);
#endif
}
