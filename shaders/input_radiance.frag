#version 450 core
// Outgoing Lambertian radiance of one deep G-buffer layer, the light the gather collects:
//   B = Le + albedo/pi * (E_direct + E_sky + (1 - damping) * w * E_indirect_last_frame)   (last term layer 1 only)
// E_sky: the environment's light with the probes' visibility (environment.glsl), with DEEPGI_SKY.
#include "common.glsl"
#include "brdf.glsl"
#include "lighting.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uAlbedo;
uniform sampler2DArray uNormal;
uniform sampler2DArray uEmission;
uniform sampler2D uReprojected;
uniform sampler2DArray uOcclusion;  // the occlusion texture (OCCLUSION)
uniform int uLayer;
uniform int uHasEmission;
uniform float uDamping;
uniform int uSourceLevel;   // this draw fills mip level uSourceLevel: each texel is its level-0 source sample's
uniform int uGBufferLevel;  // the G-buffer level this layer is read at: 0, or uSourceLevel where layer 2 was drawn there
#if defined(DEEPGI_PROBES) || defined(DEEPGI_SKY)
#include "probe_volume.glsl"
#endif
#ifdef DEEPGI_SKY
#include "environment.glsl"
#endif
layout(location = 0) out vec3 oRadiance;
void main() {
    ivec2 pix = sourcePixel(ivec2(gl_FragCoord.xy), uSourceLevel, textureSize(uDepth, 0).xy);
    ivec3 g = ivec3(uGBufferLevel == 0 ? pix : ivec2(gl_FragCoord.xy), uLayer);  // its G-buffer texel
    int gLevel = uGBufferLevel;
    float d = texelFetch(uDepth, g, gLevel).r;
    if (isSky(d)) { oRadiance = vec3(0.0); return; }
    vec3 P = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
    vec3 n = octDecode(texelFetch(uNormal, g, gLevel).rg);
    vec3 albedo = texelFetch(uAlbedo, g, gLevel).rgb;
    vec3 E = directIrradiance(P, n);  // Lambertian: the gather treats B as such (the composite adds the specular)
    // Layer 1 is seen by the camera: the probes' view bias moves it towards the camera (layer 2: along n only).
    vec3 probeView = uLayer == 0 ? viewDirection(P) : vec3(0.0);
#ifdef DEEPGI_SKY
    // The sky is direct light too (shown by the composite, bounced by the gather); an occlusion texture darkens it
    // as it does indirect light.
    vec3 Esky = probeSkyIrradiance(P, n, probeView);
#ifdef OCCLUSION
    Esky *= texelFetch(uOcclusion, g, gLevel).r;
#endif
    E += Esky;
#endif
    vec3 Eind = vec3(0.0);
#ifdef DEEPGI_HISTORY_FEEDBACK  // layer 1 with a history: last frame's indirect light (multi-bounce)
    Eind = (1.0 - uDamping) * texelFetch(uReprojected, radiosityPixelOfScreen(pix), 0).rgb;
#elif defined(DEEPGI_PROBES)
    // Layer 2 has no gathered light of its own, nor layer 1 before there is a history: the probes give theirs.
    Eind = (1.0 - uDamping) * probeIrradiance(P, n, probeView);
#endif
#ifdef OCCLUSION
    Eind *= texelFetch(uOcclusion, g, gLevel).r;  // occlusion textures darken indirect light only
#endif
    E += Eind;
    vec3 B = albedo / PI * E;
    if (uHasEmission != 0) B += texelFetch(uEmission, g, gLevel).rgb;
    // Layer 1's dither at its level-0 pixel at any level: its coarse texels are the bits a full-resolution draw wrote.
    oRadiance = sanitizeR11G11B10(B, uLayer == 0 ? vec2(pix) + 0.5 : gl_FragCoord.xy);
}
