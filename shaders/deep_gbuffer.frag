#version 450 core
// Writes albedo, oct16 normal (and emission, specular, occlusion where the scene has any) for both layers. A layer-2 fragment is
// discarded unless it lies at least min-separation behind layer 1: predicted from last frame's depth
// (reprojected with the previous camera), or exact from this frame's layer 1 when depth peeling.
#include "common.glsl"
#include "material.glsl"
in GS { vec3 world; vec3 normal; vec2 uv; } gs;
#ifdef NORMAL_MAPS
in vec4 gsTangent;
#endif
layout(location = 0) out vec3 oAlbedo;
layout(location = 1) out vec2 oNormal;
#ifdef EMISSION
layout(location = 2) out vec3 oEmission;
#endif
#ifdef OBJECT_IDS
flat in uint gsObjectId;   // node index + 1
layout(location = 5) out uint oObjectId;
#endif
#ifdef OBJECT_MOTION
in vec3 gsPrevWorld;       // this surface point last frame (its object's previous model matrix)
layout(location = 6) out vec4 oMotion;  // xyz: previous - current world position (the paper's per-object change)
#endif
#ifdef SPECULAR
layout(location = 3) out vec4 oSpecular;  // F0 rgb, perceptual roughness
#endif
#ifdef OCCLUSION
layout(location = 4) out float oOcclusion;
#endif
uniform int uDiffuseOnly;         // material.diffuse_only: albedo = base colour, no specular
uniform sampler2D uLastDepth;     // last frame's layer-1 depth (predicted mode)
uniform sampler2D uPeelDepth;     // this frame's layer-1 depth (depth-peel mode)
uniform float uMinSeparation;
uniform int uPeel;          // 1 = depth peeling
uniform int uDrawLevel;     // the level of the targets this draw fills: 0, or L when layer 2 is drawn at the tap level

// Albedo (the diffuse lobe: base x (1 - metallic)) and, where the scene needs them, the specular parameters and
// the occlusion texture's value.
void writeMaterial(vec3 base) {
    vec2 mr = metallicRoughness(gs.uv);
    bool diffuseOnly = uDiffuseOnly != 0 || uMetalRoughF0.w == 0.0;
    oAlbedo = uDiffuseOnly != 0 ? base : base * (1.0 - mr.x);
#ifdef SPECULAR
    oSpecular = diffuseOnly ? vec4(0.0) : vec4(mix(vec3(uMetalRoughF0.z), base, mr.x), mr.y);
#endif
#ifdef OCCLUSION
    oOcclusion = clamp(occlusion(gs.uv), 0.0, 1.0);
#endif
}

// LAYER2_PREPASS: layer 2's depth only (the tests that discard, no outputs); LAYER2_SHADE: layer 2's outputs for the
// fragment that won the prepass (depth test EQUAL, no discard, so llvmpipe tests depth before shading).
void main() {
    vec4 base = baseColor(gs.uv);
#if defined(MASKED) && !defined(LAYER2_SHADE)
    if (base.a < uAlphaCutoff) discard;
#endif
#if !defined(LAYER1_ONLY) && !defined(LAYER2_SHADE)
    if (gl_Layer == 1) {
        if (uPeel != 0) {
            ivec2 pix = ivec2(gl_FragCoord.xy);  // the level-0 pixel whose ray this fragment samples
            if (uDrawLevel > 0) pix = (pix << uDrawLevel) + ivec2(uTapSample.yz);
            float d0 = texelFetch(uPeelDepth, pix, 0).r;
            if (!isSky(d0) && eyeDepthCurrent(gl_FragCoord.z) < eyeDepthCurrent(d0) + uMinSeparation) discard;
        } else {
            // Where this point was last frame (its own motion, not only the camera's).
#ifdef OBJECT_MOTION
            vec3 prevWorld = gsPrevWorld;
#else
            vec3 prevWorld = gs.world;
#endif
            vec4 pc = uPrevViewProj * vec4(prevWorld, 1.0);
            if (pc.w > 0.0 || uPrevCameraPos.w < 0.5) {
                vec2 uv = clamp(pc.xy / pc.w * 0.5 + 0.5, vec2(0.0), vec2(1.0));
                ivec2 size = textureSize(uLastDepth, 0);
                float dLast = texelFetch(uLastDepth, min(ivec2(uv * vec2(size)), size - 1), 0).r;
                float zPrev = dot(prevWorld - uPrevCameraPos.xyz, uPrevCameraForward.xyz);
                if (!isSky(dLast) && zPrev < eyeDepthPrevious(dLast) + uMinSeparation) discard;
            }
        }
    }
#endif
#ifdef LAYER2_PREPASS
    return;
#endif
    vec3 n = gs.normal;
    float len = length(n);
    n = (len > 1e-20 && !isnan(len)) ? n / len : normalize(cross(dFdx(gs.world), dFdy(gs.world)));
    if (!gl_FrontFacing) n = -n;  // only double-sided materials reach here with back faces
    if (any(isnan(n))) n = vec3(0.0, 1.0, 0.0);
#ifdef NORMAL_MAPS
    n = mappedNormal(n, gl_FrontFacing ? gsTangent : -gsTangent, gs.uv);
#endif
    oNormal = octEncode(n);
#ifdef OBJECT_IDS
    oObjectId = gsObjectId;
#endif
#ifdef OBJECT_MOTION
    vec3 motion = gsPrevWorld - gs.world;
    oMotion = vec4(any(isnan(motion)) || any(isinf(motion)) ? vec3(0.0) : motion, 0.0);
#endif
    writeMaterial(clamp(base.rgb, 0.0, 1.0));
#ifdef EMISSION
    oEmission = sanitizeR11G11B10(emission(gs.uv), gl_FragCoord.xy);
#endif
}
