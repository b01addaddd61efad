#version 450 core
// Writes albedo, oct16 normal (and emission where the scene has any) for both layers. A layer-2 fragment is
// discarded unless it lies at least min-separation behind layer 1: predicted from last frame's depth
// (reprojected with the previous camera), or exact from this frame's layer 1 when depth peeling.
#include "common.glsl"
#include "material.glsl"
in GS { vec3 world; vec3 normal; vec2 uv; } gs;
layout(location = 0) out vec3 oAlbedo;
layout(location = 1) out vec2 oNormal;
#ifdef EMISSION
layout(location = 2) out vec3 oEmission;
#endif
in vec3 gsPrevWorld;       // this surface point last frame (its object's previous model matrix)
flat in uint gsObjectId;   // node index + 1
layout(location = 5) out uint oObjectId;
layout(location = 6) out vec4 oMotion;  // xyz: previous - current world position (the paper's per-object change)
uniform sampler2D uLastDepth;     // last frame's layer-1 depth (predicted mode)
uniform sampler2D uPeelDepth;     // this frame's layer-1 depth (depth-peel mode)
uniform float uMinSeparation;
uniform int uPeel;          // 1 = depth peeling

void main() {
    vec4 base = baseColor(gs.uv);
#ifdef MASKED
    if (base.a < uAlphaCutoff) discard;
#endif
    if (gl_Layer == 1) {
        if (uPeel != 0) {
            float d0 = texelFetch(uPeelDepth, ivec2(gl_FragCoord.xy), 0).r;
            if (!isSky(d0) && eyeDepthCurrent(gl_FragCoord.z) < eyeDepthCurrent(d0) + uMinSeparation) discard;
        } else {
            // Where this point was last frame (its own motion, not only the camera's).
            vec4 pc = uPrevViewProj * vec4(gsPrevWorld, 1.0);
            if (pc.w > 0.0 || uPrevCameraPos.w < 0.5) {
                vec2 uv = clamp(pc.xy / pc.w * 0.5 + 0.5, vec2(0.0), vec2(1.0));
                ivec2 size = textureSize(uLastDepth, 0);
                float dLast = texelFetch(uLastDepth, min(ivec2(uv * vec2(size)), size - 1), 0).r;
                float zPrev = dot(gsPrevWorld - uPrevCameraPos.xyz, uPrevCameraForward.xyz);
                if (!isSky(dLast) && zPrev < eyeDepthPrevious(dLast) + uMinSeparation) discard;
            }
        }
    }
    vec3 n = gs.normal;
    float len = length(n);
    n = (len > 1e-20 && !isnan(len)) ? n / len : normalize(cross(dFdx(gs.world), dFdy(gs.world)));
    if (!gl_FrontFacing) n = -n;  // only double-sided materials reach here with back faces
    if (any(isnan(n))) n = vec3(0.0, 1.0, 0.0);
    oAlbedo = clamp(base.rgb, 0.0, 1.0);
    oNormal = octEncode(n);
    oObjectId = gsObjectId;
    vec3 motion = gsPrevWorld - gs.world;
    oMotion = vec4(any(isnan(motion)) || any(isinf(motion)) ? vec3(0.0) : motion, 0.0);
#ifdef EMISSION
    oEmission = sanitizeR11G11B10(emission(gs.uv), gl_FragCoord.xy);
#endif
}
