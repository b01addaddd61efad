// Direct light from the punctual lights with shadow maps. Mirrors renderer/scene/lighting.cpp. Includes brdf.glsl (ggxSpecular).
#include "brdf.glsl"
struct GpuLight {
    vec4 radiance;      // rgb = colour * intensity; w = type (0 directional, 1 point, 2 spot)
    vec4 position;      // xyz; w = range (0 = infinite)
    vec4 direction;     // xyz = direction light travels; w = cos(outer cone)
    vec4 params;        // x = cos(inner cone), y = shadow layer (-1 none), z = shadow texel size at distance 1 (or world), w = shadow far (point)
    mat4 shadowMatrix;  // world -> shadow clip (directional, spot)
};
layout(std430, binding = 1) readonly buffer Lights { GpuLight uLights[]; };
const int MAX_LIGHTS = 16384;  // kMaxGpuLights (renderer/scene/lighting.h); the renderer refuses more
// The first lights again, as a uniform block over the same buffer (kBlockLights): llvmpipe loads a storage buffer
// per lane and a uniform block once per batch; with the sun alone the storage-buffer loop was 2/3 of the pass.
const int MAX_BLOCK_LIGHTS = 32;
layout(std140, binding = 3) uniform LightBlock { GpuLight uLightBlock[MAX_BLOCK_LIGHTS]; };
GpuLight lightAt(int i) {
#ifdef DEEPGI_BLOCK_LIGHTS_ONLY  // every light is in the block: llvmpipe would still load the storage buffer per lane
    return uLightBlock[i];
#else
    if (i < MAX_BLOCK_LIGHTS) return uLightBlock[i];
    return uLights[i];
#endif
}
#ifndef DEEPGI_LIGHT_COUNT
uniform int uLightCount;
#endif
uniform float uShadowBias;  // in shadow-map texels
uniform sampler2DArrayShadow uShadowMaps;
uniform samplerCubeArrayShadow uShadowCubes;

float rangeWindow(float dist, float range) {
    if (range <= 0.0) return 1.0;
    float r = dist / range;
    float w = clamp(1.0 - r * r * r * r, 0.0, 1.0);
    return w * w;
}

// type: L's type (0 directional, 1 point, 2 spot), a constant where DEEPGI_LIGHT_TYPES gives it.
float shadowFactor(GpuLight L, int type, vec3 P, vec3 n, vec3 toLight, float dist) {
    int layer = int(L.params.y);
    if (layer < 0) return 1.0;
    // Normal offset grows with the texel footprint (constant for the sun, with distance for spot/point).
    float texel = type == 0 ? L.params.z : L.params.z * dist;
    float cosT = clamp(dot(n, toLight), 0.0, 1.0);
    // P was rebuilt from a depth buffer: its error along the view axis is about dd * z^2 / near with dd = 2^-23 in
    // perspective (depth precision near 1), dd * (far - near) in orthographic. Offset along the normal by it as well
    // as by the texel: without it a near plane of 1e-4 gives shadow acne (18% image error), with more it moves edges.
    float z = max(dot(P - uCameraPos.xyz, uCameraForward.xyz), 0.0);
    float posErr = 1.2e-7 * (uCameraPos.w > 0.5 ? z * z / max(uClip.x, 1e-30) : (uClip.y - uClip.x));
    float offset = uShadowBias * texel * (1.0 + 2.0 * sqrt(1.0 - cosT * cosT)) + posErr;
    vec3 Pb = P + n * offset + toLight * (0.5 * texel);
    if (type == 1) {
        vec3 d = Pb - L.position.xyz;
        return texture(uShadowCubes, vec4(d, float(layer)), length(d) / L.params.w);
    }
    vec4 c = L.shadowMatrix * vec4(Pb, 1.0);
    if (c.w <= 0.0) return 1.0;
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0))) || s.z >= 1.0) return 1.0;
    return texture(uShadowMaps, vec4(s.xy, float(layer), s.z));
}

// The light's radiance reaching P (colour x intensity x distance/range/cone attenuation) and the unit direction
// to it.
vec3 lightArrival(GpuLight L, int type, vec3 P, out vec3 toLight, out float dist) {
    if (type == 0) {
        toLight = -L.direction.xyz;
        dist = 1e30;
        return L.radiance.rgb;
    }
    vec3 d = L.position.xyz - P;
    float d2 = dot(d, d);
    dist = sqrt(d2);
    toLight = dist > 0.0 ? d / dist : vec3(0.0, 1.0, 0.0);
    float atten = rangeWindow(dist, L.position.w) / max(d2, 1e-20);  // guards only 0 (scale-free; see lighting.cpp)
    if (type == 2) {
        float cd = dot(L.direction.xyz, -toLight);
        float t = clamp((cd - L.direction.w) / max(L.params.x - L.direction.w, 1e-4), 0.0, 1.0);
        atten *= t * t;
    }
    return L.radiance.rgb * atten;
}

