#version 450 core
// One direction of the separable bilateral blur (G3D's reconstruction filter, technique.md 1.9): Gaussian taps
// weighted by normal and plane-distance agreement with the centre, optionally monotonically decreasing, read off a
// weighted line fit so that a gradient cut by an edge keeps its value.
#include "common.glsl"
uniform sampler2D uGeometry;  // Radiosity Geometry: each grid pixel's world position and normal, from the gather
uniform sampler2D uSource;
uniform ivec2 uAxis;
const int MAX_BLUR_RADIUS = 6;  // taps of the radiosity grid on each side (blurTaps of blur.radius; kMaxBlurTaps)
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
    // A weighted line fit along the axis (offset t in taps), read at the centre: where both sides count it is the
    // weighted mean; where an edge or the screen border cuts one side off, the fitted slope keeps a linear gradient's
    // value (a one-sided mean took the brighter interior's light into every concave corner: one bounce 10-100 % too
    // bright in bands along the sun patch room's edges) while the taps still average the noise.
    float s0 = uKernel[0], s1 = 0.0, s2 = 0.0;
    vec3 sv = centre * uKernel[0], stv = vec3(0.0), lo = centre, hi = centre;
    for (int side = -1; side <= 1; side += 2) {
        float lastB = 1.0;
        for (int r = 1; r <= MAX_BLUR_RADIUS; ++r) {
            if (r > uRadius) break;
            ivec2 tp = pix + uAxis * (side * r * uStep);
            if (any(lessThan(tp, ivec2(0))) || any(greaterThanEqual(tp, size))) break;
            float b = bilateral(C, nC, tp);
            if (uMonotonic != 0) {
                b = min(b, lastB);
                lastB = b;
                // No tap beyond counts on this side: llvmpipe leaves the loop once every pixel of a batch is here.
                if (b == 0.0) break;
            }
            float w = (0.3 + uKernel[r]) * b, t = float(side * r);
            vec3 v = texelFetch(uSource, tp, 0).rgb;
            s0 += w;
            s1 += w * t;
            s2 += w * t * t;
            sv += w * v;
            stv += (w * t) * v;
            if (w > 0.0) {
                lo = min(lo, v);
                hi = max(hi, v);
            }
        }
    }
    // s0 >= kernel[0] > 0: the centre always counts; det = 0 when no tap but the centre's does.
    float det = s0 * s2 - s1 * s1;
    vec3 slope = det > 1e-6 * s0 * s2 ? (s0 * stv - s1 * sv) / det : vec3(0.0);
    // Within the values it was fitted to (the centre's among them, so a line keeps its value): noise read off a
    // one-sided fit's end must not overshoot them (a dark speck where a moved camera's new pixels meet reused ones).
    vec3 value = clamp((sv - slope * s1) / s0, lo, hi);
    oValue = sanitizeR11G11B10(value, gl_FragCoord.xy);
}
