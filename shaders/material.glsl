// Per-draw material (uniforms set by SceneGpu before each batch).
uniform vec4 uBaseColor;     // linear rgba factor
uniform vec3 uEmissive;      // linear, strength included
uniform int uHasBaseTex;
uniform int uHasEmissiveTex;
uniform float uAlphaCutoff;
layout(binding = 0) uniform sampler2D uBaseTex;      // sRGB texture: decoded by the sampler
layout(binding = 1) uniform sampler2D uEmissiveTex;

vec4 baseColor(vec2 uv) {
    vec4 c = uBaseColor;
    if (uHasBaseTex != 0) c *= texture(uBaseTex, uv);
    return c;
}
vec3 emission(vec2 uv) {
    vec3 e = uEmissive;
    if (uHasEmissiveTex != 0) e *= texture(uEmissiveTex, uv).rgb;
    return e;
}
