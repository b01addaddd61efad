#version 450 core
// Viewer/inspector display of one texture layer (and optionally a second one right of a split line).
// Output is display-encoded RGBA8. Standalone on purpose (no common.glsl): a broken pipeline include must not
// take the viewer's display down with it.
uniform sampler2D uTex2DA;
uniform sampler2DArray uTexArrA;
uniform sampler2D uTex2DB;
uniform sampler2DArray uTexArrB;
uniform usampler2DArray uTexArrUA;  // integer arrays (Object ID)
uniform usampler2DArray uTexArrUB;

uniform int uHasB;
uniform int uIsArray[2];
uniform int uLayer[2];    // array layer (cube arrays: first face of the cube)
uniform int uFaces[2];    // 1, or 6 for a cube shown as 6 faces side by side
uniform int uLevel[2];
uniform ivec2 uSize[2];   // size of the shown level, one face
uniform int uMode[2];     // resolved mode: 1 raw, 2 radiance, 3 depth, 4 normal, 5 object id (integer array)

uniform int uChannel;     // 0 rgb, 1 r, 2 g, 3 b, 4 a, 5 luminance
uniform float uExposure;  // linear scale
uniform vec2 uRange;
uniform int uUseRange;
uniform int uHighlight;
uniform vec2 uOrigin;     // texel coordinates of the output's bottom-left corner (source A)
uniform float uTexelsPerPixel;
uniform int uGrid;
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

vec4 fetch(int i, ivec2 t) {
    int face = t.x / uSize[i].x;
    ivec2 p = ivec2(t.x - face * uSize[i].x, t.y);
    if (uMode[i] == 5) return vec4(float(i == 0 ? texelFetch(uTexArrUA, ivec3(p, uLayer[0]), 0).r
                                                : texelFetch(uTexArrUB, ivec3(p, uLayer[1]), 0).r));
    if (i == 0) {
        if (uIsArray[0] != 0) return texelFetch(uTexArrA, ivec3(p, uLayer[0] + face), uLevel[0]);
        return texelFetch(uTex2DA, p, uLevel[0]);
    }
    if (uIsArray[1] != 0) return texelFetch(uTexArrB, ivec3(p, uLayer[1] + face), uLevel[1]);
    return texelFetch(uTex2DB, p, uLevel[1]);
}

void main() {
    vec2 frag = gl_FragCoord.xy;
    int src = (uHasB != 0 && frag.x >= uSplitX) ? 1 : 0;
    if (uHasB != 0 && abs(frag.x - uSplitX) < 0.75) { oColor = vec4(1.0, 1.0, 1.0, 1.0); return; }

    vec2 t = uOrigin + frag * uTexelsPerPixel;  // texel coordinates in A's level
    if (src == 1) t = (t - uCropA) * vec2(uSize[1] * ivec2(uFaces[1], 1)) / (vec2(uSize[0] * ivec2(uFaces[0], 1)) - 2.0 * uCropA);
    ivec2 full = uSize[src] * ivec2(uFaces[src], 1);
    if (t.x < 0.0 || t.y < 0.0 || t.x >= float(full.x) || t.y >= float(full.y)) { oColor = uBackground; return; }

    vec4 raw = fetch(src, ivec2(floor(t)));
    vec4 v = raw;
    int mode = uMode[src];
    if (mode == 3) {
        float z = linearDepth(raw.r);
        float lo = uUseRange != 0 ? uRange.x : uClip.x, hi = uUseRange != 0 ? uRange.y : uClip.y;
        float g = 1.0 - clamp((z - lo) / max(hi - lo, 1e-20), 0.0, 1.0);  // near = white, far = black
        v = vec4(vec3(g), 1.0);
    } else if (mode == 4) {
        v = vec4(decodeOct(raw.rg) * 0.5 + 0.5, 1.0);
    } else if (mode == 5) {
        uint id = uint(raw.r), h = id * 2654435761u;  // a stable colour per object, black for none
        v = id == 0u ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(vec3((h >> 8u) & 255u, (h >> 16u) & 255u, (h >> 24u) & 255u) / 255.0 * 0.8 + 0.2, 1.0);
    } else {
        if (mode == 2) v.rgb *= uExposure;
        if (uUseRange != 0) v = (v - uRange.x) / max(uRange.y - uRange.x, 1e-20);
    }

    vec3 c;
    if (uChannel == 0) c = v.rgb;
    else if (uChannel == 5) c = vec3(dot(v.rgb, vec3(0.2126, 0.7152, 0.0722)));
    else c = vec3(v[uChannel - 1]);
    c = (mode == 2) ? toSrgb(c) : clamp(c, 0.0, 1.0);

    if (uHighlight != 0) {
        bvec4 nan = isnan(raw), inf = isinf(raw);
        if (any(nan)) c = vec3(1.0, 0.0, 1.0);                                   // NaN: magenta
        else if (any(inf)) c = any(lessThan(raw, vec4(0.0))) ? vec3(0.0, 1.0, 1.0) : vec3(1.0, 1.0, 0.0);  // -Inf cyan, +Inf yellow
        else if (mode != 4 && any(lessThan(raw, vec4(0.0)))) c = mix(c, vec3(0.1, 0.3, 1.0), 0.75);  // negative: blue
    }

    float ppt = 1.0 / uTexelsPerPixel;  // output pixels per texel
    if (uGrid != 0 && ppt >= 8.0) {
        vec2 f = fract(t);
        if (any(lessThan(f, vec2(uTexelsPerPixel)))) c = mix(c, vec3(0.35), 0.6);
    }
    oColor = vec4(c, 1.0);
}