// Adds light L's shadowed irradiance on the surface at P with unit normal n to E.
void addLightIrradiance(GpuLight L, int type, vec3 P, vec3 n, inout vec3 E) {
    vec3 toLight;
    float dist;
    vec3 radiance = lightArrival(L, type, P, toLight, dist);
    float cosT = dot(n, toLight);
    if (cosT <= 0.0 || all(lessThanEqual(radiance, vec3(0.0)))) return;
    E += radiance * cosT * shadowFactor(L, type, P, n, toLight, dist);
}

// ---- With the GGX specular lobe (glTF metallic-roughness; brdf.glsl) ----
// Adds light L's shadowed irradiance on the surface (P, unit n) to E and, where specular, its GGX radiance towards
// v to Ls.
void addLightWithSpecular(GpuLight L, int type, vec3 P, vec3 n, vec3 v, vec4 spec, bool specular, inout vec3 E,
                          inout vec3 Ls) {
    vec3 toLight;
    float dist;
    vec3 radiance = lightArrival(L, type, P, toLight, dist);
    float cosT = dot(n, toLight);
    if (cosT <= 0.0 || all(lessThanEqual(radiance, vec3(0.0)))) return;
    vec3 Ei = radiance * cosT * shadowFactor(L, type, P, n, toLight, dist);
    E += Ei;
    if (specular) Ls += ggxSpecular(n, v, toLight, spec.rgb, spec.a) * Ei;
}

// DEEPGI_LIGHT_COUNT (kUnrolledLights or fewer lights, all in the block): the light loop has a compile-time length,
// so the compiler unrolls it and every light is read at a constant index. llvmpipe loads a block member at a
// variable index once per lane: with the sun alone the uniform-count loop cost a fifth of the composite.
const int MAX_UNROLLED_LIGHTS = 4;  // kUnrolledLights (test_shader_loops checks)
#ifdef DEEPGI_LIGHT_COUNT
// Each unrolled light's type as a constant (DEEPGI_LIGHT_TYPES, padded to MAX_UNROLLED_LIGHTS), or read per light.
#ifdef DEEPGI_LIGHT_TYPES
const int kLightTypes[MAX_UNROLLED_LIGHTS] = int[MAX_UNROLLED_LIGHTS](DEEPGI_LIGHT_TYPES);
#define DEEPGI_UNROLLED_TYPE(i) kLightTypes[i]
#else
#define DEEPGI_UNROLLED_TYPE(i) int(uLightBlock[i].radiance.w)
#endif
#endif

// Shadowed irradiance on the surface at P with unit normal n.
vec3 directIrradiance(vec3 P, vec3 n) {
    vec3 E = vec3(0.0);
#ifdef DEEPGI_LIGHT_COUNT
    for (int i = 0; i < MAX_UNROLLED_LIGHTS; ++i) {
        if (i >= DEEPGI_LIGHT_COUNT) break;
        addLightIrradiance(uLightBlock[i], DEEPGI_UNROLLED_TYPE(i), P, n, E);
    }
#else
    for (int i = 0; i < MAX_LIGHTS; ++i) {
        if (i >= uLightCount) break;
        GpuLight L = lightAt(i);
        addLightIrradiance(L, int(L.radiance.w), P, n, E);
    }
#endif
    return E;
}

// Shadowed irradiance E on the surface (P, unit n) and, in Ls, the specular radiance towards v (unit, to the
// viewer) of F0 = spec.rgb, roughness spec.a: sum over lights of F D V * radiance * cos, one shadow lookup each.
vec3 directIrradianceAndSpecular(vec3 P, vec3 n, vec3 v, vec4 spec, out vec3 Ls) {
    vec3 E = vec3(0.0);
    Ls = vec3(0.0);
    bool specular = any(greaterThan(spec.rgb, vec3(0.0)));
#ifdef DEEPGI_LIGHT_COUNT
    for (int i = 0; i < MAX_UNROLLED_LIGHTS; ++i) {
        if (i >= DEEPGI_LIGHT_COUNT) break;
        addLightWithSpecular(uLightBlock[i], DEEPGI_UNROLLED_TYPE(i), P, n, v, spec, specular, E, Ls);
    }
#else
    for (int i = 0; i < MAX_LIGHTS; ++i) {
        if (i >= uLightCount) break;
        GpuLight L = lightAt(i);
        addLightWithSpecular(L, int(L.radiance.w), P, n, v, spec, specular, E, Ls);
    }
#endif
    return E;
}
