// Where this pixel's surface was last frame, and how far it may be trusted (shared by reproject and temporal).
uniform sampler2DArray uDepth;      // Depth 1/2 (layer 0 used)
uniform sampler2D uLastDepthTex;    // Last Depth
#ifdef OBJECT_MOTION
uniform sampler2DArray uMotion;     // Motion (layer 0): previous - current world position of the pixel's surface
#endif
uniform float uFalloffStart;
uniform float uFalloffEnd;
uniform int uHistoryValid;  // 0 on the first frame and after a camera cut

// Returns the history weight in [0,1] and the previous-frame uv of the surface at screen pixel pix.
float reprojectionWeight(ivec2 pix, out vec2 prevUV) {
    prevUV = vec2(-1.0);
    if (uHistoryValid == 0) return 0.0;
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    if (isSky(d)) return 0.0;
    vec3 P = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
#ifdef OBJECT_MOTION
    P += texelFetch(uMotion, ivec3(pix, 0), 0).xyz;  // where this surface was last frame (moving objects)
#endif
    vec4 pc = uPrevViewProj * vec4(P, 1.0);
    if (pc.w <= 0.0) return 0.0;
    prevUV = pc.xy / pc.w * 0.5 + 0.5;
    if (any(lessThan(prevUV, vec2(0.0))) || any(greaterThan(prevUV, vec2(1.0)))) return 0.0;
    ivec2 size = textureSize(uLastDepthTex, 0);
    ivec2 ppix = min(ivec2(prevUV * vec2(size)), size - 1);
    float dPrev = texelFetch(uLastDepthTex, ppix, 0).r;
    if (isSky(dPrev)) return 0.0;
    vec3 Pprev = worldFromDepth(vec2(ppix) + 0.5, dPrev, uPrevInvViewProj);
    float dist = length(P - Pprev);
    float w = 1.0 - smoothstep(uFalloffStart, max(uFalloffEnd, uFalloffStart + 1e-6), dist);
    return isnan(w) ? 0.0 : w;
}
