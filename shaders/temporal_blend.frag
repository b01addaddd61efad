#version 450 core
// E = w * E_reprojected + (1 - w) * E_current with w = alpha * (1 - smoothstep(start, end, world distance)).
#include "common.glsl"
uniform sampler2D uHistoryWeight;  // the reprojection pass's rejection weight
uniform sampler2D uCurrent;
uniform sampler2D uReprojected;
uniform float uAlpha;
layout(location = 0) out vec3 oValue;
void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);  // radiosity grid
    float w = uAlpha * texelFetch(uHistoryWeight, pix, 0).r;
    vec3 cur = texelFetch(uCurrent, pix, 0).rgb;
    vec3 prev = texelFetch(uReprojected, pix, 0).rgb;
    oValue = sanitizeR11G11B10(mix(cur, prev, w), gl_FragCoord.xy);
}
