#version 450 core
// What the radiosity gather does at each radiosity-grid pixel, decided before it runs: every pixel's receiver
// (Radiosity Geometry) and, with the interleaved gather (radiosity.interleave), whether the pixel gathers this frame
// or reuses last frame's filtered irradiance. A reusing pixel gets that irradiance and coverage 0 here; a gathering
// one gets 0, which the gather overwrites. The decision goes to Gather Mask as depth (0 = gather, 1 = not): the
// gather runs behind an early depth test, and llvmpipe skips the shader where the test fails for all of a batch's
// pixels (a reusing pixel in the gather itself ran its taps' first pass masked and its probe lookups in full).
#include "common.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
#ifdef DEEPGI_INTERLEAVE
uniform sampler2D uHistoryWeight;  // each pixel's reprojection weight (the reprojection pass)
uniform sampler2D uReprojected;
uniform int uInterleave;      // 2 or 4
uniform int uInterleaveSlot;  // this frame's blocks
#endif
layout(location = 0) out vec3 oIrradiance;
layout(location = 1) out float oCoverage;
layout(location = 2) out vec4 oGeometry;  // Radiosity Geometry: X, packNormalCode(its Normal texel); sky: w = -1
void main() {
    ivec2 g = ivec2(gl_FragCoord.xy);
    ivec2 pix = screenPixelOfRadiosity(g);
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    oIrradiance = vec3(0.0);
    oCoverage = 0.0;
    gl_FragDepth = 1.0;  // the sky: nothing to gather
    if (isSky(d)) { oGeometry = vec4(0.0, 0.0, 0.0, -1.0); return; }
    vec2 nCode = texelFetch(uNormal, ivec3(pix, 0), 0).rg;
    oGeometry = vec4(worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj), packNormalCode(nCode));
    gl_FragDepth = 0.0;
#ifdef DEEPGI_INTERLEAVE
    ivec2 block = g >> 2;  // llvmpipe shades 4x4 blocks: a block gathers whole or not at all
    int slot = uInterleave == 2 ? ((block.x + block.y) & 1) : ((block.x & 1) | ((block.y & 1) << 1));
    if (slot != uInterleaveSlot) {
        // A block where any history is rejected gathers anyway, so it gathers all its pixels: next to a disocclusion
        // a history that passes the test may still be another surface's (across an edge-on wall's zero thickness,
        // where the positions agree). The corners stand for the block.
        ivec2 b0 = block << 2, last = textureSize(uHistoryWeight, 0) - 1;
        float w = min(texelFetch(uHistoryWeight, g, 0).r,
                      min(min(texelFetch(uHistoryWeight, b0, 0).r, texelFetch(uHistoryWeight, min(b0 + ivec2(3, 0), last), 0).r),
                          min(texelFetch(uHistoryWeight, min(b0 + ivec2(0, 3), last), 0).r,
                              texelFetch(uHistoryWeight, min(b0 + ivec2(3, 3), last), 0).r)));
        if (w >= 0.999) {
            oIrradiance = texelFetch(uReprojected, g, 0).rgb;
            gl_FragDepth = 1.0;
        }
    }
#endif
}
