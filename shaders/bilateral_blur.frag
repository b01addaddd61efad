#version 450 core
// One direction of the separable bilateral blur (G3D's reconstruction filter, technique.md 1.9): Gaussian taps
// weighted by normal and plane-distance agreement with the centre, optionally monotonically decreasing.
#include "common.glsl"
uniform sampler2D uGeometry;  // Radiosity Geometry: each grid pixel's world position and normal, from the gather
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

// Weight of grid pixel tp against the centre (position C, normal nC): 0 for sky, else normal x plane agreement.
float bilateral(vec3 C, vec3 nC, ivec2 tp) {
    vec4 g = texelFetch(uGeometry, tp, 0);
    if (g.w < 0.0) return 0.0;  // sky
    vec3 T = g.xyz;
    vec3 nT = unpackNormalCode(g.w);
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
    vec4 g = texelFetch(uGeometry, pix, 0);
    vec3 centre = texelFetch(uSource, pix, 0).rgb;
    if (g.w < 0.0) { oValue = centre; return; }  // sky
    vec3 C = g.xyz;
    vec3 nC = unpackNormalCode(g.w);
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
