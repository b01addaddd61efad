#version 450 core
// Screen-space radiosity gather over both deep G-buffer layers (Mara et al. 2016, technique.md 1.6):
// spiral taps, world radius projected to pixels, per-tap mip level, normal tests, the brighter valid layer per
// tap, and E = 2*pi / M_used * sum(B * cos).
#include "common.glsl"
layout(binding = 4) uniform sampler2DArray uDepth;
layout(binding = 8) uniform sampler2DArray uNormal;
layout(binding = 11) uniform sampler2DArray uRadiance;
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
        vec3 E[2], B[2];
        float w[2];
        for (int j = 0; j < 2; ++j) {
            E[j] = B[j] = vec3(0.0);
            w[j] = 0.0;
            if (j == 1 && uUseLayer2 == 0) break;
            float dj = texelFetch(uDepth, ivec3(T, j), m).r;
            if (isSky(dj)) continue;
            vec3 Yj = worldFromDepth(vec2(Y) + 0.5, dj, uInvViewProj);
            vec3 v = Yj - X;
            float vv = dot(v, v);
            if (vv <= 1e-12) continue;
            vec3 wh = v * inversesqrt(vv);
            float cosX = dot(wh, nX);
            bool ok = cosX > 0.0;
            if (ok && uTapNormalTest != 0) ok = dot(-wh, octDecode(texelFetch(uNormal, ivec3(T, j), m).rg)) > 0.01;
            if (ok && vv < r2) {
                B[j] = texelFetch(uRadiance, ivec3(T, j), m).rgb;
                E[j] = B[j] * cosX;
            }
            w[j] = ok ? 1.0 : 0.0;  // a valid tap beyond the radius counts as used but dark (as in G3D)
        }
        float a0 = w[0] * dot(E[0], E[0]) + w[0];
        float a1 = w[1] * dot(E[1], E[1]) + w[1];
        int pick = a0 > a1 ? 0 : 1;
        sum += E[pick];
        brightest = max(brightest, B[pick]);
        used += w[pick];
    }
    // Irradiance from surroundings no brighter than `brightest` is at most pi * brightest. The 2pi/M_used
    // estimator can exceed that where the accepted taps are steep (a few percent to +55%); with full multi-bounce
    // feedback that is a loop gain rho * k above 1 and the radiance runs away to the format maximum. Bounded
    // this way, the feedback is a contraction for albedo < 1 (tests/test_hard_stability.cpp, LongRun...).
    oIrradiance = sanitizeR11G11B10(min(2.0 * PI * sum / (used + 1e-5), PI * brightest), gl_FragCoord.xy);
}
