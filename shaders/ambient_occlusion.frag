#version 450 core
// Two-layer ambient occlusion (technique.md 1.10): the AlchemyAO estimator with the radiosity gather's spiral
// taps, tap count, projected radius and per-tap mip level, taking the max over the two layers per tap (a coarse
// tap is reconstructed at the pixel its point-sampled depth came from, else a grazing plane occludes itself):
//   AO = max(0, 1 - sqrt(intensity * pi/N * sum_i max(0, A_i1, A_i2)))
//   A  = max(0, 1 - v.v/r^2) * max(0, (v.n - bias) / sqrt(v.v + eps)),  v = Y - X (camera space)
#include "common.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
uniform int uNumSamples;
uniform float uSpiralTurns;
uniform float uRadius;
uniform int uMinMip;
uniform int uMaxMip;
uniform int uLogMaxOffset;
uniform int uUseLayer2;
uniform float uTime;
uniform float uBias;
uniform float uIntensity;
layout(location = 0) out float oAO;

// Camera-space position from a pixel position (centre = +0.5) and a depth-buffer value: one divide for z.
vec3 viewFromDepth(vec2 pixel, float d) {
    vec2 ndc = pixel * uViewport.zw * 2.0 - 1.0;
    float z = eyeDepthCurrent(d);
    if (uCameraPos.w > 0.5) return vec3(z * (ndc + vec2(uProj[2][0], uProj[2][1])) / vec2(uProj[0][0], uProj[1][1]), -z);
    return vec3((ndc - vec2(uProj[3][0], uProj[3][1])) / vec2(uProj[0][0], uProj[1][1]), -z);
}

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    if (isSky(d)) { oAO = 1.0; return; }
    vec3 X = viewFromDepth(vec2(pix) + 0.5, d);
    vec3 nX = normalize(mat3(uView) * octDecode(texelFetch(uNormal, ivec3(pix, 0), 0).rg));
    float z = -X.z;
    float rss = uCameraPos.w > 0.5 ? uClip.z * uRadius / max(z, 1e-6) : uClip.z * uRadius;
    // The gather's per-pixel rotation and jitter, so both passes see the same taps.
    float phi, jitter;
    spiralPixel(pix, gl_FragCoord.xy, uTime, phi, jitter);
    ivec2 size = ivec2(uViewport.xy);
    float r2 = uRadius * uRadius;
    float eps = 1e-4 * r2;
    float sum = 0.0;
    for (int i = 0; i < MAX_SPIRAL_TAPS; ++i) {
        if (i >= uNumSamples) break;
        float h;
        vec2 dir = spiralTap(i, uNumSamples, uSpiralTurns, phi, jitter, rss, h);
        ivec2 Y = pix + ivec2(h * dir);
        if (any(lessThan(Y, ivec2(0))) || any(greaterThanEqual(Y, size))) continue;  // off-screen: unoccluded
        int m = clamp(findMSB(int(h)) - uLogMaxOffset, uMinMip, uMaxMip);
        ivec2 T = Y >> m;
        vec2 P = vec2(sourcePixel(T, m, size)) + 0.5;
        float best = 0.0;
        for (int j = 0; j < 2; ++j) {
            if (j == 1 && uUseLayer2 == 0) break;
            float dj = texelFetch(uDepth, ivec3(T, j), m).r;
            if (isSky(dj)) continue;
            vec3 v = viewFromDepth(P, dj) - X;
            float vv = dot(v, v);
            float a = max(0.0, 1.0 - vv / r2) * max(0.0, (dot(v, nX) - uBias) * inversesqrt(vv + eps));
            best = max(best, a);
        }
        sum += best;
    }
    oAO = max(0.0, 1.0 - sqrt(uIntensity * PI / float(uNumSamples) * sum));
}
