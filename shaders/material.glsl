// Per-draw material (uniforms set by SceneGpu before each batch). A texture is read only in the variant that has it
// (BASE_TEX, EMISSIVE_TEX, METAL_ROUGH_TEX, NORMAL_TEX, OCCLUSION_TEX: SceneGpu::materialTextureDefines()); llvmpipe
// would sample it under any `if`.
uniform vec4 uBaseColor;     // linear rgba factor
uniform vec3 uEmissive;      // linear, strength included
uniform float uAlphaCutoff;
layout(binding = 0) uniform sampler2D uBaseTex;      // sRGB texture: decoded by the sampler
layout(binding = 1) uniform sampler2D uEmissiveTex;
// glTF metallic-roughness (renderer/scene/brdf.h): x metallic, y roughness, z dielectric F0, w 1 = any specular.
uniform vec4 uMetalRoughF0;
uniform vec2 uNormalScaleOcclusion;  // normal texture scale, occlusion strength
layout(binding = 2) uniform sampler2D uMetalRoughTex;  // linear: G roughness, B metallic
layout(binding = 3) uniform sampler2D uNormalTex;      // linear, tangent space
layout(binding = 4) uniform sampler2D uOcclusionTex;   // linear, R

vec4 baseColor(vec2 uv) {
    vec4 c = uBaseColor;
#ifdef BASE_TEX
    c *= texture(uBaseTex, uv);
#endif
    return c;
}
vec3 emission(vec2 uv) {
    vec3 e = uEmissive;
#ifdef EMISSIVE_TEX
    e *= texture(uEmissiveTex, uv).rgb;
#endif
    return e;
}

// (metallic, roughness) with the texture applied.
vec2 metallicRoughness(vec2 uv) {
    vec2 mr = uMetalRoughF0.xy;
#ifdef METAL_ROUGH_TEX
    mr *= texture(uMetalRoughTex, uv).bg;
#endif
    return clamp(mr, 0.0, 1.0);
}
float occlusion(vec2 uv) {
#ifdef OCCLUSION_TEX
    return 1.0 + uNormalScaleOcclusion.y * (texture(uOcclusionTex, uv).r - 1.0);
#else
    return 1.0;
#endif
}
// The shading normal: n (unit, facing the viewer) perturbed by the normal texture in the frame of tangent t
// (xyz, w = handedness: bitangent = cross(n, t) * w). The same as the path tracer's (renderer/scene/brdf.h).
vec3 mappedNormal(vec3 n, vec4 t, vec2 uv) {
#ifndef NORMAL_TEX
    return n;
#endif
    vec3 tn = texture(uNormalTex, uv).rgb * 2.0 - 1.0;
    tn.xy *= uNormalScaleOcclusion.x;
    vec3 T = t.xyz - n * dot(n, t.xyz);
    float len = length(T);
    if (!(len > 1e-12)) return n;
    T /= len;
    vec3 B = cross(n, T) * (t.w < 0.0 ? -1.0 : 1.0);
    vec3 m = T * tn.x + B * tn.y + n * tn.z;
    float ml = length(m);
    return ml > 1e-12 ? m / ml : n;
}
