#version 450 core
// Viewer/inspector display of one texture layer (and optionally a second one right of a split line).
// Output is display-encoded RGBA8. Standalone on purpose (no common.glsl): a broken pipeline include must not
// take the viewer's display down with it.
// Variants (renderer/passes/buffer_view_pass.cpp): SOURCE_A / SOURCE_B (0 a 2D texture, 1 an array, 2 an integer
// array) pick the one sampler each side reads and MODE_A / MODE_B (1 raw, 2 radiance, 3 depth, 4 normal, 5 object
// id) its mapping; HAS_B adds the split; CHANNEL (0 rgb, 1 r, 2 g, 3 b, 4 a, 5 luminance), USE_RANGE, HIGHLIGHT
// and GRID are the view's choices. llvmpipe runs every side of a uniform test, so a single shader fetched all six
// samplers and ran every mapping per pixel (the viewer's 896x688 frame: 12.1 ms, 1.x ms as variants).
#ifndef CHANNEL
#define CHANNEL 0
#endif
#ifndef SOURCE_A
#define SOURCE_A 0
#endif
#ifndef MODE_A
#define MODE_A 1
#endif
#ifndef SOURCE_B
#define SOURCE_B 0
#endif
#ifndef MODE_B
#define MODE_B 1
#endif
uniform sampler2D uTex2DA;
uniform sampler2DArray uTexArrA;
uniform sampler2D uTex2DB;
uniform sampler2DArray uTexArrB;
uniform usampler2DArray uTexArrUA;  // integer arrays (Object ID)
uniform usampler2DArray uTexArrUB;

uniform int uLayer[2];    // array layer (cube arrays: first face of the cube)
uniform int uFaces[2];    // 1, or 6 for a cube shown as 6 faces side by side
uniform int uLevel[2];
uniform ivec2 uSize[2];   // size of the shown level, one face

uniform float uExposure;  // linear scale
uniform vec2 uRange;
uniform vec2 uOrigin;     // texel coordinates of the output's bottom-left corner (source A)
uniform float uTexelsPerPixel;
uniform vec4 uBackground;
uniform vec2 uClip;       // near, far
uniform int uPersp;
uniform float uSplitX;    // output pixels, B at x >= this
uniform vec2 uCropA;      // A's guard band in texels on each side: B covers A's centre
layout(location = 0) out vec4 oColor;

vec3 decodeOct(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    float l = length(n);
    return l > 0.0 ? n / l : vec3(0.0, 0.0, 1.0);
}

float linearDepth(float d) {
    float n = uClip.x, f = uClip.y;
    if (uPersp != 0) return 2.0 * n * f / max(f + n - (d * 2.0 - 1.0) * (f - n), 1e-30);
    return n + d * (f - n);
}

vec3 toSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Texel t of source i's shown level (a cube array: 6 faces side by side).
ivec3 texelOf(int i, ivec2 t) {
    int face = t.x / uSize[i].x;
    return ivec3(t.x - face * uSize[i].x, t.y, uLayer[i] + face);
}

vec4 fetchA(ivec2 t) {
#if SOURCE_A == 2
    return vec4(float(texelFetch(uTexArrUA, ivec3(t, uLayer[0]), 0).r));
#elif SOURCE_A == 1
    return texelFetch(uTexArrA, texelOf(0, t), uLevel[0]);
#else
    return texelFetch(uTex2DA, t, uLevel[0]);
#endif
}

#ifdef HAS_B
vec4 fetchB(ivec2 t) {
#if SOURCE_B == 2
    return vec4(float(texelFetch(uTexArrUB, ivec3(t, uLayer[1]), 0).r));
#elif SOURCE_B == 1
    return texelFetch(uTexArrB, texelOf(1, t), uLevel[1]);
#else
    return texelFetch(uTex2DB, t, uLevel[1]);
#endif
}
#endif

void main() {
    vec2 frag = gl_FragCoord.xy;
    vec2 t = uOrigin + frag * uTexelsPerPixel;  // texel coordinates in A's level
#ifdef HAS_B
    int src = frag.x >= uSplitX ? 1 : 0;
    if (abs(frag.x - uSplitX) < 0.75) { oColor = vec4(1.0, 1.0, 1.0, 1.0); return; }
    if (src == 1) t = (t - uCropA) * vec2(uSize[1] * ivec2(uFaces[1], 1)) / (vec2(uSize[0] * ivec2(uFaces[0], 1)) - 2.0 * uCropA);
    int mode = src == 1 ? MODE_B : MODE_A;
#else
    const int src = 0;
    const int mode = MODE_A;
#endif
    ivec2 full = uSize[src] * ivec2(uFaces[src], 1);
    if (t.x < 0.0 || t.y < 0.0 || t.x >= float(full.x) || t.y >= float(full.y)) { oColor = uBackground; return; }

#ifdef HAS_B
    vec4 raw = src == 1 ? fetchB(ivec2(floor(t))) : fetchA(ivec2(floor(t)));
#else
    vec4 raw = fetchA(ivec2(floor(t)));
#endif
    vec4 v = raw;
    if (mode == 3) {
        float z = linearDepth(raw.r);
#ifdef USE_RANGE
        float lo = uRange.x, hi = uRange.y;
#else
        float lo = uClip.x, hi = uClip.y;
#endif
        float g = 1.0 - clamp((z - lo) / max(hi - lo, 1e-20), 0.0, 1.0);  // near = white, far = black
        v = vec4(vec3(g), 1.0);
    } else if (mode == 4) {
        v = vec4(decodeOct(raw.rg) * 0.5 + 0.5, 1.0);
    } else if (mode == 5) {
        uint id = uint(raw.r), h = id * 2654435761u;  // a stable colour per object, black for none
        v = id == 0u ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(vec3((h >> 8u) & 255u, (h >> 16u) & 255u, (h >> 24u) & 255u) / 255.0 * 0.8 + 0.2, 1.0);
    } else {
        if (mode == 2) v.rgb *= uExposure;
#ifdef USE_RANGE
        v = (v - uRange.x) / max(uRange.y - uRange.x, 1e-20);
#endif
    }

#if CHANNEL == 0
    vec3 c = v.rgb;
#elif CHANNEL == 5
    vec3 c = vec3(dot(v.rgb, vec3(0.2126, 0.7152, 0.0722)));
#else
    vec3 c = vec3(v[CHANNEL - 1]);
#endif
    c = (mode == 2) ? toSrgb(c) : clamp(c, 0.0, 1.0);

#ifdef HIGHLIGHT
    {
        bvec4 nan = isnan(raw), inf = isinf(raw);
        if (any(nan)) c = vec3(1.0, 0.0, 1.0);                                   // NaN: magenta
        else if (any(inf)) c = any(lessThan(raw, vec4(0.0))) ? vec3(0.0, 1.0, 1.0) : vec3(1.0, 1.0, 0.0);  // -Inf cyan, +Inf yellow
        else if (mode != 4 && any(lessThan(raw, vec4(0.0)))) c = mix(c, vec3(0.1, 0.3, 1.0), 0.75);  // negative: blue
    }
#endif

#ifdef GRID
    if (1.0 / uTexelsPerPixel >= 8.0) {  // output pixels per texel
        vec2 f = fract(t);
        if (any(lessThan(f, vec2(uTexelsPerPixel)))) c = mix(c, vec3(0.35), 0.6);
    }
#endif
    oColor = vec4(c, 1.0);
}
