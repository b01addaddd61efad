#version 450 core
// Final image. physical: L = Le + albedo/pi * (E_direct + E_indirect), indirect counted once.
// seed: L = E_input1 + E_output * albedo (the seed's formula, kept to measure its error).
#include "common.glsl"
#include "lighting.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uAlbedo;
uniform sampler2DArray uNormal;
uniform sampler2DArray uEmission;
uniform sampler2DArray uRadiance;   // Input Radiance 1/2
uniform sampler2D uIndirect;        // Output Radiance
uniform int uHasEmission;
uniform int uIndirectOn;
uniform int uSeedMode;
uniform float uExposure;   // linear scale 2^EV
uniform int uTonemap;      // 0 clamp, 1 ACES fit
layout(location = 0) out vec4 oRadiance;  // linear, unexposed
layout(location = 1) out vec4 oDisplay;   // sRGB-encoded, exposed

vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 toSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    vec3 L;
    if (isSky(d)) {
        L = uBackground.rgb;
    } else {
        vec3 albedo = texelFetch(uAlbedo, ivec3(pix, 0), 0).rgb;
        vec3 E = uIndirectOn != 0 ? texelFetch(uIndirect, pix, 0).rgb : vec3(0.0);
        if (uSeedMode != 0) {
            L = texelFetch(uRadiance, ivec3(pix, 0), 0).rgb + E * albedo;
        } else {
            vec3 P = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
            vec3 n = octDecode(texelFetch(uNormal, ivec3(pix, 0), 0).rg);
            L = albedo / PI * (directIrradiance(P, n) + E);
            if (uHasEmission != 0) L += texelFetch(uEmission, ivec3(pix, 0), 0).rgb;
        }
    }
    L = sanitize(L);
    oRadiance = vec4(L, 1.0);
    vec3 x = L * uExposure;
    oDisplay = vec4(toSrgb(uTonemap == 1 ? aces(x) : x), 1.0);
}
