#version 450 core
// Final image. physical: L = Le + albedo/pi * (E_direct + E_indirect), indirect counted once.
// seed: L = E_input1 + E_output * albedo (the seed's formula, kept to measure its error).
// Layer 1's direct light is evaluated here, where the image needs it (lighting.glsl).
#include "common.glsl"
#include "lighting.glsl"
#ifdef DEEPGI_SKY
#include "probe_volume.glsl"
#endif
#include "environment.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uAlbedo;
uniform sampler2DArray uNormal;
uniform sampler2DArray uEmission;
uniform sampler2DArray uRadiance;   // Input Radiance 1/2
uniform sampler2D uIndirect;        // Output Radiance
uniform sampler2D uGeometry;        // Radiosity Geometry (a coarser radiosity grid only): the grid's positions, normals
#ifdef SPECULAR
uniform sampler2DArray uSpecular;   // F0 rgb, roughness: layer 1's direct specular
#endif
#ifdef OCCLUSION
uniform sampler2DArray uOcclusion;  // the material's occlusion texture: darkens indirect light (and the sky's) only
#endif
uniform int uHasEmission;
#include "display.glsl"
layout(location = 0) out vec4 oRadiance;  // linear, unexposed
layout(location = 1) out vec4 oDisplay;   // sRGB-encoded, exposed
layout(location = 2) out vec4 oDirect;    // Direct Radiance: layer 1's outgoing direct radiance, for the inspector


// Indirect irradiance at screen pixel pix (surface P, normal n) from the radiosity grid: its own texel at full
// resolution; on a coarser grid the bilinear neighbours, each weighted by how well its surface matches this one
// (distance from this pixel's tangent plane, normal agreement: a joint bilateral upsample), or the best-matching
// neighbour alone where none matches (a silhouette against a different surface). Which of the two is a define, not
// a test of uRadiosityGrid.x: llvmpipe runs both sides of an if (the unused fetch: composite 0.95 x in passtime).
vec3 indirectAt(ivec2 pix, vec3 P, vec3 n) {
#ifdef DEEPGI_RADIOSITY_FULL
    return texelFetch(uIndirect, pix, 0).rgb;
#else
    int d = int(uRadiosityGrid.x);
    ivec2 grid = ivec2(uRadiosityGrid.yz);
    vec2 f = (vec2(pix) + 0.5) / float(d) - 0.5;
    ivec2 b = ivec2(floor(f));
    vec2 t = f - vec2(b);
    float z = max(dot(P - uCameraPos.xyz, uCameraForward.xyz), 1e-30);
    vec3 sum = vec3(0.0), best = vec3(0.0);
    float total = 0.0, bestErr = 1e30;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = clamp(b + o, ivec2(0), grid - 1);
        vec4 g = texelFetch(uGeometry, q, 0);
        if (g.w < 0.0) continue;  // sky
        vec3 Ps = g.xyz;
        vec3 ns = unpackNormalCode(g.w);
        float plane = abs(dot(Ps - P, n)) / (0.005 * z);  // off this pixel's plane, in units of 0.5 % of its depth
        float facing = max(dot(n, ns), 0.0);
        float err = plane + (1.0 - facing) * 20.0;
        float wb = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
        float facing4 = facing * facing;
        float w = wb * facing4 * facing4 / (1.0 + plane * plane);
        vec3 E = texelFetch(uIndirect, q, 0).rgb;
        sum += w * E;
        total += w;
        if (err < bestErr) { bestErr = err; best = E; }
    }
    return total > 1e-3 ? sum / total : best;
#endif
}

// Layer 1's outgoing direct radiance at pixel pix (surface P, unit n): albedo/pi x the shadowed irradiance of every
// light and of the sky, plus the GGX specular towards the camera. The one evaluation of it at full resolution (the
// input radiance pass evaluates it again only at the level-L samples the gather reads, before the gather).
vec3 directRadiance(ivec2 pix, vec3 P, vec3 n, vec3 albedo) {
    vec3 Ls = vec3(0.0);
#ifdef SPECULAR
    vec3 E = directIrradianceAndSpecular(P, n, viewDirection(P), texelFetch(uSpecular, ivec3(pix, 0), 0), Ls);
#else
    vec3 E = directIrradiance(P, n);
#endif
#ifdef DEEPGI_SKY  // the sky is direct light too; an occlusion texture darkens it as it does indirect light
    vec3 Esky = probeSkyIrradiance(P, n, viewDirection(P));
#ifdef OCCLUSION
    Esky *= texelFetch(uOcclusion, ivec3(pix, 0), 0).r;
#endif
    E += Esky;
#endif
    return sanitize(albedo / PI * E + Ls);  // radiance: below the clamp wherever the final image is
}

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    vec3 L;
    oDirect = vec4(0.0);
#ifndef DEEPGI_SURFACE_PIXELS  // defined where the sky's pixels have a draw of their own (composite_sky.frag)
    if (isSky(d)) {
        L = uBackground.rgb + environmentBackdrop(gl_FragCoord.xy);  // the environment is seen, and lights (input radiance)
    } else
#endif
    {
        vec3 albedo = texelFetch(uAlbedo, ivec3(pix, 0), 0).rgb;
        vec3 P = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
        vec3 n = octDecode(texelFetch(uNormal, ivec3(pix, 0), 0).rg);
#ifdef DEEPGI_NO_INDIRECT  // radiosity.enabled=false: no Output Radiance
        vec3 E = vec3(0.0);
#else
        vec3 E = indirectAt(pix, P, n);
#endif
#ifdef OCCLUSION
        E *= texelFetch(uOcclusion, ivec3(pix, 0), 0).r;
#endif
        oDirect = vec4(directRadiance(pix, P, n, albedo), 1.0);
#ifdef DEEPGI_SEED_COMPOSITE
        L = texelFetch(uRadiance, ivec3(pix, 0), 0).rgb + E * albedo;
#else
        L = oDirect.rgb + albedo / PI * E;
        if (uHasEmission != 0) L += texelFetch(uEmission, ivec3(pix, 0), 0).rgb;
#endif
    }
    L = sanitize(L);
    oRadiance = vec4(L, 1.0);
    oDisplay = vec4(displayColor(L));
}
