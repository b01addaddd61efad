#version 450 core
// Screen-space radiosity gather over both deep G-buffer layers (Mara et al. 2016, technique.md 1.6):
// spiral taps, world radius projected to pixels, per-tap mip level, normal tests, the brighter valid layer per
// tap, and E = 2*pi / M_used * sum(B * cos).
#include "common.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
uniform sampler2DArray uRadiance;
uniform int uNumSamples;
uniform float uSpiralTurns;
uniform float uRadius;
uniform int uMinMip;
uniform int uMaxMip;
uniform int uLogMaxOffset;
uniform int uTapNormalTest;
uniform int uUseLayer2;
uniform float uTime;  // varies the pattern per frame when temporally varying taps
layout(location = 0) out vec3 oIrradiance;

// One layer's contribution of a tap: its radiance B and E = B * cos (both zero beyond the radius), and whether
// the tap counts (w).
// h0 = the tap pixel's homogeneous world position without the depth term; adding (2d - 1) * hz gives depth d
// (worldFromDepth with the matrix product distributed, shared by the two layers). (2d - 1) is formed first:
// folding -hz into h0 cancels catastrophically when near/far are extreme (hz huge).
void tapLayer(int j, ivec2 T, int m, vec4 h0, vec4 hz, vec3 X, vec3 nX, float r2, out vec3 B, out vec3 E, out float w) {
    B = vec3(0.0);
    E = vec3(0.0);
    w = 0.0;
    float dj = texelFetch(uDepth, ivec3(T, j), m).r;
    if (isSky(dj)) return;
    vec4 hw = h0 + (dj * 2.0 - 1.0) * hz;
    vec3 v = hw.xyz / hw.w - X;
    float vv = dot(v, v);
    if (vv <= 1e-12) return;
    vec3 wh = v * inversesqrt(vv);
    float cosX = dot(wh, nX);
    bool ok = cosX > 0.0;
    if (ok && uTapNormalTest != 0) ok = dot(-wh, octDecode(texelFetch(uNormal, ivec3(T, j), m).rg)) > 0.01;
    if (ok && vv < r2) {
        B = texelFetch(uRadiance, ivec3(T, j), m).rgb;
        E = B * cosX;
    }
    w = ok ? 1.0 : 0.0;  // a valid tap beyond the radius counts as used but dark (as in G3D)
}

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    if (isSky(d)) { oIrradiance = vec3(0.0); return; }
    vec3 X = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
    vec3 nX = octDecode(texelFetch(uNormal, ivec3(pix, 0), 0).rg);
    float z = eyeDepthCurrent(d);
    float rss = uCameraPos.w > 0.5 ? uClip.z * uRadius / max(z, 1e-6) : uClip.z * uRadius;
    // Per-pixel rotation and radial jitter (G3D's hash), optionally varied per frame.
    float phi = float((3 * pix.x) ^ (pix.y + pix.x * pix.y)) * 10.0 + uTime;
    float jitter = fract(sin(gl_FragCoord.x * 100.0 + gl_FragCoord.y + uTime) * 1e5 + sin(gl_FragCoord.y * 1000.0) * 1000.0) * 0.8 + 0.1;
    ivec2 size = ivec2(uViewport.xy);
    float r2 = uRadius * uRadius;
    // worldFromDepth(p, d) = (c + p.x * cx + p.y * cy + (2d - 1) * hz).xyz / w.
    vec4 cx = uInvViewProj[0] * (2.0 * uViewport.z), cy = uInvViewProj[1] * (2.0 * uViewport.w), hz = uInvViewProj[2];
    vec4 c = uInvViewProj[3] - uInvViewProj[0] - uInvViewProj[1];
    bool twoLayers = uUseLayer2 != 0;
    vec3 sum = vec3(0.0);
    vec3 brightest = vec3(0.0);  // per channel, the largest radiance among the taps that contribute
    float used = 0.0;
    for (int i = 0; i < uNumSamples; ++i) {
        float alpha = (float(i) + jitter) / float(uNumSamples);
        float theta = alpha * uSpiralTurns * 6.28 + phi;
        float h = alpha * rss;
        ivec2 Y = pix + ivec2(h * vec2(cos(theta), sin(theta)));
        if (any(lessThan(Y, ivec2(0))) || any(greaterThanEqual(Y, size))) continue;  // off-screen: no data
        int m = clamp(findMSB(int(h)) - uLogMaxOffset, uMinMip, uMaxMip);
        ivec2 T = Y >> m;
        // xy at full resolution, z from the coarse level, as G3D does. Placing the tap at its sample's source pixel
        // instead (sourcePixel(), as the AO pass must) changed the indirect error by < 0.001 (docs/BENCHMARKS.md).
        vec2 P = vec2(Y) + 0.5;
        vec4 h0 = c + P.x * cx + P.y * cy;
        vec3 B0, E0, B1 = vec3(0.0), E1 = vec3(0.0);
        float w0, w1 = 0.0;
        tapLayer(0, T, m, h0, hz, X, nX, r2, B0, E0, w0);
#ifndef DEEPGI_SINGLE_LAYER  // defined when layer 2 is off: no layer-2 code at all
        if (twoLayers) tapLayer(1, T, m, h0, hz, X, nX, r2, B1, E1, w1);
#endif
        float a0 = w0 * dot(E0, E0) + w0;
        float a1 = w1 * dot(E1, E1) + w1;
        bool pick0 = a0 > a1;
        sum += pick0 ? E0 : E1;
        brightest = max(brightest, pick0 ? B0 : B1);
        used += pick0 ? w0 : w1;
    }
    // Irradiance from surroundings no brighter than `brightest` is at most pi * brightest. The 2pi/M_used
    // estimator can exceed that where the accepted taps are steep (a few percent to +55%); with full multi-bounce
    // feedback that is a loop gain rho * k above 1 and the radiance runs away to the format maximum. Bounded
    // this way, the feedback is a contraction for albedo < 1 (tests/test_hard_stability.cpp, LongRun...).
    oIrradiance = sanitizeR11G11B10(min(2.0 * PI * sum / (used + 1e-5), PI * brightest), gl_FragCoord.xy);
}
