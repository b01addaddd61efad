#version 450 core
// One mip level of depth, normal and input radiance for one layer by rotated-grid point subsampling: every
// quantity of a coarse texel comes from the same real surface sample (no averaged phantom depths or normals).
#include "common.glsl"
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
uniform sampler2DArray uRadiance;
uniform int uLayer;
uniform int uSrcLevel;
#ifdef MIP_FROM_BASE  // level uLevel straight from level 0 (uSrcLevel 0): the texel the chain of levels would pick
uniform int uLevel;
#endif
layout(location = 0) out vec2 oNormal;
layout(location = 1) out vec3 oRadiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 srcSize = textureSize(uDepth, uSrcLevel).xy;
#ifdef MIP_FROM_BASE
    ivec2 q = sourcePixel(p, uLevel, srcSize);
#else
    ivec2 q = clamp(p * 2 + ivec2(p.y & 1, p.x & 1), ivec2(0), srcSize - 1);
#endif
    gl_FragDepth = texelFetch(uDepth, ivec3(q, uLayer), uSrcLevel).r;
    oNormal = texelFetch(uNormal, ivec3(q, uLayer), uSrcLevel).rg;
    oRadiance = texelFetch(uRadiance, ivec3(q, uLayer), uSrcLevel).rgb;  // where the level's radiance is not evaluated
}
