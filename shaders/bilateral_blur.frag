#version 450 core
// One direction of the separable bilateral blur (G3D's reconstruction filter, technique.md 1.9): Gaussian taps
// weighted by normal and plane-distance agreement with the centre, optionally monotonically decreasing.
#include "common.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
uniform sampler2D uSource;
uniform ivec2 uAxis;
const int MAX_BLUR_RADIUS = 6;  // blur.radius
uniform int uRadius;     // 1..MAX_BLUR_RADIUS
uniform int uStep;
uniform float uEdgeSharpness;
uniform int uMonotonic;
uniform float uKernel[MAX_BLUR_RADIUS + 1];
uniform float uPlaneEpsilon2;  // squared distance under which a tap is trusted without the plane test
layout(location = 0) out vec3 oValue;

// World position of the surface a radiosity-grid pixel stands for.
vec3 position(ivec2 p, out bool sky) {
    ivec2 s = screenPixelOfRadiosity(p);
    float d = texelFetch(uDepth, ivec3(s, 0), 0).r;
    sky = isSky(d);
    return worldFromDepth(vec2(s) + 0.5, d, uInvViewProj);
}
vec3 normalAt(ivec2 p) { return octDecode(texelFetch(uNormal, ivec3(screenPixelOfRadiosity(p), 0), 0).rg); }

float bilateral(vec3 C, vec3 nC, ivec2 tp) {
    bool sky;
    vec3 T = position(tp, sky);
    if (sky) return 0.0;
    vec3 nT = normalAt(tp);
    float normalW = max(0.0, 1.0 - uEdgeSharpness * 40.0 * (1.0 - dot(nC, nT)));
    vec3 dq = C - T;
    float dd = dot(dq, dq);
    float planeW = 1.0;
    if (dd >= uPlaneEpsilon2) {
        float planeErr = max(abs(dot(dq, nT)), abs(dot(dq, nC)));
        planeW = max(0.0, 1.0 - 2.0 * uEdgeSharpness * 0.5 * planeErr / sqrt(dd));
        planeW *= planeW;
    }
    return normalW * planeW;
}

void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    bool sky;
    vec3 C = position(pix, sky);
    vec3 centre = texelFetch(uSource, pix, 0).rgb;
    if (sky) { oValue = centre; return; }
    vec3 nC = normalAt(pix);
    ivec2 size = ivec2(uRadiosityGrid.yz);
    vec3 sum = centre * uKernel[0];
    float total = uKernel[0];
    for (int side = -1; side <= 1; side += 2) {
        float lastB = 1.0;
        for (int r = 1; r <= MAX_BLUR_RADIUS; ++r) {
            if (r > uRadius) break;
            ivec2 tp = pix + uAxis * (side * r * uStep);
            if (any(lessThan(tp, ivec2(0))) || any(greaterThanEqual(tp, size))) break;
            float b = bilateral(C, nC, tp);
            if (uMonotonic != 0) { b = min(b, lastB); lastB = b; }
            float w = (0.3 + uKernel[r]) * b;
            sum += texelFetch(uSource, tp, 0).rgb * w;
            total += w;
        }
    }
    oValue = sanitizeR11G11B10(sum / total, gl_FragCoord.xy);  // total >= kernel[0] > 0: the centre always counts
}
